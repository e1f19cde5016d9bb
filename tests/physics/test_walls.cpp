// SPDX-License-Identifier: MIT
// Smooth analytic walls (walls/wall.hpp): the touch of each shape against
// hand-worked geometry, the Hertz radius of a curved wall in the engine's
// force, an infinite plane that is the box's flat wall to the last bit and
// the same wall tilted, a moving wall's surface velocity (a grain set
// rolling by a belt ends at 2/7 of its speed), a turned wall where its
// motion has carried it, a still wall touched where it lies, and the load the grains put on a wall. Mesh walls
// (walls/mesh.hpp) in the engine: a floor of triangles is the plane it
// tessellates, for a grain rolling and sliding over its edges and vertices,
// for an impact, as a belt, and turning about an axis. The examples with
// walls run as written: the hopper, the chute and the V-blender.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <utility>
#include <vector>

#include "io/config.hpp"
#include "physics_helpers.hpp"
#include "tumble/sim/time_step.hpp"
#include "tumble/walls/mesh.hpp"
#include "tumble/walls/wall.hpp"

namespace physics_test {
namespace {

using tumble::Wall;
using tumble::WallShape;
using tumble::WallTouch;

constexpr double g = 9.81;  // m/s^2
constexpr int wall_material = 2;

void expect_touch(const WallTouch& t, double distance, Vec3 n, double curvature, const char* what) {
    SCOPED_TRACE(what);
    EXPECT_NEAR(t.distance, distance, 1e-15);
    EXPECT_NEAR(t.n.x, n.x, 1e-15);
    EXPECT_NEAR(t.n.y, n.y, 1e-15);
    EXPECT_NEAR(t.n.z, n.z, 1e-15);
    EXPECT_NEAR(t.curvature, curvature, 1e-12);
}

Wall shape(WallShape kind) {
    Wall w;
    w.shape = kind;
    return w;
}

// Points worked by hand (3-4-5 triangles, so every number is exact to the
// last bit or two): faces, edges, corners, rims, the mantles inside and
// out, and the rim beyond a cylinder's end.
TEST(WallShapes, TouchOfEachShapeAtHandWorkedPoints) {
    const Wall plane = shape(WallShape::plane);
    expect_touch(wall_touch(plane, {1.0, 2.0, 0.5}), 0.5, {0, 0, 1}, 0.0, "plane, above");
    expect_touch(wall_touch(plane, {1.0, 2.0, -0.5}), -0.5, {0, 0, 1}, 0.0, "plane, behind: pushed back");

    Wall rectangle = shape(WallShape::rectangle);
    rectangle.half_width = 1.0;
    rectangle.half_height = 0.5;
    expect_touch(wall_touch(rectangle, {0.5, 0.2, -0.3}), 0.3, {0, 0, -1}, 0.0, "rectangle, face from below");
    expect_touch(wall_touch(rectangle, {1.3, 0.0, 0.4}), 0.5, {0.6, 0, 0.8}, 0.0, "rectangle, edge");
    expect_touch(wall_touch(rectangle, {1.3, 0.9, 0.0}), 0.5, {0.6, 0.8, 0}, 0.0, "rectangle, corner");

    Wall disc = shape(WallShape::disc);
    disc.radius = 1.0;
    expect_touch(wall_touch(disc, {0.3, 0.4, 0.25}), 0.25, {0, 0, 1}, 0.0, "disc, face");
    expect_touch(wall_touch(disc, {1.3, 0.0, 0.4}), 0.5, {0.6, 0, 0.8}, 0.0, "disc, rim");
    disc.hole_radius = 0.5;  // an annulus
    expect_touch(wall_touch(disc, {0.7, 0.0, -0.25}), 0.25, {0, 0, -1}, 0.0, "annulus, face from below");
    expect_touch(wall_touch(disc, {0.2, 0.0, 0.4}), 0.5, {-0.6, 0, 0.8}, 0.0, "annulus, the hole's rim");

    Wall cylinder = shape(WallShape::cylinder);
    cylinder.radius = 1.0;
    cylinder.length = 2.0;
    expect_touch(wall_touch(cylinder, {0.3, 0.4, 1.0}), 0.5, {-0.6, -0.8, 0}, 1.0, "cylinder, inside");
    expect_touch(wall_touch(cylinder, {0.7, 0.0, 2.4}), 0.5, {-0.6, 0, 0.8}, 0.0, "cylinder, beyond its end: the rim");
    // A finite mantle is a thin shell: a centre behind it (outside a
    // cylinder whose grains are inside) is pushed away from its outer face,
    // which curves the other way.
    expect_touch(wall_touch(cylinder, {1.8, 0.0, 1.0}), 0.8, {1, 0, 0}, -1.0, "cylinder, behind its mantle");
    cylinder.inside = false;
    expect_touch(wall_touch(cylinder, {1.8, 0.0, 1.0}), 0.8, {1, 0, 0}, -1.0, "cylinder, outside");
    expect_touch(wall_touch(cylinder, {0.3, 0.4, 1.0}), 0.5, {-0.6, -0.8, 0}, 1.0, "cylinder, behind from inside");
    cylinder.length = std::numeric_limits<double>::infinity();  // no rim to go round: one-sided
    expect_touch(wall_touch(cylinder, {0.3, 0.4, 1.0}), -0.5, {0.6, 0.8, 0}, -1.0, "infinite cylinder, behind");

    // A cone from radius 1 at s = 0 to a tip at s = 1 (half-angle 45
    // degrees). At (s, rho) = (0.3, 0.2) the nearest point of the meridian
    // rho = 1 - s is (0.55, 0.45), 0.25 sqrt(2) away along (-1, -1)/sqrt(2);
    // across the mantle it curves by cos(45 deg)/0.45 there.
    Wall cone = shape(WallShape::cone);
    cone.radius = 1.0;
    cone.end_radius = 0.0;
    cone.length = 1.0;
    const double r = std::sqrt(0.5);
    expect_touch(wall_touch(cone, {0.2, 0.0, 0.3}), 0.25 / r, {-r, 0, -r}, r / 0.45, "cone, inside");
    EXPECT_EQ(tumble::largest_curvature(cone), std::numeric_limits<double>::infinity());  // its tip
}

// The Hertz radius of a sphere of material 2 (R = 2.4 mm) inside the
// paper's drum (R_c = 4 cm): R sqrt(R_c / (R_c - R)), 3.1 % above R; in
// the engine's elastic force 4/3 E* sqrt(R*) h^(3/2), towards the axis.
TEST(WallShapes, TheEngineTakesTheCylindersHertzRadius) {
    const double R = R2, Rc = 0.04, h = 1e-4;
    const double R_star = R * std::sqrt(Rc / (Rc - R));
    EXPECT_NEAR(tumble::wall_contact_radius(R, 1.0 / Rc), R_star, 1e-18);
    EXPECT_NEAR(R_star / R, 1.0314, 1e-4);
    tumble::Scenario s = open_scenario(0.0);
    s.model.viscous = s.model.attraction = false;
    s.model.shear = tumble::ShearModel::Off;
    Wall drum = shape(WallShape::cylinder);
    drum.name = "drum";
    drum.radius = Rc;
    drum.point = {0.0, 0.0, -0.05};
    drum.length = 0.1;
    drum.material = wall_material;
    s.walls.push_back(drum);
    s.particles.push_back(sphere({0.0, -(Rc - R + h), 0.0}, R, 1));
    tumble::Simulation sim(s);
    const auto materials = paper_materials();
    const double expected = 4.0 / 3.0 * e_star(materials[1], materials[wall_material]) * std::sqrt(R_star) * std::pow(h, 1.5);
    const Vec3 F = sim.particles().force[0];
    report("elastic force inside the drum (N)", F.y, expected, 1e-12);
    EXPECT_LT(relative_difference(F.y, expected), 1e-12);
    EXPECT_EQ(F.x, 0.0);
    EXPECT_EQ(F.z, 0.0);
    // And the time step takes the wall's contact at that radius.
    for (const tumble::ContactPair& pair : tumble::contact_pairs(s))
        if (pair.name == "material-2-drum (wall)") {
            EXPECT_NEAR(pair.R_star, R_star, 1e-18);
        }
}

// A grain thrown at a slant with spin onto the floor and sliding along it:
// the box's flat wall at z = lo, or an infinite plane [[wall]] there.
tumble::Scenario thrown_grain(bool box_wall, Vec3 up) {
    tumble::Scenario s = open_scenario(0.0);
    s.model.shear = tumble::ShearModel::Spring;
    if (box_wall) {
        s.domain.walls = {false, false, true};
        s.domain.wall_material = wall_material;
    } else {
        Wall floor = shape(WallShape::plane);
        floor.name = "floor";
        floor.point = s.domain.lo.z * up;
        floor.normal = up;
        floor.material = wall_material;
        s.walls.push_back(floor);
    }
    s.gravity = -g * up;
    return s;
}

// The plane is the box's wall: the same numbers to the last bit.
TEST(Walls, AnInfinitePlaneIsTheBoxsFlatWall) {
    tumble::Scenario box = thrown_grain(true, {0, 0, 1}), plane = thrown_grain(false, {0, 0, 1});
    for (tumble::Scenario* s : {&box, &plane})
        s->particles.push_back(sphere({0.0, 0.0, -1.0 + R1 + 2e-4}, R1, 0, {0.3, 0.1, -0.2}, {5.0, -20.0, 3.0}));
    tumble::Simulation a(box), b(plane);
    for (int k = 0; k < 40; ++k) {
        a.advance(100);
        b.advance(100);
        ASSERT_EQ(a.particles().position[0], b.particles().position[0]) << "after " << 100 * (k + 1) << " steps";
        ASSERT_EQ(a.particles().velocity[0], b.particles().velocity[0]);
        ASSERT_EQ(a.particles().angular_velocity[0], b.particles().angular_velocity[0]);
    }
    EXPECT_LT(a.particles().position[0].z, -1.0 + R1);  // it came down and touched
}

// The same throw on a floor tilted by a turn about an oblique axis (and
// gravity turned with it) is the same motion turned: 1e-9 of the path.
TEST(Walls, ATiltedPlaneIsTheSamePlaneTurned) {
    const tumble::Rotation turn({0.6, 0.0, 0.8}, 0.7);
    const auto turned = [&](Vec3 v) { return tumble::rotate(v, turn); };
    tumble::Scenario flat = thrown_grain(false, {0, 0, 1}), tilted = thrown_grain(false, turned({0, 0, 1}));
    const Vec3 x{0.0, 0.0, -1.0 + R1 + 2e-4}, v{0.3, 0.1, -0.2}, w{5.0, -20.0, 3.0};
    flat.particles.push_back(sphere(x, R1, 0, v, w));
    tilted.particles.push_back(sphere(turned(x), R1, 0, turned(v), turned(w)));
    tumble::Simulation a(flat), b(tilted);
    ASSERT_EQ(a.dt(), b.dt());
    a.advance(4000);
    b.advance(4000);
    const Vec3 moved = a.particles().position[0] - x;
    const double path = tumble::norm(moved);
    EXPECT_GT(path, 0.02);
    EXPECT_LT(tumble::norm(b.particles().position[0] - turned(a.particles().position[0])), 1e-9 * path);
    EXPECT_LT(tumble::norm(b.particles().velocity[0] - turned(a.particles().velocity[0])), 1e-9);
    EXPECT_LT(tumble::norm(b.particles().angular_velocity[0] - turned(a.particles().angular_velocity[0])), 1e-6);
}

// A grain at rest on a belt that moves at V in its own plane: friction
// drives it until it rolls on the belt. The belt's force acts at the
// contact point, so the grain's angular momentum about that point,
// m R v_x + I w_y, stays 0; rolling, the contact point moves with the belt,
// v_x - w_y R = V; so v_x = V / (1 + m R^2 / I) = 2/7 V for a solid sphere.
// The belt's velocity enters the contact only through its motion.
TEST(Walls, AGrainOnAMovingBeltEndsAtTwoSeventhsOfItsSpeed) {
    const double V = 0.1;  // m/s
    tumble::Scenario s = thrown_grain(false, {0, 0, 1});
    s.model.attraction = false;
    s.motions.push_back({{}, {0.0, 0.0, 1.0}, 0.0, {V, 0.0, 0.0}});
    s.walls[0].motion = 0;
    const double m = sphere_mass(1000.0, R1);
    const double h = std::pow(m * g / (4.0 / 3.0 * e_star(paper_materials()[0], paper_materials()[wall_material]) *
                                       std::sqrt(R1)), 2.0 / 3.0);  // Hertz rest
    s.particles.push_back(sphere({0.0, 0.0, -1.0 + R1 - h}, R1, 0));
    tumble::Simulation sim(s);
    // Slip stops after 2 V / (7 mu g) = 15 ms; average the last 100 of 200 ms
    // (the undamped tangential spring rings about the rolling speed).
    const auto steps = static_cast<std::int64_t>(std::ceil(0.1 / sim.dt()));
    sim.advance(steps);
    double mean = 0.0;
    for (std::int64_t k = 0; k < steps; ++k) {
        sim.step();
        mean += sim.particles().velocity[0].x / static_cast<double>(steps);
    }
    // 2/7 for the lever R; with the force's lever L = R - h/2 (h = 12.6 um
    // here) it is 1 / (1 + 5/2 (L/R)^2), 2.5e-3 above 2/7. What is left is
    // the ringing spring's average over 100 ms.
    const double L = R1 - 0.5 * h, expected = 1.0 / (1.0 + 2.5 * (L / R1) * (L / R1));
    report("the grain's speed / the belt's vs 1 / (1 + 5/2 (L/R)^2)", mean / V, expected, 1e-4);
    EXPECT_LT(relative_difference(mean / V, expected), 1e-4);  // measured 9e-6
    EXPECT_GT(relative_difference(mean / V, 2.0 / 7.0), 1e-3);  // the lever's share shows
}

// A rectangle turned a quarter turn about z by its motion is the rectangle
// placed there: the same touch, to round-off, and the surface moves at
// Omega z x (c - axis point).
TEST(Walls, ATurnedWallIsWhereItsMotionCarriedIt) {
    Wall paddle = shape(WallShape::rectangle);
    paddle.point = {0.5, 0.0, 0.0};
    paddle.normal = {1.0, 0.0, 0.0};
    paddle.edge = {0.0, 1.0, 0.0};
    paddle.half_width = 0.2;
    paddle.half_height = 0.3;
    const double omega = 2.0;
    const tumble::MotionNow now{{}, {}, {}, tumble::Rotation({0.0, 0.0, 1.0}, 0.5 * pi), omega};
    Wall there = paddle;
    there.point = {0.0, 0.5, 0.0};
    there.normal = {0.0, 1.0, 0.0};
    there.edge = {-1.0, 0.0, 0.0};
    const tumble::PlacedWall placed = tumble::place_wall(paddle, &now);
    EXPECT_LT(tumble::norm(placed.origin - there.point), 1e-15);
    for (const Vec3 x : {Vec3{0.1, 0.7, 0.05}, Vec3{0.3, 0.4, -0.2}, Vec3{-0.1, 0.6, 0.5}}) {
        const tumble::WallContact c = tumble::wall_contact(placed, x);
        const WallTouch expected = tumble::wall_touch(there, x);
        EXPECT_NEAR(c.touch.distance, expected.distance, 1e-15);
        EXPECT_LT(tumble::norm(c.touch.n - expected.n), 1e-15);
        const Vec3 point = x - c.touch.distance * c.touch.n;
        EXPECT_LT(tumble::norm(c.velocity - tumble::cross({0.0, 0.0, omega}, point)), 1e-15);
        EXPECT_EQ(c.angular_velocity, (Vec3{0.0, 0.0, omega}));
    }
}

// A wall whose motion leaves its surface in place (a drum's mantle and cap
// turning about their axis, a plane about its normal, after a translation
// that has stopped) is still: touched where it lies, in the lab frame, it
// gives the touch found in its own frame and turned forward, to round-off
// (1e-15 m on distances of order 1 m; 4e-15 on the unit normal, a few
// units of the last place, 2.2e-16, from turning there and back), with
// the surface velocity
// Omega u x (c - axis point). A cylinder tilted off the motion's axis, or
// turned about a parallel axis, is not still; nor is a rectangle a motion
// has turned, whose edge only its own frame knows.
TEST(Walls, AStillWallIsTouchedWhereItLies) {
    const Vec3 u{0.0, 0.6, 0.8};  // unit to round-off
    const double omega = 3.0;
    // The axis began through (0.1, 0.2, 0.3) and has since been carried to
    // (0.4, 0.2, 0.3), then turned 1.1 rad about.
    const tumble::MotionNow now{{0.1, 0.2, 0.3}, {0.4, 0.2, 0.3}, {}, tumble::Rotation(u, 1.1), omega};
    Wall mantle = shape(WallShape::cylinder);
    mantle.point = {0.1, 0.2, 0.3};  // on the axis exactly (stays_put() asks it to the bit)
    mantle.normal = u;
    mantle.radius = 0.4;
    mantle.length = 1.0;
    Wall cap = shape(WallShape::disc);
    cap.point = mantle.point;
    cap.normal = u;
    cap.radius = 0.4;
    Wall plane = shape(WallShape::plane);
    plane.point = {0.7, -0.3, 0.2};
    plane.normal = -u;
    for (const Wall* w : {&mantle, &cap, &plane}) {
        const tumble::PlacedWall placed = tumble::place_wall(*w, &now);
        ASSERT_TRUE(placed.still);
        for (const Vec3 x : {Vec3{0.5, 0.3, 0.1}, Vec3{0.2, -0.1, 0.4}, Vec3{0.6, 0.1, 0.0}}) {
            const tumble::WallContact c = tumble::wall_contact(placed, x);
            const WallTouch framed = tumble::wall_touch(*w, tumble::to_start_frame(&now, x));
            EXPECT_NEAR(c.touch.distance, framed.distance, 1e-15);
            EXPECT_LT(tumble::norm(c.touch.n - tumble::to_lab_direction(&now, framed.n)), 4e-15);
            EXPECT_EQ(c.touch.curvature, framed.curvature);
            const Vec3 point = x - c.touch.distance * c.touch.n;
            EXPECT_LT(tumble::norm(c.velocity - tumble::cross(omega * u, point - now.axis_point)), 4e-15);
        }
    }
    Wall tilted = mantle;
    tilted.normal = {0.0, 0.0, 1.0};
    EXPECT_FALSE(tumble::place_wall(tilted, &now).still);
    Wall beside = mantle;
    beside.point = mantle.point + Vec3{0.05, 0.0, 0.0};
    EXPECT_FALSE(tumble::place_wall(beside, &now).still);
    tumble::MotionNow sliding = now;
    sliding.velocity = {0.0, 0.0, 0.01};
    EXPECT_FALSE(tumble::place_wall(mantle, &sliding).still);
    // A rectangle turned by a motion that has since stopped: its edge has
    // turned too, so it is touched in its own frame, where it is right.
    tumble::MotionNow stopped = now;
    stopped.angular_velocity = 0.0;
    Wall gate = shape(WallShape::rectangle);
    gate.point = {0.1, 0.2, 0.3};
    gate.normal = {1.0, 0.0, 0.0};
    gate.edge = {0.0, 1.0, 0.0};
    gate.half_width = 0.05;
    gate.half_height = 0.5;
    const tumble::PlacedWall placed_gate = tumble::place_wall(gate, &stopped);
    EXPECT_FALSE(placed_gate.still);
    const Vec3 x{0.3, 0.3, 0.3};
    const WallTouch framed = tumble::wall_touch(gate, tumble::to_start_frame(&stopped, x));
    EXPECT_EQ(tumble::wall_contact(placed_gate, x).touch.distance, framed.distance);
}

// A grain resting on a plane wall, off its point: the wall carries the
// grain's weight, F = -m g z, and its moment about the wall's point,
// (x - point) x F, within the settling's residue.
TEST(Walls, TheLoadOnAWallIsTheWeightItCarries) {
    tumble::Scenario s = thrown_grain(false, {0, 0, 1});
    s.walls[0].point = {0.01, 0.0, -1.0};  // the load's moment about it
    s.particles.push_back(sphere({0.03, 0.0, -1.0 + R1}, R1, 0));
    tumble::Simulation sim(s);
    sim.advance(static_cast<std::int64_t>(0.2 / sim.dt()));
    const std::vector<tumble::WallLoad> loads = sim.wall_loads();
    ASSERT_EQ(loads.size(), 1u);
    const double weight = sphere_mass(1000.0, R1) * g;
    report("the wall's load (N)", -loads[0].force.z, weight, 1e-6);
    EXPECT_LT(relative_difference(-loads[0].force.z, weight), 1e-6);
    EXPECT_LT(std::hypot(loads[0].force.x, loads[0].force.y), 1e-9 * weight);
    // (0.02, 0, 0) x (0, 0, -m g) = (0, 0.02 m g, 0).
    EXPECT_LT(relative_difference(loads[0].torque.y, 0.02 * weight), 1e-6);
}


// ---- Mesh walls ----------------------------------------------------------

// A square of n x n squares of side a from `corner` in the plane z =
// corner.z, each split in two along its diagonal: 2 n^2 triangles, their
// normals +z.
tumble::TriangleMesh grid_floor(Vec3 corner, double a, int n) {
    tumble::TriangleMesh m;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) m.vertices.push_back({corner.x + i * a, corner.y + j * a, corner.z});
    const auto at = [n](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return m;
}

// The scenario with its plane wall 0 made a mesh: the grid in its plane.
tumble::Scenario on_mesh(tumble::Scenario s, tumble::TriangleMesh grid) {
    s.walls[0].shape = WallShape::mesh;
    s.walls[0].mesh = 0;
    s.meshes = {std::move(grid)};
    return s;
}

// The largest normal force of the grain's wall contacts in the last step,
// and how many there were.
std::pair<double, std::size_t> wall_normal_force(const tumble::Simulation& sim) {
    double largest = 0.0;
    std::size_t count = 0;
    for (const tumble::ContactRecord& r : sim.contact_records())
        if (r.id_j < 0) largest = std::max(largest, r.forces.normal_force), ++count;
    return {largest, count};
}

// A grain thrown at a slant with spin onto a floor of 200 triangles (5 mm
// squares) from above a vertex, sliding, then rolling, across the edges
// along x, along y and along the diagonals, and over vertices: the plane's
// path to round-off. With the "spring" shear model the tangential spring
// is carried from facet to facet; a spring lost at an edge would change
// the path by far more than round-off, and a contact counted twice on an
// edge would double the normal force there.
TEST(MeshWalls, AGrainRollingOverTrianglesFollowsThePlane) {
    tumble::Scenario plane = thrown_grain(false, {0, 0, 1});
    plane.particles.push_back(sphere({0.0, 0.0, -1.0 + R1 + 2e-4}, R1, 0, {0.3, 0.1, -0.2}, {5.0, -20.0, 3.0}));
    const double a = 5e-3;
    const tumble::Scenario mesh = on_mesh(plane, grid_floor({-2 * a, -2 * a, -1.0}, a, 10));
    ASSERT_EQ(mesh.meshes[0].triangles.size(), 200u);
    tumble::Simulation A(plane), B(mesh);
    A.set_contact_recording(true);
    B.set_contact_recording(true);
    ASSERT_EQ(A.dt(), B.dt());
    double path = 0.0, largest_A = 0.0, largest_B = 0.0, worst = 0.0;
    std::size_t touching = 0;
    Vec3 last = A.particles().position[0];
    for (int k = 0; k < 4000; ++k) {
        A.step();
        B.step();
        const auto [fa, na] = wall_normal_force(A);
        const auto [fb, nb] = wall_normal_force(B);
        ASSERT_EQ(na, nb) << "step " << k << ": one contact on the plane, one on the mesh";
        touching += na;
        largest_A = std::max(largest_A, fa);
        largest_B = std::max(largest_B, fb);
        path += tumble::norm(A.particles().position[0] - last);
        last = A.particles().position[0];
        worst = std::max(worst, tumble::norm(B.particles().position[0] - A.particles().position[0]));
    }
    const Vec3 end = A.particles().position[0];
    // It crossed the grid's lines: 1 cm or more along x over 5 mm squares.
    EXPECT_GT(end.x, 2 * a);
    EXPECT_LT(end.x, 8 * a);  // and stayed on the mesh
    EXPECT_LT(std::abs(end.y), 8 * a);
    EXPECT_GT(touching, 3000u);
    std::printf("  [measured] largest distance of the mesh's path from the plane's: %.3g m over a path of %.3g m\n",
                worst, path);
    // Round-off at most (the overlap as R - |d| on the mesh against d . n
    // on the plane; near d = R both subtractions are exact, so here the
    // paths agree to the bit), not the facets.
    EXPECT_LT(worst, 1e-12 * path);
    report("largest normal force on the mesh (N) vs on the plane", largest_B, largest_A, 1e-9);
    EXPECT_LT(relative_difference(largest_B, largest_A), 1e-9);  // no spike at an edge or vertex
    EXPECT_LT(tumble::norm(B.particles().angular_velocity[0] - A.particles().angular_velocity[0]),
              1e-9 * tumble::norm(A.particles().angular_velocity[0]));
}

// A grain dropped straight onto a face of the mesh, off its edges: the
// plane's restitution and contact time (the same steps in contact, the
// rebound speed to round-off).
TEST(MeshWalls, AnImpactOnAFaceIsThePlanes) {
    tumble::Scenario plane = thrown_grain(false, {0, 0, 1});
    plane.gravity = {};
    plane.model.attraction = false;  // so that it comes off
    const double v = 0.5;
    plane.particles.push_back(sphere({1.3e-3, 2.1e-3, -1.0 + R1 + 1e-4}, R1, 0, {0.0, 0.0, -v}));
    const tumble::Scenario mesh = on_mesh(plane, grid_floor({-0.05, -0.05, -1.0}, 0.01, 10));
    tumble::Simulation A(plane), B(mesh);
    A.set_contact_recording(true);
    B.set_contact_recording(true);
    std::int64_t steps_A = 0, steps_B = 0;
    for (int k = 0; k < 3000; ++k) {
        A.step();
        B.step();
        steps_A += static_cast<std::int64_t>(wall_normal_force(A).second);
        steps_B += static_cast<std::int64_t>(wall_normal_force(B).second);
    }
    ASSERT_GT(steps_A, 20);  // the contact was resolved in many steps
    EXPECT_EQ(steps_B, steps_A);  // the contact time to the step
    const double e_A = A.particles().velocity[0].z / v, e_B = B.particles().velocity[0].z / v;
    std::printf("  [measured] restitution %.4f, %lld steps in contact\n", e_A, static_cast<long long>(steps_A));
    ASSERT_GT(e_A, 0.01);  // it came off (the paper's grains are nearly plastic: 0.02 at 0.5 m/s)
    report("restitution on the mesh vs on the plane", e_B, e_A, 1e-12);
    EXPECT_LT(relative_difference(e_B, e_A), 1e-12);  // round-off
    EXPECT_LT(std::hypot(B.particles().velocity[0].x, B.particles().velocity[0].y), 1e-12 * v);  // straight back up
}

// The belt of Walls.AGrainOnAMovingBeltEndsAtTwoSeventhsOfItsSpeed made of
// triangles (2 cm squares): the mesh moves with its motion (its surface
// velocity in the contact), and the grain ends at the plane's speed.
TEST(MeshWalls, AGrainOnAMovingMeshBeltEndsAtTwoSeventhsOfItsSpeed) {
    const double V = 0.1;  // m/s
    tumble::Scenario plane = thrown_grain(false, {0, 0, 1});
    plane.model.attraction = false;
    plane.motions.push_back({{}, {0.0, 0.0, 1.0}, 0.0, {V, 0.0, 0.0}});
    plane.walls[0].motion = 0;
    const double m = sphere_mass(1000.0, R1);
    const double h = std::pow(m * g / (4.0 / 3.0 * e_star(paper_materials()[0], paper_materials()[wall_material]) *
                                       std::sqrt(R1)), 2.0 / 3.0);  // Hertz rest
    plane.particles.push_back(sphere({1e-3, 3e-3, -1.0 + R1 - h}, R1, 0));
    // The belt carries 2 cm in 0.2 s under the grain, which moves 2/7 of it.
    const tumble::Scenario mesh = on_mesh(plane, grid_floor({-0.1, -0.1, -1.0}, 0.02, 10));
    tumble::Simulation A(plane), B(mesh);
    const auto steps = static_cast<std::int64_t>(std::ceil(0.1 / B.dt()));
    A.advance(steps);
    B.advance(steps);
    double mean = 0.0;
    for (std::int64_t k = 0; k < steps; ++k) {
        B.step();
        mean += B.particles().velocity[0].x / static_cast<double>(steps);
    }
    A.advance(steps);
    const double L = R1 - 0.5 * h, expected = 1.0 / (1.0 + 2.5 * (L / R1) * (L / R1));  // as for the plane
    report("the grain's speed / the mesh belt's vs 1 / (1 + 5/2 (L/R)^2)", mean / V, expected, 5e-4);
    EXPECT_LT(relative_difference(mean / V, expected), 5e-4);
    // And it is where the plane's grain is, to round-off over 0.2 s.
    EXPECT_LT(tumble::norm(B.particles().position[0] - A.particles().position[0]), 1e-12);
}

// A grain sliding and spinning along a V groove: two analytic planes at 45
// degrees (two walls, a history each), or the groove made of triangles (160
// of them, 2.5 mm along the crease: two face contacts at every step, their
// features changing as the grain moves on). Each contact's spring must
// follow it to its next face on the same side, not to the other side's
// face that shares a vertex of the crease with it (handed to the first
// old slot whose feature shares any vertex, the springs swap at every
// other station, and the grain ends 4e-5 m off); then the grain takes
// the planes' path to round-off (the faces' normals, from cross products,
// may differ from the planes' in the last bit).
TEST(MeshWalls, AGrainSlidingAlongATriangulatedVFollowsTheTwoPlanes) {
    tumble::Scenario planes = thrown_grain(false, {0, 0, 1});
    const double r = std::sqrt(0.5), z0 = -0.5;
    planes.walls[0].point = {0.0, 0.0, z0};
    planes.walls[0].normal = {0.0, -r, r};  // the side rising towards +y
    Wall other = planes.walls[0];
    other.name = "other side";
    other.normal = {0.0, r, r};
    planes.walls.push_back(other);
    planes.particles.push_back(
        sphere({0.0, 0.0, z0 + R1 / r - 1e-6}, R1, 0, {0.3, 0.02, 0.0}, {5.0, -20.0, 3.0}));
    tumble::Scenario mesh = planes;
    mesh.walls.pop_back();
    tumble::TriangleMesh groove;
    const int segments = 40;
    const double x0 = -0.02, step = 2.5e-3, w = 0.01;
    for (int i = 0; i <= segments; ++i) {  // per station: the crease, side A (+y), side B (-y)
        const double x = x0 + i * step;
        groove.vertices.push_back({x, 0.0, z0});
        groove.vertices.push_back({x, w, z0 + w});
        groove.vertices.push_back({x, -w, z0 + w});
    }
    for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(segments); ++i) {
        const std::uint32_t c = 3 * i, a = c + 1, b = c + 2, c1 = c + 3, a1 = c + 4, b1 = c + 5;
        const std::array<std::uint32_t, 3> side_a[2] = {{c, c1, a1}, {c, a1, a}}, side_b[2] = {{c, b1, c1}, {c, b, b1}};
        // Side A's faces first in even segments, side B's in odd ones: the
        // contacts come in another order than their slots at every other
        // station, where a new face shares a vertex of the crease with the
        // other side's old face.
        for (const auto* side : i % 2 == 0 ? std::array{side_a, side_b} : std::array{side_b, side_a})
            for (int k = 0; k < 2; ++k) groove.triangles.push_back(side[k]);
    }
    mesh = on_mesh(mesh, groove);
    tumble::Simulation A(planes), B(mesh);
    A.set_contact_recording(true);
    B.set_contact_recording(true);
    double path = 0.0, worst = 0.0;
    std::size_t both = 0;
    Vec3 last = A.particles().position[0];
    for (int k = 0; k < 4000; ++k) {
        A.step();
        B.step();
        const std::size_t na = wall_normal_force(A).second, nb = wall_normal_force(B).second;
        ASSERT_EQ(na, nb) << "step " << k;
        both += na == 2;
        path += tumble::norm(A.particles().position[0] - last);
        last = A.particles().position[0];
        worst = std::max(worst, tumble::norm(B.particles().position[0] - A.particles().position[0]));
    }
    std::printf("  [measured] largest distance of the mesh's path from the planes': %.3g m over a path of %.3g m\n",
                worst, path);
    EXPECT_GT(both, 3000u);  // in the V, touching both sides
    EXPECT_GT(A.particles().position[0].x, 4 * step);  // over several segments
    EXPECT_LT(A.particles().position[0].x, x0 + segments * step - 2 * R1);  // and still on the mesh
    EXPECT_LT(worst, 1e-9 * path);
}

// A mesh plate turned by its motion is where the motion carried it: a
// grain resting on a triangulated floor turning about the vertical axis
// through a point off the grain feels the plate's surface velocity, as on
// the analytic plane turning the same way (the same path to round-off).
TEST(MeshWalls, ATurningMeshIsTheTurningPlane) {
    tumble::Scenario plane = thrown_grain(false, {0, 0, 1});
    plane.motions.push_back({{0.01, -0.02, 0.0}, {0.0, 0.0, 1.0}, 3.0, {}});
    plane.walls[0].motion = 0;
    plane.particles.push_back(sphere({0.0, 0.0, -1.0 + R1 + 1e-5}, R1, 0, {0.02, 0.0, 0.0}));
    const tumble::Scenario mesh = on_mesh(plane, grid_floor({-0.05, -0.06, -1.0}, 0.01, 10));
    tumble::Simulation A(plane), B(mesh);
    A.advance(3000);
    B.advance(3000);
    const double moved = tumble::norm(A.particles().position[0] - Vec3{0.0, 0.0, -1.0 + R1});
    EXPECT_GT(moved, 1e-3);  // the plate carried it along
    std::printf("  [measured] distance of the mesh's grain from the plane's: %.3g m after %.3g m\n",
                tumble::norm(B.particles().position[0] - A.particles().position[0]), moved);
    EXPECT_LT(tumble::norm(B.particles().position[0] - A.particles().position[0]), 1e-10 * moved);
}

}  // namespace
}  // namespace physics_test

namespace physics_test {
namespace {

// examples/hopper.toml for 0.3 s: the beads, placed inside the cone by the
// fill, flow out through the orifice and none passes through the mantle:
// every bead still above the orifice lies inside the cone. A bead that had
// passed through would overlap it by more than its radius; the deepest
// contact measured, at the orifice's rim, is 0.10 of a radius (soft beads,
// E = 5 MPa, squeezed by the flow against a sharp edge).
TEST(Walls, TheExampleHopperDischargesThroughItsOrificeOnly) {
    const tumble::io::RunConfig c = tumble::io::load_run_config(std::string(TUMBLE_SOURCE_DIR) + "/examples/hopper.toml");
    const Wall& cone = c.scenario.walls.at(0);
    ASSERT_EQ(cone.shape, WallShape::cone);
    tumble::Simulation sim(c.scenario);
    sim.advance(static_cast<std::int64_t>(0.3 / sim.dt()));
    const tumble::ParticleStore& p = sim.particles();
    std::size_t out = 0;
    double deepest = 0.0;  // the largest overlap with the cone, over the radius
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (p.position[i].z < -p.radius[i]) {
            ++out;
            continue;
        }
        deepest = std::max(deepest, 1.0 - tumble::wall_touch(cone, p.position[i]).distance / p.radius[i]);
    }
    std::printf("  [measured] %zu of %zu beads out after 0.3 s; deepest overlap with the cone %.3g of a radius\n", out,
                p.size(), deepest);
    // Flowing: Beverloo's law, C rho_b sqrt(g) (D0 - k d)^(5/2) with C = 0.58,
    // k = 1.5, rho_b = 0.6 rho, gives about 320 beads a second through the
    // 16 mm orifice, about 100 in 0.3 s less the start.
    EXPECT_GT(out, 30u);
    EXPECT_LT(deepest, 0.25);
}

}  // namespace
}  // namespace physics_test

namespace physics_test {
namespace {

// The deepest overlap of the spheres with a mesh, over their radii
// (mesh_contacts with every face a candidate: the examples' meshes are
// small); `frame` carries a lab centre into the mesh's frame at the start
// of its motion.
template <class Frame>
double deepest_mesh_overlap(const tumble::MeshTopology& mesh, const tumble::ParticleStore& p, Frame frame) {
    std::vector<std::uint32_t> faces;
    for (std::uint32_t f = 0; f < mesh.face_count(); ++f) faces.push_back(f);
    std::vector<tumble::MeshContact> contacts;
    double deepest = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        tumble::mesh_contacts(mesh, frame(p.position[i]), p.radius[i], faces, contacts);
        for (const tumble::MeshContact& k : contacts) deepest = std::max(deepest, k.overlap / p.radius[i]);
    }
    return deepest;
}

// examples/chute.toml for 0.5 s: 500 beads fall onto a trough of triangles
// (examples/meshes/chute.stl) tilted 28 degrees, roll down it and leave its
// lip. Measured with the example's numbers: none passes through the chute
// (no bead beneath its base; the deepest overlap with it over the whole run
// 0.075 of a radius, at the impacts of the pour) or the floor; 479 of the
// 500 past the lip at 0.5 s; from 0.35 s on, once the pour has landed,
// the chute carries 0.86 of the weight of the beads on it.
TEST(Walls, TheExampleChuteCarriesItsBeadsOverItsLip) {
    const tumble::io::RunConfig c = tumble::io::load_run_config(std::string(TUMBLE_SOURCE_DIR) + "/examples/chute.toml");
    ASSERT_EQ(c.scenario.walls.at(0).shape, WallShape::mesh);
    ASSERT_EQ(c.scenario.walls.at(1).shape, WallShape::plane);
    // The trough as the example places it: from its upper end at (0, 0,
    // 0.1) m down the slope `down`, its base's normal `up`; 0.2 m long,
    // 30 mm wide, side walls 25 mm high.
    const double theta = 28.0 * pi / 180.0, length = 0.2, half_width = 0.015, height = 0.025;
    const Vec3 top{0.0, 0.0, 0.1};
    const Vec3 down{std::cos(theta), 0.0, -std::sin(theta)}, up{std::sin(theta), 0.0, std::cos(theta)};
    const double floor_z = c.scenario.walls[1].point.z;
    double lowest = 1.0;  // the mesh is where these say: its lowest vertices are the lip's
    for (const Vec3& v : c.scenario.meshes.at(0).vertices) lowest = std::min(lowest, v.z);
    ASSERT_NEAR(lowest, top.z - length * std::sin(theta), 1e-6);
    const tumble::MeshTopology chute(c.scenario.meshes[0]);

    tumble::Simulation sim(c.scenario);
    // Samples every 0.002 s from 0.1 s; from 0.35 s, once the pour has
    // landed, every step, for the mean load (the beads rattle: the load of
    // one step is anything from 0.2 to 2 times its mean).
    const std::int64_t sample = std::max<std::int64_t>(1, std::llround(0.002 / sim.dt()));
    const std::int64_t averaged_from = std::llround(0.35 / sim.dt()), end = std::llround(0.5 / sim.dt());
    std::int64_t step = std::llround(0.1 / sim.dt());
    sim.advance(step);
    std::size_t beneath = 0;  // beads found beneath the base, over all samples to 0.4 s
    double deepest = 0.0, load = 0.0, weight = 0.0;  // N, summed over the steps from 0.35 s
    while (step < end) {
        const std::int64_t n = step < averaged_from ? std::min(sample, averaged_from - step) : 1;
        sim.advance(n);
        step += n;
        const double t = sim.time();
        const tumble::ParticleStore& p = sim.particles();
        double on_chute = 0.0;  // N: the weight of the beads in the trough
        for (std::size_t i = 0; i < p.size(); ++i) {
            const Vec3 d = p.position[i] - top;
            const double along = dot(d, down), above = dot(d, up);
            if (along >= 0.0 && along <= length && std::abs(d.y) < half_width && above > 0.0 && above < height)
                on_chute += p.mass[i] * g;
            // Beneath the base: seen from above over it, and below it by a
            // quarter of a radius. (After 0.4 s beads bounce back from the
            // floor under the lip.)
            if (t <= 0.4 && d.x > 0.0 && d.x < length * std::cos(theta) && std::abs(d.y) < half_width &&
                above < -0.25 * p.radius[i])
                ++beneath;
        }
        if (step % sample == 0)
            deepest = std::max(deepest, deepest_mesh_overlap(chute, p, [](const Vec3& x) { return x; }));
        if (step > averaged_from) {
            load -= sim.wall_loads()[0].force.z;  // the force the beads put on the chute, downwards
            weight += on_chute;
        }
    }
    const tumble::ParticleStore& p = sim.particles();
    std::size_t past = 0, below_floor = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (dot(p.position[i] - top, down) > length) ++past;
        if (p.position[i].z < floor_z + 0.75 * p.radius[i]) ++below_floor;
    }
    std::printf("  [measured] t = %.3g s: %zu of %zu beads past the lip, %zu below the floor, %zu samples of a bead "
                "beneath the chute; deepest overlap with it %.3g of a radius; its load / the weight on it %.3g\n",
                sim.time(), past, p.size(), below_floor, beneath, deepest, load / weight);
    EXPECT_EQ(beneath, 0u);
    EXPECT_EQ(below_floor, 0u);
    EXPECT_LT(deepest, 0.25);  // as the hopper's: soft beads, impacts of 1.3 m/s
    // The last beads land by about 0.15 s some 5 cm down the chute; rolling
    // from rest at (5/7) g sin(28 deg) = 3.3 m/s^2 they cover the 15 cm left
    // in 0.3 s: by 0.5 s all are past the lip but the few a bounce sent over
    // a side wall or off the upper end.
    EXPECT_GT(past, p.size() * 8 / 10);
    // A bead running down the slope with acceleration a presses on it with
    // m (g - a sin(theta)) downwards: between cos^2(theta) = 0.78 of its
    // weight (sliding without friction) and 1 (at rest); rolling without
    // slip, a = (5/7) g sin(theta), 0.84.
    EXPECT_GT(load / weight, 0.75);
    EXPECT_LT(load / weight, 1.0);
}

// examples/v_blender.toml for a quarter turn (0.5 s): 1274 beads of two
// sizes in a closed V of two tubes of triangles (examples/meshes/
// v_blender.stl) turning at pi rad/s. Every bead stays inside the tubes:
// measured with the example's numbers, the nearest comes 0.96 of its
// radius from the round tube (whose facets lie up to 0.12 mm inside it),
// and the deepest overlap with the mesh at the end is 0.012 of a radius.
// Over the second eighth of the turn the blender carries the beads'
// weight: the mean vertical load 1.005 of it.
TEST(Walls, TheExampleVBlenderKeepsItsBeadsInItsTubes) {
    const tumble::io::RunConfig c =
        tumble::io::load_run_config(std::string(TUMBLE_SOURCE_DIR) + "/examples/v_blender.toml");
    const Wall& blender = c.scenario.walls.at(0);
    ASSERT_EQ(blender.shape, WallShape::mesh);
    ASSERT_GE(blender.motion, 0);
    const tumble::RigidMotion& turning = c.scenario.motions.at(static_cast<std::size_t>(blender.motion));
    ASSERT_NEAR(turning.unit_axis().x, 1.0, 1e-12);  // about x: the turn back below is written for it
    const double omega = turning.angular_velocity;
    const tumble::MeshTopology mesh(c.scenario.meshes.at(static_cast<std::size_t>(blender.mesh)));
    // Where a lab point was at the start: turned back by omega t about the axis.
    const auto start_frame = [&](const Vec3& x, double t) {
        const Vec3 d = x - turning.axis_point;
        const double a = -omega * t, ca = std::cos(a), sa = std::sin(a);
        return turning.axis_point + Vec3{d.x, ca * d.y - sa * d.z, sa * d.y + ca * d.z};
    };
    // The round tubes the mesh is drawn on (examples/meshes/make_meshes.py):
    // the apex at the origin, the arms' axes at 40 degrees either side of
    // +z in the x-z plane, 25 mm in radius, 0.1 m from the apex to the end
    // caps, mitred in the plane x = 0. The clearance of a point in the start
    // frame from the mantle and the end of the arm on its side, > 0 inside.
    const double radius = 0.025, arm = 0.1, alpha = 40.0 * pi / 180.0;
    const Vec3 u{std::sin(alpha), 0.0, std::cos(alpha)};
    const auto clearance = [&](const Vec3& q) {
        const Vec3 x{std::abs(q.x), q.y, q.z};
        const double s = dot(x, u);
        return std::min(radius - norm(x - s * u), arm - s);
    };

    tumble::Simulation sim(c.scenario);
    const tumble::ParticleStore& p = sim.particles();
    double weight = 0.0;  // N
    for (std::size_t i = 0; i < p.size(); ++i) weight += p.mass[i] * g;
    sim.advance(std::llround(0.25 / sim.dt()));
    const std::int64_t sample = std::max<std::int64_t>(1, std::llround(0.005 / sim.dt()));
    std::size_t outside = 0;  // beads more than a quarter of their radius into the round tube's wall, over the samples
    double nearest = 1e300, load = 0.0;
    for (int k = 0; k < 50; ++k) {
        sim.advance(sample);
        const tumble::ParticleStore& q = sim.particles();
        for (std::size_t i = 0; i < q.size(); ++i) {
            const double ratio = clearance(start_frame(q.position[i], sim.time())) / q.radius[i];
            nearest = std::min(nearest, ratio);
            if (ratio < 0.75) ++outside;
        }
        load -= sim.wall_loads()[0].force.z;
    }
    const double t = sim.time();
    const double deepest =
        deepest_mesh_overlap(mesh, sim.particles(), [&](const Vec3& x) { return start_frame(x, t); });
    std::printf("  [measured] after %.3g of a turn: %zu samples of a bead outside the tubes; nearest bead to the "
                "round tube %.3g of its radius; deepest overlap with the mesh %.3g of a radius; mean load / weight "
                "%.4g\n",
                omega * t / (2.0 * pi), outside, nearest, deepest, load / 50.0 / weight);
    EXPECT_EQ(sim.particles().size(), c.scenario.particles.size());
    EXPECT_EQ(outside, 0u);
    EXPECT_LT(deepest, 0.25);
    // The beads have settled against the turning wall: their centre of mass
    // hardly accelerates, so the wall carries their weight, to the
    // fluctuation of their sliding and collisions.
    EXPECT_NEAR(load / 50.0 / weight, 1.0, 0.1);
}

}  // namespace
}  // namespace physics_test
