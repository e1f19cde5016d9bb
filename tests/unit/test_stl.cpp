// SPDX-License-Identifier: MIT
// The STL reader (io/stl.hpp): ASCII and binary files of one box give the
// same welded mesh, whatever the header says; the placement is scale, then
// rotation, then offset; and bad files are refused with the file, the line
// or triangle, and the reason, exactly as written here. The files are
// written by the tests; tests/data/stl holds one file as an exporter wrote
// it (upper-case keywords, CRLF line ends).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/config.hpp"
#include "io/stl.hpp"
#include "test_support.hpp"
#include "tumble/core/constants.hpp"
#include "tumble/walls/mesh.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;
using Triangle = std::array<Vec3, 3>;

// The box [0, 1] x [0, 2] x [0, 3], two triangles per side, N outwards.
std::vector<Triangle> box_triangles() {
    auto corner = [](int v) { return Vec3{double(v & 1), 2.0 * ((v >> 1) & 1), 3.0 * ((v >> 2) & 1)}; };
    const std::array<std::array<int, 4>, 6> sides{
        {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}}};
    std::vector<Triangle> out;
    for (const auto& q : sides) {
        out.push_back({corner(q[0]), corner(q[1]), corner(q[2])});
        out.push_back({corner(q[0]), corner(q[2]), corner(q[3])});
    }
    return out;
}

std::string ascii_stl(const std::vector<Triangle>& triangles) {
    std::string text = "solid box\n";
    char line[128];
    for (const Triangle& t : triangles) {
        text += "  facet normal 0 0 0\n    outer loop\n";
        for (const Vec3& v : t) {
            std::snprintf(line, sizeof line, "      vertex %.17g %.17g %.17g\n", v.x, v.y, v.z);
            text += line;
        }
        text += "    endloop\n  endfacet\n";
    }
    return text + "endsolid box\n";
}

void put_float(std::string& out, float x) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &x, 4);
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((bits >> (8 * i)) & 0xff));
}

std::string binary_stl(const std::vector<Triangle>& triangles, const std::string& header = "tumble test") {
    std::string out = header;
    out.resize(80, ' ');
    const auto n = static_cast<std::uint32_t>(triangles.size());
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((n >> (8 * i)) & 0xff));
    for (const Triangle& t : triangles) {
        for (int k = 0; k < 3; ++k) put_float(out, 0.0f);
        for (const Vec3& v : t)
            for (int a = 0; a < 3; ++a) put_float(out, static_cast<float>(v[a]));
        out += std::string(2, '\0');
    }
    return out;
}

class Stl : public test_support::ScratchTest {
protected:
    fs::path file(const std::string& name, const std::string& bytes) {
        std::ofstream(dir_ / name, std::ios::binary) << bytes;
        return dir_ / name;
    }
    // The message of the refusal of `path`, or "accepted".
    static std::string refusal(const fs::path& path, const io::StlPlacement& placement = {}) {
        try {
            io::read_stl(path, placement);
        } catch (const io::ConfigError& e) {
            return e.what();
        }
        return "accepted";
    }
};

void expect_box(const TriangleMesh& mesh) {
    const std::vector<Triangle> box = box_triangles();
    ASSERT_EQ(mesh.triangles.size(), 12u);
    EXPECT_EQ(mesh.vertices.size(), 8u);  // welded
    for (std::size_t t = 0; t < 12; ++t)
        for (int j = 0; j < 3; ++j) EXPECT_EQ(mesh.vertices[mesh.triangles[t][j]], box[t][j]);
    const MeshTopology topology(mesh);
    EXPECT_EQ(topology.edge_count(), 18u);
    // Outward normals from the corner order: the side x = 1 (triangles 10, 11) has N = +x.
    EXPECT_EQ(topology.face(10).normal, (Vec3{1.0, 0.0, 0.0}));
}

TEST_F(Stl, AsciiAndBinaryGiveTheSameWeldedMesh) {
    const TriangleMesh ascii = io::read_stl(file("box.stl", ascii_stl(box_triangles())));
    expect_box(ascii);
    const TriangleMesh binary = io::read_stl(file("box_binary.stl", binary_stl(box_triangles())));
    expect_box(binary);
    EXPECT_EQ(binary.vertices, ascii.vertices);
    EXPECT_EQ(binary.triangles, ascii.triangles);
}

TEST_F(Stl, BinaryFileWhoseHeaderBeginsWithSolidIsBinary) {
    expect_box(io::read_stl(file("solid_header.stl", binary_stl(box_triangles(), "solid box exported by CAD"))));
    // Even with a line break in the header: the word after it is no "facet".
    expect_box(io::read_stl(file("solid_line.stl", binary_stl(box_triangles(), "solid box\nexported"))));
}

TEST_F(Stl, ExportersFileWithUpperCaseAndCrlfIsRead) {
    const fs::path path = fs::path(TUMBLE_SOURCE_DIR) / "tests" / "data" / "stl" / "tetrahedron_crlf.stl";
    const MeshTopology tetrahedron(io::read_stl(path));
    EXPECT_EQ(tetrahedron.face_count(), 4u);
    EXPECT_EQ(tetrahedron.vertex_count(), 4u);
    EXPECT_EQ(tetrahedron.edge_count(), 6u);  // closed: every edge has two faces
    for (std::uint32_t e = 0; e < 6; ++e) EXPECT_EQ(tetrahedron.edge_sides(e).size(), 2u);
}

TEST_F(Stl, SeveralSolidsInOneFileAreOneMesh) {
    std::vector<Triangle> box = box_triangles();
    const std::vector<Triangle> first(box.begin(), box.begin() + 6), second(box.begin() + 6, box.end());
    expect_box(io::read_stl(file("two.stl", ascii_stl(first) + ascii_stl(second))));
}

TEST_F(Stl, PlacementScalesThenTurnsThenMoves) {
    // Corner (1, 0, 0) of the box: x 1e-3 -> (1e-3, 0, 0); a quarter turn about
    // +z -> (0, 1e-3, 0); + (1, 2, 3) -> (1, 2.001, 3).
    io::StlPlacement placement;
    placement.scale = 1e-3;
    placement.rotation = io::StlRotation{{0.0, 0.0, 5.0}, pi / 2.0};
    placement.offset = {1.0, 2.0, 3.0};
    const TriangleMesh mesh = io::read_stl(file("box.stl", ascii_stl(box_triangles())), placement);
    const Vec3 moved = mesh.vertices[mesh.triangles[1][2]];  // the file's (1, 0, 0)
    // Round-off of cos(pi/2) = 6e-17 and of the sums: 1e-15.
    EXPECT_NEAR(moved.x, 1.0, 1e-15);
    EXPECT_NEAR(moved.y, 2.001, 1e-15);
    EXPECT_NEAR(moved.z, 3.0, 1e-15);
    // The file's (0, 0, 3) goes to (0, 0, 3e-3) + offset: the offset is
    // neither scaled nor turned.
    const Vec3 top = mesh.vertices[mesh.triangles[5][2]];
    EXPECT_NEAR(top.x, 1.0, 1e-15);
    EXPECT_NEAR(top.y, 2.0, 1e-15);
    EXPECT_NEAR(top.z, 3.003, 1e-15);
}

TEST_F(Stl, BadFilesAreRefusedNamingFileWhereAndWhy) {
    const std::vector<Triangle> box = box_triangles();
    const std::string name = (dir_ / "x.stl").string();

    EXPECT_EQ(refusal(dir_ / "missing.stl"), (dir_ / "missing.stl").string() + ": no such file");

    std::string truncated = binary_stl({box[0], box[1], box[2]});
    truncated.resize(84 + 50 * 2 + 10);
    EXPECT_EQ(refusal(file("x.stl", truncated)),
              name + ": triangle 3: truncated: the file ends after 194 bytes, the 3 triangles its header announces "
                     "need 84 + 50 x 3 = 234");

    EXPECT_EQ(refusal(file("x.stl", binary_stl({box[0], box[1], box[2]}) + "extra!")),
              name + ": the header announces 3 triangles, 84 + 50 x 3 = 234 bytes, but the file has 240 bytes (not a "
                     "binary STL, or a wrong count)");

    EXPECT_EQ(refusal(file("x.stl", "nothing")),
              name + ": 7 bytes: too short for a binary STL (84 bytes of header and count), and no ASCII STL (that "
                     "begins with \"solid\")");

    std::vector<Triangle> with_nan = {box[0], box[1]};
    with_nan[1][2].y = NAN;
    EXPECT_EQ(refusal(file("x.stl", binary_stl(with_nan))),
              name + ": triangle 2: corner 3: y is not a finite number (nan)");

    // ASCII: line 1 solid; 2-8 the first facet (its corners on 4-6); 9-15 the second.
    std::string text = ascii_stl({box[0], box[1]});
    text.replace(text.find("vertex 0 2 0"), 6, "vertx");
    EXPECT_EQ(refusal(file("x.stl", text)), name + ": line 5: expected \"vertex\", found \"vertx\"");

    text = ascii_stl({box[0], box[1]});
    text.replace(text.rfind("vertex 1 0 0") + 7, 1, "inf");
    EXPECT_EQ(refusal(file("x.stl", text)), name + ": line 13: triangle 2, corner 3: x is not a finite number");

    text = ascii_stl({box[0]});
    text.replace(text.find("vertex 0 2 0") + 9, 1, "2.0.0");
    EXPECT_EQ(refusal(file("x.stl", text)),
              name + ": line 5: expected a number (y of corner 2), found \"2.0.0\"");

    text = ascii_stl({box[0]});
    EXPECT_EQ(refusal(file("x.stl", text.substr(0, text.find("endloop")))),
              name + ": line 6: expected \"endloop\", found the end of the file");
    EXPECT_EQ(refusal(file("x.stl", text + "solid\nfacet normal 0 0 0\nouter loop\nbogus")),
              name + ": line 13: expected \"vertex\", found \"bogus\"");

    EXPECT_EQ(refusal(file("x.stl", "solid empty\nendsolid empty\n")), name + ": no triangles");
    EXPECT_EQ(refusal(file("x.stl", binary_stl({}))), name + ": no triangles");

    // Triangle 2 collinear; the ASCII message adds its line.
    const Triangle line{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{2, 0, 0}};
    EXPECT_EQ(refusal(file("x.stl", ascii_stl({box[0], line}))),
              name + ": triangle 2 (line 9): degenerate: its area, 0 m^2, is not above 1e-12 times its longest edge "
                     "squared, 4 m^2 (corners (0, 0, 0), (1, 0, 0), (2, 0, 0))");
    EXPECT_EQ(refusal(file("x.stl", binary_stl({box[0], box[1], {box[0][1], box[0][2], box[0][0]}}))),
              name + ": triangle 3: repeats triangle 1 (the same three vertices): its forces would count twice");

    // The placement is checked before the file is read (it need not exist).
    io::StlPlacement bad;
    bad.scale = 0.0;
    EXPECT_EQ(refusal(dir_ / "missing.stl", bad),
              (dir_ / "missing.stl").string() + ": scale: must be a positive number, got 0");
    bad.scale = 1.0;
    bad.rotation = io::StlRotation{{0.0, 0.0, 0.0}, 1.0};
    EXPECT_EQ(refusal(dir_ / "missing.stl", bad),
              (dir_ / "missing.stl").string() + ": rotation: the axis must be a finite vector of length > 0");
}

}  // namespace
}  // namespace tumble
