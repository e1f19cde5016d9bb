// SPDX-License-Identifier: MIT
#include "tumble/walls/wall.hpp"

namespace tumble {

namespace {

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// A unit vector normal to the unit vector u (for a centre on an axis, where
// any radial direction will do).
Vec3 any_normal(const Vec3& u) {
    const Vec3 other = std::abs(u.x) < 0.9 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
    const Vec3 v = cross(u, other);
    return (1.0 / norm(v)) * v;
}

// The touch of a point from a point q of the wall's edge or rim (a line, a
// corner): along x - q, with no curvature.
WallTouch from_edge(const Vec3& v, const Vec3& fallback_normal) {
    WallTouch t;
    t.distance = norm(v);
    t.n = t.distance > 0.0 ? (1.0 / t.distance) * v : fallback_normal;
    return t;
}

// A surface of revolution about the unit axis u through `point`, whose
// meridian is the segment from (s, rho) = (0, r0) to (length, r1) (s along
// the axis, rho from it): a cylinder where r0 = r1, a cone otherwise.
// Within the segment's reach the centre is touched across the mantle along
// the meridian's normal, towards the axis for grains inside; beyond it
// from the rim circle at its nearer end (none where the cylinder is
// infinite).
WallTouch revolution_touch(const Vec3& point, const Vec3& u, double r0, double r1, double length, bool inside,
                           const Vec3& x) {
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
    const double l = std::hypot(length, r1 - r0);
    const double T_s = length / l, T_rho = (r1 - r0) / l;
    const double N_s = T_rho, N_rho = -T_s;
    const double q_s = s, q_rho = rho - r0;  // from the meridian's start
    const double along = q_s * T_s + q_rho * T_rho;
    if (along >= 0.0 && along <= l) {
        WallTouch t;
        const double towards_axis = q_s * N_s + q_rho * N_rho;  // > 0 on the axis's side
        t.distance = inside ? towards_axis : -towards_axis;
        const Vec3 n_in = N_s * u + N_rho * out;
        t.n = inside ? n_in : -n_in;
        // Across the mantle a surface of revolution curves by |N_rho| / rho
        // (Meusnier), rho the radius at the contact; along the meridian not.
        const double rho_contact = r0 + along * T_rho;
        t.curvature = (inside ? 1.0 : -1.0) * T_s / rho_contact;
        return t;
    }
    const bool at_start = along < 0.0;
    const double rim_s = at_start ? 0.0 : length, rim_rho = at_start ? r0 : r1;
    return from_edge((s - rim_s) * u + (rho - rim_rho) * out, inside ? -out : out);
}

}  // namespace

std::string wall_problem(const Wall& w) {
    if (!finite(w.point) || !finite(w.normal) || !finite(w.edge)) return "its point and directions must be finite";
    if (std::abs(norm(w.normal) - 1.0) > 1e-12) return "its normal (or axis) must be a unit vector";
    switch (w.shape) {
        case WallShape::plane: return {};
        case WallShape::rectangle:
            if (std::abs(norm(w.edge) - 1.0) > 1e-12 || std::abs(dot(w.edge, w.normal)) > 1e-12)
                return "its edge must be a unit vector in its plane";
            if (!(w.half_width > 0.0) || !(w.half_height > 0.0) || !std::isfinite(w.half_width) ||
                !std::isfinite(w.half_height))
                return "its sides must be positive and finite";
            return {};
        case WallShape::disc:
            if (!(w.radius > 0.0) || !std::isfinite(w.radius)) return "its radius must be positive and finite";
            if (!(w.hole_radius >= 0.0 && w.hole_radius < w.radius)) return "its hole_radius must lie in [0, radius)";
            return {};
        case WallShape::cylinder:
            if (!(w.radius > 0.0) || !std::isfinite(w.radius)) return "its radius must be positive and finite";
            if (!(w.length > 0.0)) return "its length must be positive (or infinite)";
            return {};
        case WallShape::cone:
            if (!(w.radius >= 0.0) || !(w.end_radius >= 0.0) || !std::isfinite(w.radius) ||
                !std::isfinite(w.end_radius) || (w.radius == 0.0 && w.end_radius == 0.0))
                return "its radii must be finite, >= 0 and not both 0";
            if (!(w.length > 0.0) || !std::isfinite(w.length)) return "its length must be positive and finite";
            return {};
        case WallShape::mesh:
            if (w.mesh < 0) return "it names no mesh";
            return {};
    }
    return "unknown shape";
}

WallTouch wall_touch(const Wall& w, const Vec3& x) {
    const Vec3 d = x - w.point;
    switch (w.shape) {
        case WallShape::plane: {  // one-sided: the grains are on the side n points to
            WallTouch t;
            t.distance = dot(d, w.normal);
            t.n = w.normal;
            return t;
        }
        case WallShape::rectangle: {
            const Vec3 e2 = cross(w.normal, w.edge);
            const double a = dot(d, w.edge), b = dot(d, e2), c = dot(d, w.normal);
            if (std::abs(a) <= w.half_width && std::abs(b) <= w.half_height) {  // across its face, from either side
                WallTouch t;
                t.distance = std::abs(c);
                t.n = c < 0.0 ? -w.normal : w.normal;
                return t;
            }
            const double a_edge = std::clamp(a, -w.half_width, w.half_width);
            const double b_edge = std::clamp(b, -w.half_height, w.half_height);
            return from_edge((a - a_edge) * w.edge + (b - b_edge) * e2 + c * w.normal, w.normal);
        }
        case WallShape::disc: {
            const double c = dot(d, w.normal);
            const Vec3 in_plane = d - c * w.normal;
            const double rho = norm(in_plane);
            if (rho <= w.radius && rho >= w.hole_radius) {  // across its face, from either side
                WallTouch t;
                t.distance = std::abs(c);
                t.n = c < 0.0 ? -w.normal : w.normal;
                return t;
            }
            // From the nearer rim: the outer one, or the hole's.
            const double rim = rho > w.radius ? w.radius : w.hole_radius;
            const Vec3 out = rho > 0.0 ? (1.0 / rho) * in_plane : any_normal(w.normal);
            return from_edge(d - rim * out, w.normal);
        }
        case WallShape::cylinder:
            return revolution_touch(w.point, w.normal, w.radius, w.radius, w.length, w.inside, x);
        case WallShape::cone:
            return revolution_touch(w.point, w.normal, w.radius, w.end_radius, w.length, w.inside, x);
        case WallShape::mesh: return {};
    }
    return {};
}

double largest_curvature(const Wall& w) {
    if (!w.inside) return 0.0;
    if (w.shape == WallShape::cylinder) return 1.0 / w.radius;
    if (w.shape != WallShape::cone) return 0.0;
    const double cos_alpha = w.length / std::hypot(w.length, w.end_radius - w.radius);
    const double narrowest = std::min(w.radius, w.end_radius);
    return narrowest > 0.0 ? cos_alpha / narrowest : std::numeric_limits<double>::infinity();
}

PlacedWall place_wall(const Wall& w, const MotionNow* now) {
    PlacedWall p{&w, now, w.point};
    if (now) p.origin = now->axis_point + rotate(w.point - now->start_axis_point, now->turn);
    return p;
}

Vec3 to_start_frame(const MotionNow* now, const Vec3& x) {
    if (!now) return x;
    Rotation back = now->turn;  // the rotation since the motion began, undone
    back.s = -back.s;
    return now->start_axis_point + rotate(x - now->axis_point, back);
}

Vec3 to_lab_direction(const MotionNow* now, const Vec3& v) { return now ? rotate(v, now->turn) : v; }

void surface_motion(const MotionNow* now, const Vec3& point, Vec3& velocity, Vec3& angular_velocity) {
    if (!now) {
        velocity = angular_velocity = Vec3{};
        return;
    }
    angular_velocity = now->angular_velocity * now->turn.u;
    velocity = now->velocity + cross(angular_velocity, point - now->axis_point);
}

WallContact wall_contact(const PlacedWall& w, const Vec3& x) {
    WallContact c;
    const MotionNow* now = w.now;
    if (!now) {
        c.touch = wall_touch(*w.wall, x);
        return c;
    }
    c.touch = wall_touch(*w.wall, to_start_frame(now, x));
    c.touch.n = to_lab_direction(now, c.touch.n);
    surface_motion(now, x - c.touch.distance * c.touch.n, c.velocity, c.angular_velocity);
    return c;
}

}  // namespace tumble
