// SPDX-License-Identifier: MIT
// The complete contact model (paper section 2.5, SPEC-NOTES "Forces and
// couple"), composed from the stateless terms in this folder. This is the
// one place where the terms meet; to add a term, see ARCHITECTURE.md.
#pragma once

#include <array>
#include <cmath>
#include <string_view>

#include "tumble/contact/attraction.hpp"
#include "tumble/contact/geometry.hpp"
#include "tumble/contact/hertz.hpp"
#include "tumble/contact/history.hpp"
#include "tumble/contact/kuwabara_kono.hpp"
#include "tumble/contact/mindlin_slip.hpp"
#include "tumble/contact/mindlin_spring.hpp"
#include "tumble/contact/twisting.hpp"
#include "tumble/materials/pair_table.hpp"

namespace tumble {

enum class ShearModel { Off, IntegratedSlip, TangentialSpring };

// The shear models a scenario can name. To add one: a kernel header in this
// folder, an entry here, a branch in contact_law() below.
struct ShearModelEntry {
    std::string_view keyword;
    ShearModel model;
    std::string_view description;
};
inline constexpr std::array<ShearModelEntry, 3> shear_models{{
    {"slip", ShearModel::IntegratedSlip, "paper eq. 8: integrated scalar slip, reset at the static limit"},
    {"spring", ShearModel::TangentialSpring, "tangential spring vector truncated at the Coulomb limit"},
    {"off", ShearModel::Off, "no shear force"},
}};

// Which terms are on. Every term can be switched off for tests and users.
struct ContactModel {
    bool elastic = true;     // element 1, eq. 1
    bool viscous = true;     // element 2, eq. 4
    bool attraction = true;  // element 3, eq. 7
    ShearModel shear = ShearModel::IntegratedSlip;  // element 4, eq. 8
    bool twisting = true;    // element 5, eq. 9
    // Slip speed (m/s) below which the shear direction and the twist sign
    // fade linearly to zero (see against_slip()).
    double slip_velocity_regularisation = 1e-4;

    bool all_terms_on() const { return elastic && viscous && attraction && twisting; }
};

// What one contact does to its two spheres.
struct ContactForces {
    Vec3 force_i;              // on i; j feels -force_i, N
    Vec3 torque_i;             // on i, N m
    Vec3 torque_j;             // on j, N m
    double normal_force = 0;   // F_n, the sum of elements 1-3 along n, N
    double twisting_couple = 0;   // couple about n on i, N m
};

// The model with every term on and the shear model fixed when compiling:
// the paper's model. It reads like a ContactModel, so contact_law() takes
// either; with this one the law has no run-time switches, which lets the
// pair loop run it on several contacts per instruction (sim/pair_loop.hpp).
template <ShearModel Shear>
struct AllTermsOn {
    static constexpr bool elastic = true, viscous = true, attraction = true, twisting = true;
    static constexpr ShearModel shear = Shear;
    double slip_velocity_regularisation = 1e-4;
};

// Model: ContactModel or AllTermsOn<...>.
template <class Model>
inline ContactForces contact_law(const PairCoefficients& c, const ContactGeometry& g, const Model& model, double dt,
                                 ContactHistory& history) {
    const double a = g.contact_radius;
    ContactForces out;

    // Normal force along n: elasticity, internal friction, surface attraction.
    double F_n = 0.0;
    if (model.elastic) F_n += hertz_force(c.E_star, a, g.overlap);
    if (model.viscous) F_n += kuwabara_kono_force(c.B_star, a, g.v_n);
    if (model.attraction) F_n += attraction_force(c.attraction, a);
    const double F_n_abs = std::abs(F_n);

    // Shear force at the contact point, limited by static friction mu |F_n|.
    Vec3 F_t;
    if (model.shear == ShearModel::IntegratedSlip)
        F_t = mindlin_slip_force(c.G_star, c.mu, a, F_n_abs, g.v_t, dt, model.slip_velocity_regularisation,
                                 history.integrated_slip);
    else if (model.shear == ShearModel::TangentialSpring)
        F_t = mindlin_spring_force(c.G_star, c.mu, a, F_n_abs, g.n, g.v_t, dt, history.tangential_spring);

    // Twisting couple about n.
    const double M = model.twisting ? twisting_couple(c.G_star, c.mu, a, F_n_abs, g.w_n, dt,
                                                      model.slip_velocity_regularisation,
                                                      history.integrated_angular_slip)
                                    : 0.0;

    // Torques: F_t acts on i at -lever_i n from its centre, -F_t on j at
    // +lever_j n; elements 1-3 act along n and exert none.
    const Vec3 n_cross_Ft = cross(g.n, F_t);
    out.force_i = F_n * g.n + F_t;
    out.torque_i = -g.lever_i * n_cross_Ft + M * g.n;
    out.torque_j = -g.lever_j * n_cross_Ft - M * g.n;
    out.normal_force = F_n;
    out.twisting_couple = M;
    return out;
}

}  // namespace tumble
