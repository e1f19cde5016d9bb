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
#include "tumble/contact/mindlin_shear.hpp"
#include "tumble/contact/twisting.hpp"
#include "tumble/core/keyword.hpp"
#include "tumble/materials/pair_table.hpp"

namespace tumble {

// The shear models a scenario can name (mindlin_shear.hpp). To add one: an
// entry in ShearModel and here, its rule in mindlin_shear.hpp.
inline constexpr std::array<Keyword<ShearModel>, 4> shear_models{{
    {"paper", ShearModel::Paper, "paper eq. 8: the slip restarts at the static limit (saw-tooth, mean mu |F_n| / 2)"},
    {"coulomb", ShearModel::Coulomb, "paper eq. 8 held at the static limit while sliding (mean mu |F_n|)"},
    {"spring", ShearModel::Spring, "tangential spring truncated at the Coulomb limit, as in LAMMPS/LIGGGHTS"},
    {"off", ShearModel::Off, "no shear force"},
}};

// The stiffness of the tangential and twisting springs (pair_table.hpp).
inline constexpr std::array<Keyword<TangentialStiffness>, 2> tangential_stiffnesses{{
    {"paper", TangentialStiffness::Paper, "16/3 G* a and 8/3 G* a^3 (the paper's eqs. 8 and 9)"},
    {"mindlin", TangentialStiffness::Mindlin, "8 G* a and 16/3 G_i G_j/(G_i + G_j) a^3 (Mindlin; Lubkin)"},
}};

// The normal force that limits friction (shear and twisting):
//   Net: |F_n|, the sum of elements 1-3 (the paper's text: an adhesive
//        contact at its equilibrium overlap then has no friction);
//   Jkr: |F_elastic + F_attraction + 2 F_pull-off|, as JKR-based codes do,
//        with F_pull-off = 2 pi W R* the pull-off force of this law.
enum class FrictionNormal { Net, Jkr };
inline constexpr std::array<Keyword<FrictionNormal>, 2> friction_normals{{
    {"net", FrictionNormal::Net, "|F_n|: elastic - attraction + viscous (the paper)"},
    {"jkr", FrictionNormal::Jkr, "|elastic - attraction + 2 pull-off| (JKR-based codes)"},
}};

// Which terms are on. Every term can be switched off for tests and users.
struct ContactModel {
    bool elastic = true;     // element 1, eq. 1
    bool viscous = true;     // element 2, eq. 4
    bool attraction = true;  // element 3, eq. 7
    ShearModel shear = ShearModel::Paper;  // element 4, eq. 8
    bool twisting = true;    // element 5, eq. 9
    FrictionNormal friction_normal = FrictionNormal::Net;
    // The springs' stiffness; it enters through the pair table
    // (PairCoefficients::shear_stiffness, twist_stiffness).
    TangentialStiffness tangential_stiffness = TangentialStiffness::Paper;
    // Slip speed (m/s) above which a sliding contact slips along its
    // velocity (Paper, Coulomb; mindlin_shear.hpp); slower, along its slip.
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
// either; with this one the law has no run-time switches (but the friction
// normal, a choice between two values), which lets the pair loop run it on
// several contacts per instruction (sim/pair_loop.hpp).
template <ShearModel Shear>
struct AllTermsOn {
    static constexpr bool elastic = true, viscous = true, attraction = true, twisting = true;
    static constexpr ShearModel shear = Shear;
    FrictionNormal friction_normal = FrictionNormal::Net;
    double slip_velocity_regularisation = 1e-4;
};

// Model: ContactModel or AllTermsOn<...>.
template <class Model>
inline ContactForces contact_law(const PairCoefficients& c, const ContactGeometry& g, const Model& model, double dt,
                                 ContactHistory& history) {
    const double a = g.contact_radius;
    ContactForces out;

    // Normal force along n: elasticity, internal friction, surface attraction.
    const double F_elastic = model.elastic ? hertz_force(c.E_star, a, g.overlap) : 0.0;
    const double F_viscous = model.viscous ? kuwabara_kono_force(c.B_star, a, g.v_n) : 0.0;
    const double F_attraction = model.attraction ? attraction_force(c.attraction, a) : 0.0;
    const double F_n = F_elastic + F_viscous + F_attraction;

    // The static limit of friction, mu times the normal force chosen.
    const double pull_off = model.attraction ? c.pull_off * g.R_star : 0.0;
    const double friction_limit =
        c.mu * (model.friction_normal == FrictionNormal::Jkr ? std::abs(F_elastic + F_attraction + 2.0 * pull_off)
                                                             : std::abs(F_n));

    // Shear force at the contact point and twisting couple about n; the
    // couple follows the shear model's reading of the limit (the paper's
    // when the shear is off).
    const double v_reg = model.slip_velocity_regularisation;
    const SlipLimits limits = slip_limits(c.shear_stiffness, c.twist_stiffness, a, friction_limit);
    const Vec3 F_t = model.shear != ShearModel::Off
                         ? mindlin_shear_force(model.shear, limits, g.n, g.v_t, dt, v_reg, history.slip)
                         : Vec3{};
    const ShearModel twist_reading = model.shear == ShearModel::Off ? ShearModel::Paper : model.shear;
    const double M =
        model.twisting ? twisting_couple(twist_reading, limits, a, g.w_n, dt, v_reg, history.angular_slip) : 0.0;

    history.viscous_force = F_viscous;  // for the dashpot's next step (integrate/dashpot.hpp)

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
