// SPDX-License-Identifier: MIT
// The state of one contact between spheres i and j, built once per pair and
// handed to every force term.
//
// Convention (SPEC-NOTES "Notation"): n is the unit vector from the centre of
// j to the centre of i; overlap h = R_i + R_j - |X_i - X_j| > 0 while in
// contact; v is the velocity of i relative to j at the contact point.
//
// Velocities: the forces at t + dt are computed while the spheres' velocities
// are at the half step, v(t + dt/2) (integrate/velocity_verlet.hpp). The
// slips integrate the tangential and spin velocities over the step, so they
// take the half-step values (the midpoint rule, as the positions do). The
// internal friction needs the normal velocity at t + dt itself: it is
// predicted as v(t + dt/2) + dt/2 a(t), which makes the damping second order
// in dt (a half-step velocity there makes restitution 1.4 to 4 % low at the
// automatic step; docs/MODEL.md, "Time step"), and the engine then hands
// the law the dashpot's velocity over the step instead
// (integrate/dashpot.hpp).
#pragma once

#include <cmath>

#include "tumble/core/vec3.hpp"

namespace tumble {

struct ContactGeometry {
    Vec3 n;                // unit normal, j -> i
    double overlap = 0.0;  // h, m
    double R_star = 0.0;   // R_i R_j / (R_i + R_j), m
    double contact_radius = 0.0;  // a = sqrt(R* h), m; every term of the model is a power of a and h
    double lever_i = 0.0;  // distance from centre of i to the contact point, R_i - h/2, m
    double lever_j = 0.0;  // distance from centre of j to the contact point, R_j - h/2, m
    double v_n = 0.0;      // v . n at t + dt (predicted; integrate/dashpot.hpp), m/s (negative while approaching)
    Vec3 v_t;              // v - (v . n) n at the half step, m/s
    double w_n = 0.0;      // (omega_i - omega_j) . n at the half step, rad/s
};

// Contact point: the shear force acts at X_i - lever_i n = X_j + lever_j n.
// With lever = R - h/2 for both spheres the two points coincide, so the
// shear torques on i and j conserve angular momentum exactly.
//
// d = X_i - X_j (periodic image already applied), distance = |d| > 0,
// v_ij = v_i - v_j the velocity of the centre of i relative to that of j at
// the half step, kick_ij = its predicted change to t + dt.
inline ContactGeometry make_contact_geometry(const Vec3& d, double distance, double R_i, double R_j,
                                             const Vec3& v_ij, const Vec3& kick_ij, const Vec3& omega_i,
                                             const Vec3& omega_j) {
    ContactGeometry c;
    // 1/distance and R* from one division.
    const double r = 1.0 / (distance * (R_i + R_j));
    c.n = ((R_i + R_j) * r) * d;
    c.overlap = R_i + R_j - distance;
    c.R_star = R_i * R_j * distance * r;
    c.contact_radius = std::sqrt(c.R_star * c.overlap);
    c.lever_i = R_i - 0.5 * c.overlap;
    c.lever_j = R_j - 0.5 * c.overlap;
    // Velocity of the contact point as part of i minus as part of j:
    // (v_i + omega_i x (-lever_i n)) - (v_j + omega_j x (lever_j n)).
    // The spins add nothing along n, so v_n at t + dt needs only kick_ij.
    const Vec3 v = v_ij - cross(c.lever_i * omega_i + c.lever_j * omega_j, c.n);
    const double v_n_half = dot(v, c.n);
    c.v_t = v - v_n_half * c.n;
    c.v_n = v_n_half + dot(kick_ij, c.n);
    c.w_n = dot(omega_i - omega_j, c.n);
    return c;
}

// Contact of sphere i with a wall (walls/wall.hpp; a flat box wall is an
// infinite plane), seen as a sphere of infinite mass: n is the wall's unit
// normal pointing towards the centre of i, distance that of the centre from
// the wall's surface along n, R_star the Hertz radius of the sphere against
// the wall's curvature there (R_i on a flat face); v_i and kick_i as v_ij
// and kick_ij above, with v_wall the velocity of the wall's surface at the
// contact point and omega_wall its angular velocity (both zero for a wall
// at rest).
inline ContactGeometry make_wall_geometry(const Vec3& n, double distance, double R_i, double R_star, const Vec3& v_i,
                                          const Vec3& kick_i, const Vec3& omega_i, const Vec3& v_wall = {},
                                          const Vec3& omega_wall = {}) {
    ContactGeometry c;
    c.n = n;
    c.overlap = R_i - distance;
    c.R_star = R_star;
    c.contact_radius = std::sqrt(c.R_star * c.overlap);
    c.lever_i = R_i - 0.5 * c.overlap;
    c.lever_j = 0.0;
    // The contact point as part of i minus as part of the wall:
    // (v_i + omega_i x (-lever_i n)) - v_wall.
    const Vec3 v = v_i - v_wall - c.lever_i * cross(omega_i, c.n);
    const double v_n_half = dot(v, c.n);
    c.v_t = v - v_n_half * c.n;
    c.v_n = v_n_half + dot(kick_i, c.n);
    c.w_n = dot(omega_i - omega_wall, c.n);
    return c;
}

}  // namespace tumble
