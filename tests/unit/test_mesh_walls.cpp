// SPDX-License-Identifier: MIT
// Triangle-mesh walls (tumble/walls): a sphere on a plane made of triangles
// feels the analytic plane's one contact everywhere, on edges and vertices
// included; the convex edge and corner of a box give one edge or vertex
// contact, a V two face contacts, a single triangle its open edges and
// corners; the facet grid lists every face a sphere touches (against a
// brute-force search written here); and the mesh's checks and topology.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "tumble/core/constants.hpp"
#include "tumble/walls/facet_grid.hpp"
#include "tumble/walls/mesh.hpp"

namespace tumble {
namespace {

double uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

std::vector<std::uint32_t> all_faces(const MeshTopology& mesh) {
    std::vector<std::uint32_t> faces(mesh.face_count());
    std::iota(faces.begin(), faces.end(), 0u);
    return faces;
}

std::vector<MeshContact> contacts(const MeshTopology& mesh, const Vec3& c, double R) {
    std::vector<MeshContact> out;
    mesh_contacts(mesh, c, R, all_faces(mesh), out);
    return out;
}

// n squares of side `side` in the plane z = 0 from the origin, each split by
// its diagonal from (i, j) to (i + 1, j + 1) into two triangles, counter-
// clockwise from +z (N = +z). Vertex (i, j) at (i side / n, j side / n):
// the coordinate i / n is the double nearest that fraction, as is any k / m
// equal to it.
TriangleMesh plane_mesh(int n, double side) {
    TriangleMesh mesh;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) mesh.vertices.push_back({side * i / n, side * j / n, 0.0});
    auto id = [n](int i, int j) { return static_cast<std::uint32_t>(i + (n + 1) * j); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            mesh.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            mesh.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    return mesh;
}

// The axis-aligned box [0, 1]^3, two triangles per side, N outwards.
// Vertex ids: x + 2 y + 4 z for the corner (x, y, z) in {0, 1}^3.
TriangleMesh unit_box() {
    TriangleMesh mesh;
    for (int v = 0; v < 8; ++v) mesh.vertices.push_back({double(v & 1), double((v >> 1) & 1), double((v >> 2) & 1)});
    // Each side as four corners in order round it; split along its first diagonal.
    const std::array<std::array<std::uint32_t, 4>, 6> sides{{{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                                             {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}}};
    const Vec3 centre{0.5, 0.5, 0.5};
    for (const auto& q : sides)
        for (std::array<std::uint32_t, 3> t : {std::array<std::uint32_t, 3>{q[0], q[1], q[2]},
                                               std::array<std::uint32_t, 3>{q[0], q[2], q[3]}}) {
            const Vec3 a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
            if (dot(cross(b - a, c - a), a - centre) < 0.0) std::swap(t[1], t[2]);  // outwards
            mesh.triangles.push_back(t);
        }
    return mesh;
}

std::uint32_t edge_id(const MeshTopology& mesh, std::uint32_t a, std::uint32_t b) {
    const std::array<std::uint32_t, 2> key{std::min(a, b), std::max(a, b)};
    const auto edges = mesh.edges();
    const auto at = std::find(edges.begin(), edges.end(), key);
    EXPECT_NE(at, edges.end());
    return static_cast<std::uint32_t>(at - edges.begin());
}

// Distance from p to the triangle (a, b, c), by another route than the
// engine's: the plane's distance where p projects inside (all three
// barycentric areas of one sign), else the nearest of the three segments.
double distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 normal = cross(b - a, c - a);
    const Vec3 u = (1.0 / norm(normal)) * normal;
    const Vec3 q = p - dot(p - a, u) * u;
    const double wa = dot(cross(b - q, c - q), u), wb = dot(cross(c - q, a - q), u), wc = dot(cross(a - q, b - q), u);
    if (wa >= 0.0 && wb >= 0.0 && wc >= 0.0) return std::abs(dot(p - a, u));
    auto segment = [&p](const Vec3& x, const Vec3& y) {
        const double t = std::clamp(dot(p - x, y - x) / norm2(y - x), 0.0, 1.0);
        return norm(p - (x + t * (y - x)));
    };
    return std::min({segment(a, b), segment(b, c), segment(c, a)});
}

double distance_to_face(const MeshTopology& mesh, std::uint32_t f, const Vec3& p) {
    const auto& t = mesh.triangles()[f];
    return distance_to_triangle(p, mesh.vertices()[t[0]], mesh.vertices()[t[1]], mesh.vertices()[t[2]]);
}

// --- A plane of triangles against the analytic plane --------------------

// The centres' x (and y) on [0, side]: every multiple of side/40 (so on each
// vertex line of a 10 x 10 mesh, and on the diagonals where x - y is a
// multiple of side/10) and the doubles on either side of each.
std::vector<double> crossing_coordinates(double side) {
    std::vector<double> xs;
    for (int i = 0; i <= 40; ++i) {
        const double x = side * i / 40;
        xs.push_back(x);
        if (i > 0) xs.push_back(std::nextafter(x, -1.0));
        if (i < 40) xs.push_back(std::nextafter(x, 2.0 * side));
    }
    return xs;
}

struct FeatureCount {
    int face = 0, edge = 0, vertex = 0;
};

// For every centre (x, y, z) of the sweep: exactly one contact, with the
// plane z = 0's normal (0, 0, 1), overlap R - z and point (x, y, 0), with
// the grid's candidates and with all faces alike. `count` gets which
// features gave the contacts.
void expect_plane_everywhere(const TriangleMesh& triangles, double side, double R, FeatureCount& count) {
    const MeshTopology mesh(triangles);
    FacetGrid grid(2.0 * R, R);
    grid.rebuild(mesh);
    const std::vector<std::uint32_t> every = all_faces(mesh);
    std::vector<MeshContact> out;
    for (double z : {0.999 * R, 0.6 * R, 0.1 * R})
        for (double y : crossing_coordinates(side))
            for (double x : crossing_coordinates(side))
                for (bool use_grid : {true, false}) {
                    const Vec3 c{x, y, z};
                    mesh_contacts(mesh, c, R, use_grid ? grid.candidates(c) : std::span<const std::uint32_t>(every),
                                  out);
                    ASSERT_EQ(out.size(), 1u) << "centre " << x << ", " << y << ", " << z;
                    const MeshContact& k = out[0];
                    // Round-off only: the engine's arithmetic on a plane along
                    // the axes is exact for faces and vertices and leaves an
                    // ulp of the edge's parameter for edges.
                    EXPECT_NEAR(k.n.x, 0.0, 1e-15);
                    EXPECT_NEAR(k.n.y, 0.0, 1e-15);
                    EXPECT_NEAR(k.n.z, 1.0, 1e-15);
                    EXPECT_NEAR(k.overlap, R - z, 1e-15 * (R - z));
                    EXPECT_NEAR(k.point.x, x, 1e-15 * side);
                    EXPECT_NEAR(k.point.y, y, 1e-15 * side);
                    EXPECT_EQ(k.point.z, 0.0);
                    if (use_grid) {
                        count.face += k.feature == MeshFeature::face;
                        count.edge += k.feature == MeshFeature::edge;
                        count.vertex += k.feature == MeshFeature::vertex;
                    }
                }
}

TEST(MeshWalls, TwoTrianglesGiveThePlanesContactEverywhere) {
    // R = 0.3 and z down to 0.03: the sphere's disc on the plane (radius up
    // to 0.298) crosses the diagonal and the square's edges.
    FeatureCount count;
    expect_plane_everywhere(plane_mesh(1, 1.0), 1.0, 0.3, count);
    // The sweep met all three kinds: centres on the diagonal and the square's
    // edges give edge contacts, on its corners vertex contacts.
    EXPECT_GT(count.face, 0);
    EXPECT_GT(count.edge, 0);
    EXPECT_GT(count.vertex, 0);
}

TEST(MeshWalls, TwoHundredTrianglesGiveThePlanesContactEverywhere) {
    // Squares of 0.1 and R = 0.08: the disc (radius up to 0.08) spans up to
    // four squares, so edges and vertices of faces the centre is not over
    // come within R of it.
    const TriangleMesh triangles = plane_mesh(10, 1.0);
    ASSERT_EQ(triangles.triangles.size(), 200u);
    const MeshTopology mesh(triangles);
    // The interior vertices have six triangles each (the diagonals all one way).
    EXPECT_EQ(mesh.vertex_faces(5 + 11 * 5).size(), 6u);
    FeatureCount count;
    expect_plane_everywhere(triangles, 1.0, 0.08, count);
    EXPECT_GT(count.face, 0);
    EXPECT_GT(count.edge, 0);
    EXPECT_GT(count.vertex, 0);
}

TEST(MeshWalls, ATurnedPlaneOfTrianglesGivesOneContactEverywhere) {
    // The 200-triangle plane turned about an oblique axis and moved: its
    // triangles' normals now differ in the last bits, so the two faces of an
    // edge no longer compute exactly opposite sides, and a centre over an
    // edge may be claimed by both (rule 4 keeps one) or by neither (the
    // edge then gives the contact); over a vertex every test may fail (rule
    // 5 then takes the nearest point: at (0.1, 0.4) for one). Still one
    // contact everywhere, equal to the plane's to a few ulps of the
    // coordinates.
    TriangleMesh triangles = plane_mesh(10, 1.0);
    const Vec3 k = (1.0 / std::sqrt(14.0)) * Vec3{1.0, 2.0, 3.0};
    const double a = 0.7, co = std::cos(a), si = std::sin(a);
    auto turn = [&](const Vec3& v) { return co * v + si * cross(k, v) + ((1.0 - co) * dot(k, v)) * k; };
    const Vec3 offset{0.3, -0.2, 0.1};
    for (Vec3& v : triangles.vertices) v = turn(v) + offset;
    const MeshTopology mesh(triangles);
    const Vec3 normal = turn({0.0, 0.0, 1.0});
    const double R = 0.08;
    FacetGrid grid(2.0 * R, R);
    grid.rebuild(mesh);
    std::vector<MeshContact> out;
    for (double z : {0.6 * R, 0.1 * R})
        for (double v : crossing_coordinates(1.0))
            for (double u : crossing_coordinates(1.0)) {
                const Vec3 foot = turn({u, v, 0.0}) + offset;
                const Vec3 c = foot + z * normal;
                mesh_contacts(mesh, c, R, grid.candidates(c), out);
                ASSERT_EQ(out.size(), 1u) << "centre over " << u << ", " << v;
                // Rounding of the turned coordinates (about 1e-16 each) moves
                // the plane by a few 1e-16: 1e-14 leaves room for that alone.
                // At the open edges the normal comes from the centre's offset
                // from the edge, which is that rounding too: it tilts n by
                // about 1e-16 / z.
                EXPECT_LT(norm(out[0].n - normal), 1e-15 + 4e-16 / z);
                EXPECT_NEAR(out[0].overlap, R - z, 1e-14);
                EXPECT_LT(norm(out[0].point - foot), 1e-14);
            }
}

// --- Edges, corners, creases, open edges ---------------------------------

TEST(MeshWalls, BoxTopologyIsClosed) {
    const MeshTopology box(unit_box());
    EXPECT_EQ(box.vertex_count(), 8u);
    EXPECT_EQ(box.face_count(), 12u);
    EXPECT_EQ(box.edge_count(), 18u);  // Euler: V - E + F = 2
    for (std::uint32_t e = 0; e < box.edge_count(); ++e) EXPECT_EQ(box.edge_sides(e).size(), 2u);
    std::size_t incidences = 0;
    for (std::uint32_t v = 0; v < 8; ++v) incidences += box.vertex_faces(v).size();
    EXPECT_EQ(incidences, 36u);  // three corners per face
    for (std::uint32_t f = 0; f < 12; ++f)
        for (int k = 0; k < 3; ++k) {
            const auto edge = box.edges()[box.face_edges()[f][k]];
            const std::uint32_t a = box.triangles()[f][k], b = box.triangles()[f][(k + 1) % 3];
            EXPECT_EQ(edge[0], std::min(a, b));
            EXPECT_EQ(edge[1], std::max(a, b));
        }
}

// The winding number of the closed box is 1 inside and 0 outside (to the
// round-off of twelve solid angles), -1 inside when every face is turned
// in; the box is a closed surface, and it is not with a face missing (an
// edge of one face) or one face turned (its edges run the same way twice).
TEST(MeshWalls, TheWindingNumberTellsInsideAClosedMeshFromOutside) {
    TriangleMesh mesh = unit_box();
    const MeshTopology box(mesh);
    EXPECT_EQ(closed_surface_problem(box), "");
    for (const Vec3& x : {Vec3{0.5, 0.5, 0.5}, Vec3{0.01, 0.99, 0.5}, Vec3{0.999, 0.001, 0.999}})
        EXPECT_NEAR(winding_number(box, x), 1.0, 1e-12);
    for (const Vec3& x : {Vec3{1.5, 0.5, 0.5}, Vec3{-0.001, 0.5, 0.5}, Vec3{3.0, -2.0, 7.0}})
        EXPECT_NEAR(winding_number(box, x), 0.0, 1e-12);
    TriangleMesh turned = mesh;
    for (auto& t : turned.triangles) std::swap(t[1], t[2]);
    EXPECT_NEAR(winding_number(MeshTopology(turned), {0.5, 0.5, 0.5}), -1.0, 1e-12);
    TriangleMesh open = mesh;
    open.triangles.pop_back();
    EXPECT_NE(closed_surface_problem(MeshTopology(open)).find("has 1 face, not two"), std::string::npos)
        << closed_surface_problem(MeshTopology(open));
    TriangleMesh twisted = mesh;
    std::swap(twisted.triangles[0][1], twisted.triangles[0][2]);
    EXPECT_NE(closed_surface_problem(MeshTopology(twisted)).find("run along it the same way"), std::string::npos)
        << closed_surface_problem(MeshTopology(twisted));
}

TEST(MeshWalls, ConvexEdgeOfABoxGivesOneEdgeContact) {
    const MeshTopology box(unit_box());
    const double R = 0.3, a = 0.1, b = 0.2;  // the centre 0.1 beyond the side y = 1, 0.2 above the top
    const std::vector<MeshContact> out = contacts(box, {0.37, 1.0 + a, 1.0 + b}, R);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].feature, MeshFeature::edge);
    EXPECT_EQ(out[0].id, edge_id(box, 6, 7));  // (0, 1, 1) to (1, 1, 1)
    const double distance = std::hypot(a, b);
    // Hand values: q = (0.37, 1, 1), n = (0, a, b) / sqrt(a^2 + b^2); round-off.
    EXPECT_NEAR(out[0].overlap, R - distance, 1e-15);
    EXPECT_LT(norm(out[0].n - Vec3{0.0, a / distance, b / distance}), 1e-15);
    EXPECT_LT(norm(out[0].point - Vec3{0.37, 1.0, 1.0}), 1e-15);
}

TEST(MeshWalls, SphereOnTheTopBesideAnEdgeFeelsTheTopAlone) {
    // The centre over the top, 0.05 from its edge and 0.05 above it: the side
    // y = 1 is within R (its top edge, 0.0707 away) but the top's point is
    // nearer and the edge lies inside the top across it: one face contact.
    const MeshTopology box(unit_box());
    const std::vector<MeshContact> out = contacts(box, {0.37, 0.95, 1.05}, 0.3);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].feature, MeshFeature::face);
    EXPECT_NEAR(out[0].overlap, 0.25, 1e-15);
    EXPECT_EQ(out[0].n, (Vec3{0.0, 0.0, 1.0}));
}

TEST(MeshWalls, CornerOfABoxGivesOneVertexContact) {
    const MeshTopology box(unit_box());
    const Vec3 r{0.1, 0.15, 0.2};  // beyond the corner (1, 1, 1) on every edge at it
    const std::vector<MeshContact> out = contacts(box, Vec3{1.0, 1.0, 1.0} + r, 0.3);
    // Hand values: q = (1, 1, 1), n = r / |r|, h = R - |r|; round-off.
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].feature, MeshFeature::vertex);
    EXPECT_EQ(out[0].id, 7u);
    EXPECT_NEAR(out[0].overlap, 0.3 - norm(r), 1e-15);
    EXPECT_LT(norm(out[0].n - (1.0 / norm(r)) * r), 1e-15);
    EXPECT_EQ(out[0].point, (Vec3{1.0, 1.0, 1.0}));
}

// Floor z = 0 and wall x = 0, both 1 x 1 for y in [0, 1], meeting along the
// y axis; `plate` adds a second floor x in [-1, 0] behind the wall, so that
// the wall stands on a floor like a lifter (an edge of three faces).
TriangleMesh floor_and_wall(bool plate) {
    std::vector<std::array<Vec3, 3>> corners{
        {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{1, 1, 0}}, {Vec3{0, 0, 0}, Vec3{1, 1, 0}, Vec3{0, 1, 0}},
        {Vec3{0, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 1, 1}}, {Vec3{0, 0, 0}, Vec3{0, 1, 1}, Vec3{0, 0, 1}}};
    if (plate) {
        corners.push_back({Vec3{-1, 0, 0}, Vec3{0, 0, 0}, Vec3{0, 1, 0}});
        corners.push_back({Vec3{-1, 0, 0}, Vec3{0, 1, 0}, Vec3{-1, 1, 0}});
    }
    return weld_triangles(corners);
}

TEST(MeshWalls, SphereInAConcaveCornerGetsTwoFaceContacts) {
    const MeshTopology v(floor_and_wall(false));
    // 0.25 above the floor and 0.2 off the wall, R = 0.3: overlaps 0.05 and
    // 0.1, one per side, each along its side's normal; the crease (the y axis)
    // is within R too but lies inside both faces across it.
    const std::vector<MeshContact> out = contacts(v, {0.2, 0.37, 0.25}, 0.3);
    ASSERT_EQ(out.size(), 2u);
    for (const MeshContact& k : out) EXPECT_EQ(k.feature, MeshFeature::face);
    const MeshContact& floor = out[0].n.z > 0.5 ? out[0] : out[1];
    const MeshContact& wall = out[0].n.z > 0.5 ? out[1] : out[0];
    EXPECT_EQ(floor.n, (Vec3{0.0, 0.0, 1.0}));
    EXPECT_NEAR(floor.overlap, 0.05, 1e-15);
    EXPECT_EQ(wall.n.x, 1.0);
    EXPECT_NEAR(wall.overlap, 0.1, 1e-15);
}

TEST(MeshWalls, PlateStandingOnAFloorMakesAnEdgeOfThreeFaces) {
    const MeshTopology t(floor_and_wall(true));
    EXPECT_EQ(t.edge_sides(edge_id(t, 0, 3)).size(), 3u);  // (0, 0, 0) to (0, 1, 0)
    // Either side of the plate: the floor there and the plate, two contacts.
    for (double side : {1.0, -1.0}) {
        const std::vector<MeshContact> out = contacts(t, {0.2 * side, 0.37, 0.25}, 0.3);
        ASSERT_EQ(out.size(), 2u);
        EXPECT_NEAR(out[0].overlap + out[1].overlap, 0.15, 1e-15);
    }
    // Over the plate's top edge: one edge contact.
    const std::vector<MeshContact> top = contacts(t, {0.0, 0.37, 1.1}, 0.3);
    ASSERT_EQ(top.size(), 1u);
    EXPECT_EQ(top[0].feature, MeshFeature::edge);
    EXPECT_NEAR(top[0].overlap, 0.2, 1e-15);
}

TEST(MeshWalls, NearlyFlatCreaseGivesTwoContactsAsTheHeaderSays) {
    // The documented limit: a concave crease of theta = 10 deg; a centre
    // above the crease at height d is over both faces and feels each with
    // overlap R - d cos(theta / 2).
    const double theta = 10.0 * pi / 180.0, t = std::tan(theta / 2.0);
    const TriangleMesh crease = weld_triangles(std::vector<std::array<Vec3, 3>>{
        {Vec3{0, 0, 0}, Vec3{1, 0, t}, Vec3{1, 1, t}}, {Vec3{0, 0, 0}, Vec3{1, 1, t}, Vec3{0, 1, 0}},
        {Vec3{0, 0, 0}, Vec3{0, 1, 0}, Vec3{-1, 1, t}}, {Vec3{0, 0, 0}, Vec3{-1, 1, t}, Vec3{-1, 0, t}}});
    const double R = 0.3, d = 0.25;
    const std::vector<MeshContact> out = contacts(MeshTopology(crease), {0.0, 0.37, d}, R);
    ASSERT_EQ(out.size(), 2u);
    for (const MeshContact& k : out) EXPECT_NEAR(k.overlap, R - d * std::cos(theta / 2.0), 1e-15);
    // Beyond d tan(theta / 2) from the crease the centre is over one face only.
    EXPECT_EQ(contacts(MeshTopology(crease), {1.01 * d * t, 0.37, d}, R).size(), 1u);
}

// The triangle (0, 0, 0), (1, 0, 0), (0, 1, 0): N = +z, every edge open.
TriangleMesh single_triangle() {
    return weld_triangles(std::vector<std::array<Vec3, 3>>{{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}}});
}

TEST(MeshWalls, SingleTriangleHasOpenEdgesAndCornersOnBothSides) {
    const MeshTopology one(single_triangle());
    const double R = 0.3;
    // Hand values throughout; 1e-15 is round-off.
    // Beyond the side y = 0, above the plane: the edge, n from it.
    std::vector<MeshContact> out = contacts(one, {0.4, -0.1, 0.2}, R);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].feature, MeshFeature::edge);
    EXPECT_NEAR(out[0].overlap, R - std::sqrt(0.05), 1e-15);
    EXPECT_LT(norm(out[0].n - (1.0 / std::sqrt(0.05)) * Vec3{0.0, -0.1, 0.2}), 1e-15);
    // Beyond the hypotenuse: q = (0.5, 0.5, 0).
    out = contacts(one, {0.6, 0.6, 0.1}, R);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].feature, MeshFeature::edge);
    EXPECT_LT(norm(out[0].point - Vec3{0.5, 0.5, 0.0}), 1e-15);
    EXPECT_NEAR(out[0].overlap, R - std::sqrt(0.03), 1e-15);
    // Beyond the corner (1, 0, 0) on both its sides: the vertex.
    out = contacts(one, {1.1, -0.1, 0.1}, R);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].feature, MeshFeature::vertex);
    EXPECT_EQ(out[0].id, 1u);
    EXPECT_NEAR(out[0].overlap, R - std::sqrt(0.03), 1e-15);
    // Below the triangle: the face, n = -N (two-sided).
    out = contacts(one, {0.2, 0.2, -0.1}, R);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].feature, MeshFeature::face);
    EXPECT_EQ(out[0].n, (Vec3{0.0, 0.0, -1.0}));
    EXPECT_NEAR(out[0].overlap, 0.2, 1e-15);
    // In the triangle's plane beyond its side: the edge, n in the plane.
    out = contacts(one, {0.4, -0.1, 0.0}, R);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].n, (Vec3{0.0, -1.0, 0.0}));
}

TEST(MeshWalls, SphereOutOfReachHasNoContact) {
    const MeshTopology one(single_triangle());
    const double R = 0.3;
    EXPECT_TRUE(contacts(one, {0.2, 0.2, 0.3}, R).empty());           // touching the face: h = 0
    EXPECT_TRUE(contacts(one, {0.4, -0.2, 0.23}, R).empty());         // 0.3048 from the edge
    EXPECT_TRUE(contacts(one, {1.2, -0.2, 0.15}, R).empty());         // 0.32 from the corner
    EXPECT_TRUE(contacts(one, {5.0, 5.0, 5.0}, R).empty());
    FacetGrid grid(0.6, R);
    grid.rebuild(one);
    EXPECT_TRUE(grid.candidates({5.0, 5.0, 5.0}).empty());  // outside the grid
}

TEST(MeshWalls, UnweldedSeamCountsOnce) {
    // Two squares side by side whose shared corners were written with
    // separate vertices (no welding): a sphere over the seam finds the two
    // open edges at one point; rule 4 keeps one.
    TriangleMesh two = plane_mesh(1, 1.0);
    TriangleMesh right = plane_mesh(1, 1.0);
    for (Vec3& v : right.vertices) v.x += 1.0;
    for (auto& t : right.triangles)
        for (auto& id : t) id += static_cast<std::uint32_t>(two.vertices.size());
    two.vertices.insert(two.vertices.end(), right.vertices.begin(), right.vertices.end());
    two.triangles.insert(two.triangles.end(), right.triangles.begin(), right.triangles.end());
    const std::vector<MeshContact> out = contacts(MeshTopology(two), {1.0, 0.37, 0.2}, 0.3);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].n, (Vec3{0.0, 0.0, 1.0}));
    EXPECT_NEAR(out[0].overlap, 0.1, 1e-15);
}

// --- A curved surface: no gaps, and the grid's candidates -----------------

// A height field z = 0.1 sin(3 x) cos(2 y) on [0, 1]^2, 12 x 12 squares:
// convex and concave edges, vertices of both kinds and saddles.
TriangleMesh bumpy_surface() {
    TriangleMesh mesh = plane_mesh(12, 1.0);
    for (Vec3& v : mesh.vertices) v.z = 0.1 * std::sin(3.0 * v.x) * std::cos(2.0 * v.y);
    return mesh;
}

// Random spheres (fixed seed) with centres in [lo, hi] and radii up to
// R_max: the grid's candidates hold every face within R_max (brute force),
// they give the same contacts as all faces, and a sphere that overlaps the
// surface has a contact, the deepest at the surface's nearest point.
void expect_grid_and_contacts(const MeshTopology& mesh, const Vec3& lo, const Vec3& hi, double R_max, double cell) {
    FacetGrid grid(cell, R_max);
    grid.rebuild(mesh);
    std::mt19937_64 rng(20240611);
    std::vector<MeshContact> from_grid, from_all;
    const std::vector<std::uint32_t> every = all_faces(mesh);
    int touching = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        const Vec3 c{lo.x + (hi.x - lo.x) * uniform(rng), lo.y + (hi.y - lo.y) * uniform(rng),
                     lo.z + (hi.z - lo.z) * uniform(rng)};
        const double R = R_max * (0.1 + 0.9 * uniform(rng));
        const std::span<const std::uint32_t> candidates = grid.candidates(c);
        ASSERT_TRUE(std::is_sorted(candidates.begin(), candidates.end()));
        double nearest = std::numeric_limits<double>::infinity();
        for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
            const double distance = distance_to_face(mesh, f, c);
            nearest = std::min(nearest, distance);
            if (distance < R_max) {
                ASSERT_TRUE(std::binary_search(candidates.begin(), candidates.end(), f))
                    << "face " << f << " at " << distance << " missing for trial " << trial;
            }
        }
        mesh_contacts(mesh, c, R, candidates, from_grid);
        mesh_contacts(mesh, c, R, every, from_all);
        ASSERT_EQ(from_grid.size(), from_all.size());
        for (std::size_t k = 0; k < from_grid.size(); ++k) {
            EXPECT_EQ(from_grid[k].feature, from_all[k].feature);
            EXPECT_EQ(from_grid[k].id, from_all[k].id);
            EXPECT_EQ(from_grid[k].overlap, from_all[k].overlap);
        }
        // Both routes to the distance round differently, 1e-15 apart at most.
        if (nearest < R) {
            ++touching;
            ASSERT_FALSE(from_all.empty()) << "trial " << trial;
            double deepest = 0.0;
            for (const MeshContact& k : from_all) {
                deepest = std::max(deepest, k.overlap);
                EXPECT_NEAR(norm(k.n), 1.0, 1e-15);
                EXPECT_NEAR(norm(c - k.point), R - k.overlap, 1e-15);
            }
            EXPECT_NEAR(deepest, R - nearest, 1e-15);
        } else {
            EXPECT_TRUE(from_all.empty());
        }
    }
    EXPECT_GT(touching, 400);  // the trials exercised the contacts
}

TEST(MeshWalls, GridCandidatesHoldEveryFaceASphereTouches) {
    // A cell smaller than the reach: each face in many cells.
    expect_grid_and_contacts(MeshTopology(bumpy_surface()), {-0.15, -0.15, -0.25}, {1.15, 1.15, 0.25}, 0.1, 0.07);
    // The box turned about an oblique axis: large tilted faces, whose
    // bounding boxes hold many cells the face is far from; convex edges
    // and corners.
    TriangleMesh box = unit_box();
    const Vec3 k = (1.0 / std::sqrt(6.0)) * Vec3{1.0, -1.0, 2.0};
    const double co = std::cos(0.9), si = std::sin(0.9);
    for (Vec3& v : box.vertices) v = co * v + si * cross(k, v) + ((1.0 - co) * dot(k, v)) * k;
    expect_grid_and_contacts(MeshTopology(box), {-1.0, -1.0, -0.5}, {1.8, 1.8, 2.0}, 0.3, 0.15);
}

TEST(MeshWalls, MovedMeshKeepsItsIdsAndTheGridFollows) {
    MeshTopology mesh(unit_box());
    FacetGrid grid(0.5, 0.3);
    grid.rebuild(mesh);
    std::vector<Vec3> moved(mesh.vertices().begin(), mesh.vertices().end());
    for (Vec3& v : moved) v += Vec3{2.0, 0.0, 0.0};
    mesh.set_vertices(moved);
    grid.rebuild(mesh);
    std::vector<MeshContact> out;
    const Vec3 c = Vec3{3.0, 1.0, 1.0} + Vec3{0.1, 0.15, 0.2};
    mesh_contacts(mesh, c, 0.3, grid.candidates(c), out);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].feature, MeshFeature::vertex);
    EXPECT_EQ(out[0].id, 7u);  // the same corner, moved
    EXPECT_EQ(out[0].point, (Vec3{3.0, 1.0, 1.0}));
}

// --- Welding and the checks ----------------------------------------------

TEST(MeshWalls, WeldingJoinsIdenticalCornersInOrderOfAppearance) {
    const TriangleMesh mesh = weld_triangles(std::vector<std::array<Vec3, 3>>{
        {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}}, {Vec3{1, 0, 0}, Vec3{1, 1, 0}, Vec3{0, 1, -0.0}}});
    ASSERT_EQ(mesh.vertices.size(), 4u);  // -0 is +0
    EXPECT_EQ(mesh.triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
    EXPECT_EQ(mesh.triangles[1], (std::array<std::uint32_t, 3>{1, 3, 2}));
    // A corner 1e-15 away is another vertex: exact equality only.
    EXPECT_EQ(weld_triangles(std::vector<std::array<Vec3, 3>>{{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}},
                                                              {Vec3{1e-15, 0, 0}, Vec3{1, 0, 0}, Vec3{0, -1, 0}}})
                  .vertices.size(),
              5u);
}

std::string refusal(const TriangleMesh& mesh) {
    try {
        check_mesh(mesh);
    } catch (const Error& e) {
        return e.what();
    }
    return "accepted";
}

TEST(MeshWalls, BadMeshesAreRefusedNamingTheTriangle) {
    const std::vector<Vec3> v{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}};
    EXPECT_EQ(refusal({v, {}}), "the mesh has no triangles");
    EXPECT_EQ(refusal({v, {{0, 1, 2}, {0, 1, 7}}}),
              "triangle 2: vertex id 7 is out of range (the mesh has 4 vertices)");
    EXPECT_EQ(refusal({v, {{0, 1, 1}}}), "triangle 1: uses a vertex twice (vertex ids 0, 1, 1)");
    EXPECT_EQ(refusal({v, {{0, 1, 2}, {0, 1, 3}}}),
              "triangle 2: degenerate: its area, 0 m^2, is not above 1e-12 times its longest edge squared, 4 m^2 "
              "(corners (0, 0, 0), (1, 0, 0), (2, 0, 0))");
    // Area 5e-13 against 1e-12 x 1 m^2: a sliver.
    EXPECT_NE(refusal({{{0, 0, 0}, {1, 0, 0}, {0.5, 1e-12, 0}}, {{0, 1, 2}}}).find("triangle 1: degenerate"),
              std::string::npos);
    EXPECT_EQ(refusal({v, {{0, 1, 2}, {3, 1, 2}, {2, 1, 0}}}),
              "triangle 3: repeats triangle 1 (the same three vertices): its forces would count twice");
    EXPECT_EQ(refusal({{{0, 0, 0}, {1, 0, 0}, {0, NAN, 0}}, {{0, 1, 2}}}),
              "triangle 1: corner 3 is not finite: (0, nan, 0)");
}

TEST(MeshWalls, MovingAMeshOntoADegenerateTriangleLeavesItUnchanged) {
    MeshTopology mesh(unit_box());
    std::vector<Vec3> flat(mesh.vertices().begin(), mesh.vertices().end());
    for (Vec3& p : flat) p.z = 0.0;  // the box squashed: its sides have no area
    EXPECT_THROW(mesh.set_vertices(flat), MeshError);
    EXPECT_EQ(mesh.vertices()[7], (Vec3{1.0, 1.0, 1.0}));
    EXPECT_EQ(mesh.face(0).normal, (Vec3{0.0, 0.0, -1.0}));
    EXPECT_THROW(mesh.set_vertices(std::vector<Vec3>(3)), Error);
    EXPECT_THROW(FacetGrid(0.0, 1.0), Error);
    EXPECT_THROW(FacetGrid(1.0, -1.0), Error);
    FacetGrid tiny(1e-9, 0.0);
    EXPECT_THROW(tiny.rebuild(mesh), Error);  // 1e27 cells
}

}  // namespace
}  // namespace tumble
