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
// centre into that frame, asks wall_touch(), and turns the normal back;
// a wall whose motion leaves its surface in place (a drum's mantle turning
// about its axis) is touched where it lies, with no turning.
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

// The load the grains put on a wall: force (N) and torque (N m) about where
// the wall's point is (Simulation::wall_loads()).
struct WallLoad {
    Vec3 force, torque;
};

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
    // cylinder, cone: the grains move inside it (else outside). mesh, where
    // `sided`: the grains lie inside the closed surface (else outside); the
    // fills and the start's checks keep them there (a mesh's contact is
    // two-sided whatever this says).
    bool inside = true;
    bool sided = false;  // mesh: a closed surface with an inside (the key `inside` given)
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

// The touch (inline: the walls' loop of the time step inlines it; the
// shapes' helpers in wall_detail).
namespace wall_detail {

// A unit vector normal to the unit vector u (for a centre on an axis, where
// any radial direction will do).
inline Vec3 any_normal(const Vec3& u) {
    const Vec3 other = std::abs(u.x) < 0.9 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
    const Vec3 v = cross(u, other);
    return (1.0 / norm(v)) * v;
}

// The touch of a point from a point q of the wall's edge or rim (a line, a
// corner): along x - q, with no curvature.
inline WallTouch from_edge(const Vec3& v, const Vec3& fallback_normal) {
    WallTouch t;
    t.distance = norm(v);
    t.n = t.distance > 0.0 ? (1.0 / t.distance) * v : fallback_normal;
    return t;
}

// A surface of revolution about the unit axis u through `point`, whose
// meridian is the segment from (s, rho) = (0, r0) to (length, r1) (s along
// the axis, rho from it): a cylinder where r0 = r1, a cone otherwise.
// Within the segment's reach the centre is touched across the mantle along
// the meridian's normal, from whichever side it lies on (towards the axis
// for grains inside); beyond it from the rim circle at its nearer end. An
// infinite cylinder has no rim to go round: it is one-sided, the grains on
// the `inside` side.
inline WallTouch revolution_touch(const Vec3& point, const Vec3& u, double r0, double r1, double length,
                                  bool inside, const Vec3& x) {
    const Vec3 d = x - point;
    const double s = dot(d, u);
    const Vec3 radial = d - s * u;
    const double rho = norm(radial);
    const Vec3 out = rho > 0.0 ? (1.0 / rho) * radial : any_normal(u);  // unit, from the axis
    if (std::isinf(length)) {  // an infinite cylinder: the mantle everywhere
        WallTouch t;
        t.distance = inside ? r0 - rho : rho - r0;
        t.n = inside ? -out : out;
        t.curvature = (inside ? 1.0 : -1.0) / r0;
        return t;
    }
    // The meridian's unit tangent T = (length, r1 - r0) / l and its normal
    // towards the axis N = (r1 - r0, -length) / l, as (along u, along out).
    // (A cylinder's are (1, 0) and (0, -1), exactly as the divisions give
    // them, which are slow to make for every sphere.)
    const bool cylinder = r1 == r0;
    const double l = cylinder ? length : std::hypot(length, r1 - r0);
    const double T_s = cylinder ? 1.0 : length / l, T_rho = cylinder ? 0.0 : (r1 - r0) / l;
    const double N_s = T_rho, N_rho = -T_s;
    const double q_s = s, q_rho = rho - r0;  // from the meridian's start
    const double along = q_s * T_s + q_rho * T_rho;
    if (along >= 0.0 && along <= l) {
        // A mantle with ends is a thin shell, touched from either side: a
        // grain that has gone round its rim (one bouncing up under a
        // hopper) is pushed away from it, not through it. On the grains'
        // side (`inside`) the touch is the one-sided mantle's, to the bit.
        WallTouch t;
        const double towards_axis = q_s * N_s + q_rho * N_rho;  // > 0 on the axis's side
        const bool axis_side = inside ? towards_axis >= 0.0 : towards_axis > 0.0;
        t.distance = axis_side ? towards_axis : -towards_axis;
        const Vec3 n_in = N_s * u + N_rho * out;
        t.n = axis_side ? n_in : -n_in;
        // Across the mantle a surface of revolution curves by |N_rho| / rho
        // (Meusnier), rho the radius at the contact; along the meridian not.
        // Concave seen from the axis's side, convex from the other.
        const double rho_contact = cylinder ? r0 : r0 + along * T_rho;  // (r0 + along 0 is r0)
        t.curvature = (axis_side ? 1.0 : -1.0) * T_s / rho_contact;
        return t;
    }
    const bool at_start = along < 0.0;
    const double rim_s = at_start ? 0.0 : length, rim_rho = at_start ? r0 : r1;
    return from_edge((s - rim_s) * u + (rho - rim_rho) * out, inside ? -out : out);
}

}  // namespace wall_detail

// The touch of x with the wall's shape lying at `point` with its normal
// (or axis) `normal`: its own point and normal, or where a motion that
// leaves its surface in place has carried them (a still wall, below; a
// rectangle, whose edge is its own, only ever at its own).
inline WallTouch wall_touch(const Wall& w, const Vec3& point, const Vec3& normal, const Vec3& x) {
    const Vec3 d = x - point;
    switch (w.shape) {
        case WallShape::plane: {  // one-sided: the grains are on the side n points to
            WallTouch t;
            t.distance = dot(d, normal);
            t.n = normal;
            return t;
        }
        case WallShape::rectangle: {
            const Vec3 e2 = cross(normal, w.edge);
            const double a = dot(d, w.edge), b = dot(d, e2), c = dot(d, normal);
            if (std::abs(a) <= w.half_width && std::abs(b) <= w.half_height) {  // across its face, from either side
                WallTouch t;
                t.distance = std::abs(c);
                t.n = c < 0.0 ? -normal : normal;
                return t;
            }
            const double a_edge = std::clamp(a, -w.half_width, w.half_width);
            const double b_edge = std::clamp(b, -w.half_height, w.half_height);
            return wall_detail::from_edge((a - a_edge) * w.edge + (b - b_edge) * e2 + c * normal, normal);
        }
        case WallShape::disc: {
            const double c = dot(d, normal);
            const Vec3 in_plane = d - c * normal;
            const double rho = norm(in_plane);
            if (rho <= w.radius && rho >= w.hole_radius) {  // across its face, from either side
                WallTouch t;
                t.distance = std::abs(c);
                t.n = c < 0.0 ? -normal : normal;
                return t;
            }
            // From the nearer rim: the outer one, or the hole's.
            const double rim = rho > w.radius ? w.radius : w.hole_radius;
            const Vec3 out = rho > 0.0 ? (1.0 / rho) * in_plane : wall_detail::any_normal(normal);
            return wall_detail::from_edge(d - rim * out, normal);
        }
        case WallShape::cylinder:
            return wall_detail::revolution_touch(point, normal, w.radius, w.radius, w.length, w.inside, x);
        case WallShape::cone:
            return wall_detail::revolution_touch(point, normal, w.radius, w.end_radius, w.length, w.inside, x);
        case WallShape::mesh: return {};  // no single touch (walls/mesh.hpp: mesh_contacts): an infinite distance
    }
    return {};
}

// The touch of x (in the wall's own frame) with the wall where it was described.
inline WallTouch wall_touch(const Wall& w, const Vec3& x) { return wall_touch(w, w.point, w.normal, x); }

// Whether the centre x lies for sure at least `reach`
// (> 0) from the wall, wall_touch(w, x).distance >= reach, found without a
// square root or a division: the cheap test for the many spheres far from
// a wall. False where it cannot tell (near the wall, beyond the ends of a
// cylinder, for a cone). It keeps a relative margin far beyond round-off,
// so where it says true, wall_touch() would have found the sphere clear of
// the wall too, to the bit.
// `point` and `normal` are the wall's where x is (its own, or where its
// motion has carried them: PlacedWall).
inline bool surely_beyond(const Wall& w, const Vec3& point, const Vec3& normal, const Vec3& x, double reach) {
    constexpr double margin = 1e-9;  // relative, on squared distances too: far beyond the round-off of turning
    const Vec3 d = x - point;
    switch (w.shape) {
        case WallShape::plane: return dot(d, normal) >= reach * (1.0 + margin);
        case WallShape::rectangle:
        case WallShape::disc: return std::abs(dot(d, normal)) >= reach * (1.0 + margin);  // a face or an edge
        case WallShape::cylinder: {
            const double s = dot(d, normal);
            if (!std::isinf(w.length) && !(s >= 0.0 && s <= w.length)) return false;  // by a rim
            const double rho2 = norm2(d - s * normal);  // across the mantle, w.radius - rho inside
            if (w.inside) {
                const double clear = w.radius - reach;
                return clear > 0.0 && rho2 <= clear * clear * (1.0 - margin);
            }
            const double clear = w.radius + reach;
            return rho2 >= clear * clear * (1.0 + margin);
        }
        case WallShape::cone:
        case WallShape::mesh: return false;
    }
    return false;
}

// The largest curvature (1/m, as in WallTouch) the wall's surface turns
// towards a grain anywhere: 1/R_c inside a cylinder, cos(alpha)/r at the
// narrower end inside a cone (infinite at a tip), else 0. The time step
// takes the wall's contacts at the R* it gives.
double largest_curvature(const Wall& w);

// Whether the wall's surface stays where it is under its motion now: at
// rest; or turning (without translation) about its own axis, a disc, a
// cylinder or a cone whose axis is the motion's, or an infinite plane
// normal to the motion's axis. Exactly so: a wall tilted by round-off
// counts as moving. (A mesh in motion never does: it finds its own
// contacts, in its own frame.)
inline bool stays_put(const Wall& w, const MotionNow* now) {
    if (!now) return true;
    if (!(now->velocity == Vec3{})) return false;
    if (now->angular_velocity == 0.0) return true;
    const Vec3& u = now->turn.u;
    const bool along = cross(w.normal, u) == Vec3{};
    switch (w.shape) {
        case WallShape::plane: return along;
        case WallShape::disc:
        case WallShape::cylinder:
        case WallShape::cone: return along && cross(w.point - now->start_axis_point, u) == Vec3{};
        case WallShape::rectangle:
        case WallShape::mesh: return false;
    }
    return false;
}

// A wall where its motion has carried it at one time: `now` is its motion
// then (particles/rigid_motion.hpp), or null for a wall at rest; `origin` where
// its `point` is (m). A still wall (stays_put()) is touched where it lies,
// in the lab frame; any other in its own frame (wall_contact() below).
struct PlacedWall {
    const Wall* wall = nullptr;
    const MotionNow* now = nullptr;
    Vec3 origin;
    Vec3 normal;  // the wall's normal (or axis) turned as its motion has turned it
    bool still = true;
};
PlacedWall place_wall(const Wall& w, const MotionNow* now);

// surely_beyond() of a centre x in the lab frame (to the round-off of the
// wall's turning, which the test's margin covers).
inline bool surely_beyond(const PlacedWall& w, const Vec3& x, double reach) {
    return surely_beyond(*w.wall, w.origin, w.normal, x, reach);
}

// The touch of a sphere's centre x (lab frame) with a placed wall, its
// normal in the lab frame, and the wall's surface velocity at the nearest
// point c = x - distance n (m/s: V + Omega u x (c - axis point)) and its
// angular velocity (rad/s: Omega u); zero for a wall at rest. A still
// wall's shape is evaluated where it lies now; any other's in its frame at
// the start of its motion: x turned back by the rotation since and carried
// back by the translation, and the normal found there turned forward.
struct WallContact {
    WallTouch touch;
    Vec3 velocity, angular_velocity;
};

// The pieces of wall_contact(), also for a wall that gives its contacts by
// itself (a mesh): a lab point x carried into the wall's frame at the start
// of its motion (turned back by the rotation since and carried back by the
// translation), a direction of that frame turned into the lab frame, and
// the surface velocity and spin at a lab point of the wall (zero at rest).
inline Vec3 to_start_frame(const MotionNow* now, const Vec3& x) {
    if (!now) return x;
    Rotation back = now->turn;  // the rotation since the motion began, undone
    back.s = -back.s;
    return now->start_axis_point + rotate(x - now->axis_point, back);
}

inline Vec3 to_lab_direction(const MotionNow* now, const Vec3& v) { return now ? rotate(v, now->turn) : v; }

inline void surface_motion(const MotionNow* now, const Vec3& point, Vec3& velocity, Vec3& angular_velocity) {
    if (!now) {
        velocity = angular_velocity = Vec3{};
        return;
    }
    angular_velocity = now->angular_velocity * now->turn.u;
    velocity = now->velocity + cross(angular_velocity, point - now->axis_point);
}

// wall_contact() in three parts, for a loop over many spheres and walls:
// the centre x in the frame the wall is touched in (x itself for a still
// wall; the same for every other wall of one motion); the touch there
// (frame_touch()); and, where it is a contact, the touch turned into the
// lab frame with the wall's surface velocity and spin. wall_contact(w, x)
// is wall_contact_of(w, x, frame_touch(w, wall_frame_point(w, x))), to the
// bit.
inline Vec3 wall_frame_point(const PlacedWall& w, const Vec3& x) { return w.still ? x : to_start_frame(w.now, x); }

inline WallTouch frame_touch(const PlacedWall& w, const Vec3& x_frame) {
    return w.still ? wall_touch(*w.wall, w.origin, w.normal, x_frame) : wall_touch(*w.wall, x_frame);
}

inline WallContact wall_contact_of(const PlacedWall& w, const Vec3& x, const WallTouch& in_wall_frame) {
    WallContact c;
    c.touch = in_wall_frame;
    if (!w.now) return c;
    if (!w.still) c.touch.n = to_lab_direction(w.now, c.touch.n);
    surface_motion(w.now, x - c.touch.distance * c.touch.n, c.velocity, c.angular_velocity);
    return c;
}

inline WallContact wall_contact(const PlacedWall& w, const Vec3& x) {
    return wall_contact_of(w, x, frame_touch(w, wall_frame_point(w, x)));
}

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
