// SPDX-License-Identifier: MIT
// VTK snapshots read back by a real reader: the files are written, then
// loaded by VTK's own XML readers in python3 (Debian package python3-vtk9,
// installed by scripts/install-deps.sh), which print what they read; the
// numbers are compared here with the simulation's. Also the contact
// network's normal force against a hand computation and against the force
// loop's own records.
#include <gtest/gtest.h>

#include "test_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/vtk_input.hpp"
#include "io/vtk_output.hpp"
#include "tumble/core/error.hpp"
#include "tumble/setup/paper_materials.hpp"
#include "tumble/sim/contact_network.hpp"
#include "tumble/sim/simulation.hpp"

namespace fs = std::filesystem;
using tumble::Vec3;

namespace {

constexpr double R = 3.6e-3;  // m, the paper's material 1

tumble::ParticleSpec sphere(Vec3 x, Vec3 v, Vec3 w, int tag = 0) {
    tumble::ParticleSpec p;
    p.position = x;
    p.velocity = v;
    p.angular_velocity = w;
    p.radius = R;
    p.material = 0;
    p.tag = tag;
    return p;
}

// Six spheres of material 1 in open space, no gravity: a chain 0-1-2 with
// small overlaps and approach velocities (so Kuwabara-Kono counts), 3 alone,
// 4 kinematic (turning about z) touching 0, and 5 touching 3 along a slant.
tumble::Scenario small_scenario(bool viscous) {
    tumble::Scenario s;
    s.materials = tumble::paper::materials();
    s.pair_properties = tumble::paper::pair_properties();
    s.model.viscous = viscous;
    s.domain.lo = {-0.1, -0.1, -0.1};
    s.domain.hi = {0.1, 0.1, 0.1};
    const double gap = 2.0 * R * (1.0 - 0.004);  // overlap 0.8 % of the diameter
    s.particles.push_back(sphere({0.0, 0.0, 0.0}, {0.01, 0.002, 0.0}, {1.0, -2.0, 0.5}, 1));
    s.particles.push_back(sphere({gap, 0.0, 0.0}, {-0.02, 0.0, 0.001}, {0.0, 3.0, 0.0}));
    s.particles.push_back(sphere({2.0 * gap, 0.0001, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, -4.0}, 2));
    s.particles.push_back(sphere({0.05, 0.05, 0.05}, {0.0, 0.0, -0.01}, {}));
    tumble::ParticleSpec wall = sphere({0.0, -gap, 0.0}, {}, {});
    wall.material = 2;
    wall.radius = R;
    wall.motion = 0;
    s.particles.push_back(wall);
    const Vec3 slant = (gap / std::sqrt(3.0)) * Vec3{1.0, 1.0, 1.0};
    s.particles.push_back(sphere(Vec3{0.05, 0.05, 0.05} + slant, {-0.003, 0.0, 0.0}, {0.2, 0.0, 0.0}, 7));
    tumble::RigidMotion turning;
    turning.axis_point = {0.0, -0.05, 0.0};
    turning.angular_velocity = 0.3;
    s.motions.push_back(turning);
    return s;
}

std::size_t index_of(const tumble::ParticleStore& p, std::int64_t id) {
    for (std::size_t k = 0; k < p.size(); ++k)
        if (p.id[k] == id) return k;
    throw std::logic_error("no particle with that id");
}

// ---- Reading back through VTK --------------------------------------------

// A python3 that has VTK: Debian's python3-vtk9 installs it for
// /usr/bin/python3, which need not be the python3 first on PATH.
std::string python_with_vtk() {
    for (const char* candidate : {"/usr/bin/python3", "python3"}) {
        const std::string probe = std::string(candidate) + " -c \"import vtkmodules.vtkIOXML\" >/dev/null 2>&1";
        if (std::system(probe.c_str()) == 0) return candidate;
    }
    return {};
}

// Loads each file named on the command line with VTK's XML reader for its
// kind (.vtu, .vtp, or .pvd: ParaView's own vtkPVDReader is not part of VTK,
// so the collection is parsed as XML and every dataset in it loaded) and
// prints "tag field value ..." lines. Floats are printed with repr(), the
// shortest form that reads back to the same double.
const char* reader_script = R"PY(
import os, sys
import xml.etree.ElementTree as ET
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader, vtkXMLPolyDataReader

messages = vtkStringOutputWindow()
vtkOutputWindow.SetInstance(messages)

def values(array):
    return [repr(array.GetComponent(t, c)) for t in range(array.GetNumberOfTuples())
            for c in range(array.GetNumberOfComponents())]

def load(path):
    reader = vtkXMLUnstructuredGridReader() if path.endswith(".vtu") else vtkXMLPolyDataReader()
    if not reader.CanReadFile(path):
        print("error", "cannot read", path)
        sys.exit(0)
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()

def dump(tag, data):
    print(tag, "points", *values(data.GetPoints().GetData()) if data.GetNumberOfPoints() else [])
    print(tag, "cell_types", *[data.GetCellType(c) for c in range(data.GetNumberOfCells())])
    print(tag, "cell_sizes", *[data.GetCell(c).GetNumberOfPoints() for c in range(data.GetNumberOfCells())])
    for kind, arrays in (("point", data.GetPointData()), ("cell", data.GetCellData()), ("field", data.GetFieldData())):
        for k in range(arrays.GetNumberOfArrays()):
            a = arrays.GetAbstractArray(k)
            if a.IsA("vtkStringArray"):
                print(tag, "strings:" + a.GetName(), *[a.GetValue(i) for i in range(a.GetNumberOfValues())])
            else:
                print(tag, kind + ":" + a.GetName(), *values(a))

for arg in sys.argv[1:]:
    tag, path = arg.split("=", 1)
    if path.endswith(".pvd"):
        entries = ET.parse(path).getroot().find("Collection").findall("DataSet")
        print(tag, "entries", len(entries))
        for k, e in enumerate(entries):
            print(tag + str(k), "timestep", repr(float(e.get("timestep"))))
            dump(tag + str(k), load(os.path.join(os.path.dirname(path), e.get("file"))))
    else:
        dump(tag, load(path))

text = messages.GetOutput()
if text.strip():
    print("vtk_messages", " ".join(text.split()))
)PY";

// What the reader printed: "tag field" -> the numbers that followed.
using Readout = std::map<std::string, std::vector<double>>;

// Runs the reader on `files` (tag = path). ADD_FAILURE (not a skip) when no
// python3 has VTK, since scripts/install-deps.sh installs it.
Readout read_with_vtk(const fs::path& dir, const std::vector<std::pair<std::string, fs::path>>& files,
                      std::string& raw) {
    const std::string python = python_with_vtk();
    if (python.empty()) {
        ADD_FAILURE() << "no python3 with the VTK module: install the Debian package python3-vtk9 "
                         "(scripts/install-deps.sh does) to read the snapshots back";
        return {};
    }
    const fs::path script = dir / "read_vtk.py";
    std::ofstream(script) << reader_script;
    std::string command = python + " " + script.string();
    for (const auto& [tag, file] : files) command += " " + tag + "=" + file.string();
    const tumble::test_support::CommandResult result = tumble::test_support::run_command(command);
    raw = result.output;
    EXPECT_EQ(result.exit_code, 0) << raw;
    Readout out;
    std::istringstream lines(raw);
    std::string line;
    while (std::getline(lines, line)) {
        std::istringstream words(line);
        std::string tag, field, word;
        words >> tag >> field;
        std::vector<double>& v = out[tag + " " + field];
        while (words >> word) v.push_back(std::strtod(word.c_str(), nullptr));
    }
    return out;
}

class VtkOutput : public tumble::test_support::ScratchTest {};

}  // namespace

// ---- The contact network -------------------------------------------------

// Pairs 0-1, 1-2, 0-4 (kinematic) and 3-5 touch; contacts per id follow.
TEST(ContactNetwork, ListsEveryTouchingPairOnceByIds) {
    tumble::Simulation sim(small_scenario(true));
    sim.advance(3);
    const std::vector<tumble::ContactLink> links = tumble::contact_network(sim);
    ASSERT_EQ(links.size(), 4u);
    const std::pair<std::int64_t, std::int64_t> expected[] = {{0, 1}, {0, 4}, {1, 2}, {3, 5}};
    for (std::size_t k = 0; k < links.size(); ++k) {
        EXPECT_EQ(links[k].id_i, expected[k].first);
        EXPECT_EQ(links[k].id_j, expected[k].second);
        EXPECT_GT(links[k].overlap, 0.0);
        EXPECT_NEAR(tumble::norm(links[k].n), 1.0, 1e-15);
    }
    EXPECT_EQ(tumble::contact_counts(sim), (std::vector<std::uint32_t>{2, 2, 1, 1, 1, 1}));
}

// F_n worked out here from the paper's formulas, with the contact written
// independently of make_contact_geometry: the velocity of the material point
// of each sphere at the contact point. Tolerance 1e-12 relative: the same
// quantities, summed in a different order.
TEST(ContactNetwork, NormalForceIsHertzPlusKuwabaraKonoPlusAttraction) {
    tumble::Simulation sim(small_scenario(true));
    sim.advance(3);
    const tumble::ParticleStore& p = sim.particles();
    const tumble::Material m = tumble::paper::material_1();
    const double W = 0.2;  // J/m^2, pair 1-1
    const double E_star = m.E / (2.0 * (1.0 - m.nu * m.nu));
    const double B = 9.0 * m.xi * m.eta / (3.0 * m.xi + m.eta);
    const double s = (3.0 * m.xi - 2.0 * m.eta) / (2.0 * (3.0 * m.xi + m.eta));
    const double B_star = B / (2.0 * (1.0 - s * s));
    const double A = std::sqrt(4.0 / 3.0 * 8.0 * 3.14159265358979323846 * W * E_star);

    const std::size_t i = index_of(p, 0), j = index_of(p, 1);
    const Vec3 d = p.position[i] - p.position[j];
    const double h = 2.0 * R - tumble::norm(d);
    const Vec3 n = (1.0 / tumble::norm(d)) * d;
    const Vec3 contact = p.position[i] - (R - 0.5 * h) * n;
    const Vec3 v_i = p.velocity[i] + tumble::cross(p.angular_velocity[i], contact - p.position[i]);
    const Vec3 v_j = p.velocity[j] + tumble::cross(p.angular_velocity[j], contact - p.position[j]);
    const double v_n = tumble::dot(v_i - v_j, n);
    const double R_star = R / 2.0;
    const double hertz = 4.0 / 3.0 * E_star * std::sqrt(R_star) * std::pow(h, 1.5);
    const double viscous = -2.0 * B_star * std::sqrt(R_star * h) * v_n;
    const double attraction = -A * std::pow(R_star * h, 0.75);
    const double expected = hertz + viscous + attraction;

    const tumble::ContactLink link = tumble::contact_network(sim).front();
    ASSERT_EQ(link.id_j, 1);
    std::printf("  [measured] F_n(0,1) = %.17g N (Hertz %.6g, KK %.6g, attraction %.6g), hand %.17g\n",
                link.normal_force, hertz, viscous, attraction, expected);
    EXPECT_GT(std::abs(viscous), 1e-3 * std::abs(hertz)) << "the test should exercise the viscous term";
    EXPECT_NEAR(link.normal_force, expected, 1e-12 * std::abs(expected));
    EXPECT_NEAR(link.overlap, h, 1e-18);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(link.point[k], contact[k], 1e-17);
}

// With the viscous term off, F_n depends only on the positions, which the
// force loop of the last step saw exactly as they are now (the closing kick
// changes velocities only), so the network must agree bit for bit with the
// step's own records. (With it on, the records hold F_n from v(t + dt/2).)
TEST(ContactNetwork, AgreesExactlyWithTheForceLoopRecords) {
    tumble::Simulation sim(small_scenario(false));
    sim.set_contact_recording(true);
    sim.advance(5);
    const std::vector<tumble::ContactLink> links = tumble::contact_network(sim);
    const std::vector<tumble::ContactRecord>& records = sim.contact_records();
    ASSERT_EQ(records.size(), links.size());
    for (const tumble::ContactRecord& r : records) {
        const std::int64_t a = std::min(r.id_i, r.id_j), b = std::max(r.id_i, r.id_j);
        const auto it = std::find_if(links.begin(), links.end(),
                                     [&](const tumble::ContactLink& l) { return l.id_i == a && l.id_j == b; });
        ASSERT_NE(it, links.end()) << a << "-" << b;
        EXPECT_EQ(it->normal_force, r.forces.normal_force) << a << "-" << b;
        EXPECT_EQ(it->overlap, r.geometry.overlap) << a << "-" << b;
    }
}

// ---- The files, read back by VTK -----------------------------------------

// Binary data, compressed (zlib) and read back by VTK's own reader, printed
// by python's repr (the shortest form that reads back to the same double):
// every number must come back exactly, so the comparisons are ==.
TEST_F(VtkOutput, ParticlesAndNetworkReadBackExactlyByVtk) {
    tumble::Simulation sim(small_scenario(true));
    sim.advance(4);
    const fs::path vtu = dir_ / "000000.vtu", vtp = dir_ / "000000.vtp";
    tumble::io::write_vtu_snapshot(vtu, sim);
    tumble::io::write_vtp_contact_network(vtp, sim);

    std::string raw;
    Readout r = read_with_vtk(dir_, {{"vtu", vtu}, {"vtp", vtp}}, raw);
    if (::testing::Test::HasFailure()) return;
    ASSERT_EQ(r.count("vtk_messages"), 0u) << raw;
    ASSERT_EQ(r.count("error cannot"), 0u) << raw;

    const tumble::ParticleStore& p = sim.particles();
    const std::vector<std::uint32_t> counts = tumble::contact_counts(sim);
    const std::size_t n = p.size();
    ASSERT_EQ(r["vtu points"].size(), 3 * n) << raw;
    ASSERT_EQ(r["vtu point:id"].size(), n) << raw;
    EXPECT_EQ(r["vtu cell_types"], std::vector<double>(n, 1.0));  // VTK_VERTEX
    EXPECT_EQ(r["vtu field:TimeValue"], std::vector<double>{sim.time()});
    EXPECT_EQ(r["vtu field:step"], std::vector<double>{4.0});
    // The names of the materials that point data "material" indexes.
    std::string names = "vtu strings:material_names";
    for (const tumble::Material& m : sim.scenario().materials) names += " " + m.name;
    EXPECT_NE(raw.find(names + "\n"), std::string::npos) << raw;
    for (std::size_t row = 0; row < n; ++row) {
        const std::size_t i = index_of(p, static_cast<std::int64_t>(row));  // rows by global id
        EXPECT_EQ(r["vtu point:id"][row], static_cast<double>(row));
        for (int c = 0; c < 3; ++c) {
            EXPECT_EQ(r["vtu points"][3 * row + c], p.position[i][c]) << "row " << row;
            EXPECT_EQ(r["vtu point:velocity"][3 * row + c], p.velocity[i][c]) << "row " << row;
            EXPECT_EQ(r["vtu point:angular_velocity"][3 * row + c], p.angular_velocity[i][c]) << "row " << row;
        }
        EXPECT_EQ(r["vtu point:radius"][row], p.radius[i]);
        EXPECT_EQ(r["vtu point:material"][row], p.material[i]);
        EXPECT_EQ(r["vtu point:tag"][row], p.tag[i]);
        EXPECT_EQ(r["vtu point:kinematic"][row], p.is_kinematic(i) ? 1.0 : 0.0);
        EXPECT_EQ(r["vtu point:contacts"][row], counts[row]);
    }
    EXPECT_EQ(r["vtu point:kinematic"][4], 1.0);
    EXPECT_EQ(r["vtu point:contacts"], (std::vector<double>{2, 2, 1, 1, 1, 1}));

    const std::vector<tumble::ContactLink> links = tumble::contact_network(sim);
    ASSERT_EQ(r["vtp cell_sizes"], std::vector<double>(links.size(), 2.0)) << raw;
    EXPECT_EQ(r["vtp cell_types"], std::vector<double>(links.size(), 3.0));  // VTK_LINE
    EXPECT_EQ(r["vtp field:TimeValue"], std::vector<double>{sim.time()});
    for (std::size_t k = 0; k < links.size(); ++k) {
        EXPECT_EQ(r["vtp cell:id_i"][k], links[k].id_i);
        EXPECT_EQ(r["vtp cell:id_j"][k], links[k].id_j);
        EXPECT_EQ(r["vtp cell:normal_force"][k], links[k].normal_force);
        EXPECT_EQ(r["vtp cell:overlap"][k], links[k].overlap);
        const std::size_t i = index_of(p, links[k].id_i), j = index_of(p, links[k].id_j);
        for (int c = 0; c < 3; ++c) {
            EXPECT_EQ(r["vtp cell:normal"][3 * k + c], links[k].n[c]);
            EXPECT_EQ(r["vtp points"][6 * k + c], p.position[i][c]);  // line from the centre of i ...
            // ... to the centre of j (open space: no image), to rounding of X_i - |d| n.
            EXPECT_NEAR(r["vtp points"][6 * k + 3 + c], p.position[j][c], 1e-15);
        }
    }
}

// A collection of two snapshots at different times, each dataset loaded by
// VTK from the path in the index; no temporary file is left behind.
TEST_F(VtkOutput, PvdIndexesATimeSeries) {
    tumble::Simulation sim(small_scenario(true));
    fs::create_directories(dir_ / "snapshots");
    tumble::io::PvdIndex particles(dir_ / "particles.pvd");
    tumble::io::PvdIndex contacts(dir_ / "contacts.pvd");
    std::vector<double> times;
    for (int k = 0; k < 2; ++k) {
        const std::string name = "snapshots/00000" + std::to_string(k);
        tumble::io::write_vtu_snapshot(dir_ / (name + ".vtu"), sim);
        tumble::io::write_vtp_contact_network(dir_ / (name + ".vtp"), sim);
        particles.add(sim.time(), name + ".vtu");
        contacts.add(sim.time(), name + ".vtp");
        times.push_back(sim.time());
        sim.advance(10);
    }
    EXPECT_FALSE(fs::exists(dir_ / "particles.pvd.tmp"));
    EXPECT_FALSE(fs::exists(dir_ / "contacts.pvd.tmp"));

    std::string raw;
    Readout r = read_with_vtk(dir_, {{"particles", dir_ / "particles.pvd"}, {"contacts", dir_ / "contacts.pvd"}}, raw);
    if (::testing::Test::HasFailure()) return;
    ASSERT_EQ(r.count("vtk_messages"), 0u) << raw;
    EXPECT_EQ(r["particles entries"], std::vector<double>{2.0}) << raw;
    EXPECT_EQ(r["contacts entries"], std::vector<double>{2.0}) << raw;
    for (int k = 0; k < 2; ++k) {
        const std::string pk = "particles" + std::to_string(k), ck = "contacts" + std::to_string(k);
        EXPECT_EQ(r[pk + " timestep"], std::vector<double>{times[k]});
        EXPECT_EQ(r[pk + " field:TimeValue"], std::vector<double>{times[k]});
        EXPECT_EQ(r[pk + " point:id"].size(), 6u) << raw;
        EXPECT_EQ(r[ck + " timestep"], std::vector<double>{times[k]});
        EXPECT_EQ(r[ck + " cell:normal_force"].size(), 4u) << raw;
    }
    EXPECT_GT(times[1], times[0]);
}

// An index with no dataset yet is a valid, empty collection.
TEST_F(VtkOutput, EmptyPvdIsValid) {
    tumble::io::PvdIndex index(dir_ / "empty.pvd");
    std::string raw;
    Readout r = read_with_vtk(dir_, {{"empty", dir_ / "empty.pvd"}}, raw);
    if (::testing::Test::HasFailure()) return;
    EXPECT_EQ(r["empty entries"], std::vector<double>{0.0}) << raw;
}

// ---- The smooth walls ----------------------------------------------------

// A capped cylinder turning with a motion and a fixed plane, drawn where the
// motion has carried them: VTK reads every triangle, the wall each belongs
// to and the walls' names, and the points are those of wall_surfaces().
TEST_F(VtkOutput, WallsReadBackExactlyByVtk) {
    tumble::Scenario s = small_scenario(true);
    s.motions.push_back({{}, {0.0, 0.0, 1.0}, 3.0, {}});
    const auto turning = static_cast<std::int32_t>(s.motions.size() - 1);
    tumble::Wall drum{.name = "drum", .shape = tumble::WallShape::cylinder, .point = {0.0, 0.0, -0.1},
                      .radius = 0.12, .length = 0.2, .motion = turning};
    tumble::Wall floor{.name = "floor", .shape = tumble::WallShape::plane, .point = {0.0, 0.0, -0.1}};
    tumble::Wall cap{.name = "cap", .shape = tumble::WallShape::disc, .point = {0.0, 0.0, -0.1}, .radius = 0.12,
                     .motion = turning};
    s.walls = {drum, floor, cap};
    tumble::Simulation sim(s);
    sim.advance(10);
    const fs::path vtp = dir_ / "walls.vtp";
    const tumble::io::SnapshotData snapshot = tumble::io::snapshot_of(sim);
    tumble::io::write_vtp_walls(vtp, snapshot);
    std::string raw;
    Readout r = read_with_vtk(dir_, {{"w", vtp}}, raw);
    if (::testing::Test::HasFailure()) return;
    ASSERT_EQ(r.count("vtk_messages"), 0u) << raw;
    const std::vector<tumble::WallSurface> drawn = tumble::io::wall_surfaces(sim);
    ASSERT_EQ(drawn.size(), 3u);
    // 48 quadrilaterals around the mantle, 2 triangles for the plane, a fan of 48 for the disc.
    EXPECT_EQ(drawn[0].triangles.size(), 96u);
    EXPECT_EQ(drawn[1].triangles.size(), 2u);
    EXPECT_EQ(drawn[2].triangles.size(), 48u);
    std::vector<double> points, wall;
    for (std::size_t k = 0; k < drawn.size(); ++k) {
        for (const tumble::Vec3& v : drawn[k].vertices) points.insert(points.end(), {v.x, v.y, v.z});
        wall.insert(wall.end(), drawn[k].triangles.size(), static_cast<double>(k));
    }
    EXPECT_EQ(r["w points"], points);
    EXPECT_EQ(r["w cell:wall"], wall);
    EXPECT_EQ(r["w cell_types"], std::vector<double>(wall.size(), 5.0));  // VTK_TRIANGLE
    EXPECT_EQ(r["w field:TimeValue"], std::vector<double>{sim.time()});
    EXPECT_NE(raw.find("w strings:wall_names drum floor cap\n"), std::string::npos) << raw;
    // The mantle's first vertex, at (0, -R, -0.1) when the motion began, has
    // turned by 3 rad/s x t about z.
    const double angle = 3.0 * sim.time();
    EXPECT_NEAR(drawn[0].vertices[0].x, 0.12 * std::sin(angle), 1e-15);
    EXPECT_NEAR(drawn[0].vertices[0].y, -0.12 * std::cos(angle), 1e-15);
}

// tumble render reads the walls back (io/vtk_input.hpp): every wall's points
// bit for bit and its triangles, numbered over all walls as the file numbers
// them; arrays of more than one compressed block (32768 bytes) too.
TEST_F(VtkOutput, WallsReadBackExactlyByTumble) {
    tumble::io::SnapshotData snapshot;
    snapshot.wall_names = {"strip", "triangle"};
    tumble::WallSurface strip, triangle;
    for (std::uint32_t k = 0; k < 3000; ++k) {  // 3000 points: 72 000 bytes, three blocks
        strip.vertices.push_back({0.001 * k, std::sin(0.1 * k), 1.0 / 3.0});
        if (k >= 2) strip.triangles.push_back({k - 2, k - 1, k});
    }
    triangle.vertices = {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}};
    triangle.triangles = {{0, 1, 2}};
    snapshot.walls = {strip, triangle};
    const fs::path vtp = dir_ / "walls.vtp";
    tumble::io::write_vtp_walls(vtp, snapshot);

    const tumble::WallSurface back = tumble::io::read_vtp_walls(vtp);
    ASSERT_EQ(back.vertices.size(), 3003u);
    ASSERT_EQ(back.triangles.size(), 2999u);
    for (std::size_t k = 0; k < 3000; ++k) {
        EXPECT_EQ(back.vertices[k].y, strip.vertices[k].y) << k;
        EXPECT_EQ(back.vertices[k].z, 1.0 / 3.0) << k;
    }
    EXPECT_EQ(back.vertices[3001].x, 1.0);
    EXPECT_EQ(back.triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
    EXPECT_EQ(back.triangles[2997], (std::array<std::uint32_t, 3>{2997, 2998, 2999}));
    EXPECT_EQ(back.triangles[2998], (std::array<std::uint32_t, 3>{3000, 3001, 3002})) << "the second wall's";

    // Not a walls file: an error naming it.
    write("contacts.vtp", "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\">\n");
    try {
        tumble::io::read_vtp_walls(dir_ / "contacts.vtp");
        FAIL() << "no error";
    } catch (const tumble::Error& e) {
        EXPECT_NE(std::string(e.what()).find((dir_ / "contacts.vtp").string()), std::string::npos) << e.what();
    }
}
