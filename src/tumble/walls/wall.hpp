// SPDX-License-Identifier: MIT
// Smooth analytic walls: an infinite plane, a rectangle, a disc, a
// cylinder and a cone, each of one material and optionally carried by a
// prescribed rigid motion (Scenario::motions). A sphere touches a wall where
// its centre comes nearer to the wall's surface than its radius; the wall is
// then a body of infinite mass and the sphere's partner in the contact law
// (contact/contact_law.hpp) like a flat box wall, with the Hertz radius of
// the wall's curvature there (below; docs/MODEL.md, "Walls").
//
// Every shape is described in its own frame at the moment its motion
// began (for a wall without motion, always): the caller turns the sphere's
// centre into that frame, asks wall_touch(), and turns the normal back.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "tumble/core/keyword.hpp"
#include "tumble/core/vec3.hpp"
#include "tumble/particles/rigid_motion.hpp"

namespace tumble {

enum class WallShape : std::uint8_t { plane, rectangle, disc, cylinder, cone, mesh };
inline constexpr std::array<Keyword<WallShape>, 6> wall_shapes{{
    {"plane", WallShape::plane, "an infinite plane; the grains on the side its normal points to"},
    {"rectangle", WallShape::rectangle, "a rectangle, touched from both sides and at its edges"},
    {"disc", WallShape::disc, "a disc or an annulus, touched from both sides and at its rims"},
    {"cylinder", WallShape::cylinder, "a cylinder's mantle, grains inside or outside, open at its ends"},
    {"cone", WallShape::cone, "a cone's (or a truncated cone's) mantle, grains inside or outside, open at its ends"},
    {"mesh", WallShape::mesh, "triangles from an STL file, touched from both sides of each face"},
}};

// What the user describes (plain data, in Scenario::walls). Lengths in m.
struct Wall {
    std::string name;
    WallShape shape = WallShape::plane;
    // plane: a point on it; rectangle and disc: the centre; cylinder and
    // cone: the point on the axis where the wall begins; mesh: the point
    // the torque of its load is taken about (its triangles are placed by
    // themselves, in Scenario::meshes).
    Vec3 point;
    // plane, rectangle, disc: the normal (an infinite plane's grains lie on
    // the side it points to; rectangles and discs are touched from both
    // sides); cylinder, cone: the axis, from `point` to the far end. Unit
    // length (the readers normalise it).
    Vec3 normal{0.0, 0.0, 1.0};
    // rectangle: the direction of its first pair of sides, in its plane
    // (unit, normal to `normal`); the second is normal x edge.
    Vec3 edge{1.0, 0.0, 0.0};
    double half_width = 0.0;   // rectangle: half its side along edge
    double half_height = 0.0;  // rectangle: half its side along normal x edge
    double radius = 0.0;       // disc; cylinder; cone at `point`
    double hole_radius = 0.0;  // disc: an annulus with a hole this wide about its centre (a silo's orifice)
    double end_radius = 0.0;   // cone at point + length normal
    // cylinder, cone: how far the wall reaches along the axis from `point`;
    // a cylinder may be infinite (then it has no rims).
    double length = std::numeric_limits<double>::infinity();
    bool inside = true;        // cylinder, cone: the grains move inside it (else outside)
    std::int32_t material = 0;
    std::int32_t motion = -1;  // index into Scenario::motions, or -1: at rest
    std::int32_t mesh = -1;    // mesh: index into Scenario::meshes (walls/mesh.hpp), else -1
};

// Reason why a wall cannot be simulated (a zero normal, a value not finite,
// a radius or size not positive, a cone of no length), or empty.
std::string wall_problem(const Wall& w);

// How a sphere's centre x (in the wall's frame) lies against the wall:
// `distance` from the nearest point of the wall's surface (m; negative where
// the centre has passed through an infinite plane, or through the mantle of a
// cylinder or cone to the grains' wrong side), `n` the unit normal from the
// wall towards the centre, and `curvature` (1/m) of the wall's surface there
// in the direction it curves most, > 0 where it is concave towards the
// sphere (the inside of a cylinder or cone), < 0 where convex, 0 on a flat
// face or a rim or edge.
struct WallTouch {
    double distance = std::numeric_limits<double>::infinity();
    Vec3 n;
    double curvature = 0.0;
};
// A mesh has no single touch (walls/mesh.hpp: mesh_contacts); for it
// wall_touch() gives an infinite distance.
WallTouch wall_touch(const Wall& w, const Vec3& x);

// The largest curvature (1/m, as in WallTouch) the wall's surface turns
// towards a grain anywhere: 1/R_c inside a cylinder, cos(alpha)/r at the
// narrower end inside a cone (infinite at a tip), else 0. The time step
// takes the wall's contacts at the R* it gives.
double largest_curvature(const Wall& w);

// A wall where its motion has carried it at one time: `now` is its motion
// then (particles/rigid_motion.hpp), or null for a wall at rest; `origin` where
// its `point` is (m).
struct PlacedWall {
    const Wall* wall = nullptr;
    const MotionNow* now = nullptr;
    Vec3 origin;
};
PlacedWall place_wall(const Wall& w, const MotionNow* now);

// The touch of a sphere's centre x (lab frame) with a placed wall, its
// normal in the lab frame, and the wall's surface velocity at the nearest
// point c = x - distance n (m/s: V + Omega u x (c - axis point)) and its
// angular velocity (rad/s: Omega u); zero for a wall at rest. The shape
// is evaluated in its frame at the start of its motion: x turned back by
// the rotation since and carried back by the translation.
struct WallContact {
    WallTouch touch;
    Vec3 velocity, angular_velocity;
};
WallContact wall_contact(const PlacedWall& w, const Vec3& x);

// The pieces of wall_contact() for a wall that gives its contacts by
// itself (a mesh): a lab point x carried into the wall's frame at the start
// of its motion, a direction of that frame turned into the lab frame, and
// the surface velocity and spin at a lab point of the wall (zero at rest).
Vec3 to_start_frame(const MotionNow* now, const Vec3& x);
Vec3 to_lab_direction(const MotionNow* now, const Vec3& v);
void surface_motion(const MotionNow* now, const Vec3& point, Vec3& velocity, Vec3& angular_velocity);

// The Hertz radius R* (m) of a sphere of radius R against a surface that
// curves by `curvature` (1/m, as in WallTouch) in one direction and not in
// the other (a cylinder, a cone; a plane where it is 0): the contact is an
// ellipse whose relative radii are R' = 1 / (1/R - curvature) and R'' = R,
// and the equivalent sphere has R* = sqrt(R' R'') (Johnson, Contact
// Mechanics, eq. 4.29), i.e. R* = R / sqrt(1 - curvature R). Where the wall
// curves more tightly than that holds (curvature R above 1/2 inside a
// hopper's orifice, below -1 about a cone's tip) R* is held at R sqrt(2)
// and R / sqrt(2).
inline double wall_contact_radius(double R, double curvature) {
    return R / std::sqrt(1.0 - std::clamp(curvature * R, -1.0, 0.5));
}

}  // namespace tumble
