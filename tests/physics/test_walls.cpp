// SPDX-License-Identifier: MIT
// Smooth analytic walls (walls/wall.hpp): the touch of each shape against
// hand-worked geometry, the Hertz radius of a curved wall in the engine's
// force, an infinite plane that is the box's flat wall to the last bit and
// the same wall tilted, a moving wall's surface velocity (a grain set
// rolling by a belt ends at 2/7 of its speed), a turned wall where its
// motion has carried it, and the load the grains put on a wall.
#include <gtest/gtest.h>

#include <cmath>

#include "io/config.hpp"
#include "physics_helpers.hpp"
#include "tumble/sim/time_step.hpp"
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
    cylinder.inside = false;
    expect_touch(wall_touch(cylinder, {1.8, 0.0, 1.0}), 0.8, {1, 0, 0}, -1.0, "cylinder, outside");

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
        if (pair.name == "material-2-drum (wall)") EXPECT_NEAR(pair.R_star, R_star, 1e-18);
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
