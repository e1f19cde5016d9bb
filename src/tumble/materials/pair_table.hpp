// SPDX-License-Identifier: MIT
// Per-pair coefficients, computed once for every pair of materials.
// They depend only on the two materials, not on the radii: R* is formed per
// contact because grains of one material may have different radii.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "tumble/materials/material.hpp"

namespace tumble {

// The stiffness of the tangential spring and of the twisting spring of a
// sticking contact of radius a (docs/MODEL.md, "Tangential stiffness"):
//   Paper:   16/3 G* a and 8/3 G* a^3 (the paper's eqs. 8 and 9);
//   Mindlin: 8 G* a (Mindlin 1949, no slip) and 16/3 G_t a^3 with
//            G_t = G_i G_j / (G_i + G_j) (a bonded circular contact in
//            torsion, Lubkin 1951), the values of the elasticity of two
//            spheres in contact.
enum class TangentialStiffness { Paper, Mindlin };

struct PairCoefficients {
    double E_star = 0.0;      // E_i E_j / (E_i (1 - nu_j^2) + E_j (1 - nu_i^2)), Pa
    double G_star = 0.0;      // G_i G_j / (G_i (2 - nu_j) + G_j (2 - nu_i)), Pa
    double shear_stiffness = 0.0;  // the tangential spring's stiffness per contact radius, k_t / a, Pa
    double twist_stiffness = 0.0;  // the twisting spring's stiffness per a^3, k_twist / a^3, Pa
    double B_star = 0.0;      // B_i B_j / (B_i (1 - s_j^2) + B_j (1 - s_i^2)), Pa s
    double mu = 0.0;          // static friction coefficient
    double W = 0.0;           // surface energy, J/m^2
    double attraction = 0.0;  // sqrt(4/3 * 8 pi W E*), prefactor of eq. 7, N m^-3/2
    double pull_off = 0.0;    // 2 pi W: the pull-off force of eqs. 1 + 7 is pull_off R* (docs/MODEL.md), N/m
};

PairCoefficients make_pair_coefficients(const Material& a, const Material& b, const PairProperties& p,
                                        TangentialStiffness stiffness = TangentialStiffness::Paper);

// The coefficients the contact law uses, one array per coefficient, indexed
// by PairTable::index(): for loops that fetch several pairs' coefficients
// per instruction.
struct PairColumns {
    std::vector<double> E_star, shear_stiffness, twist_stiffness, B_star, mu, attraction, pull_off;

    PairCoefficients at(std::uint32_t index) const {
        PairCoefficients c;
        c.E_star = E_star[index], c.B_star = B_star[index], c.mu = mu[index];
        c.shear_stiffness = shear_stiffness[index], c.twist_stiffness = twist_stiffness[index];
        c.attraction = attraction[index], c.pull_off = pull_off[index];
        return c;  // G* and W stay 0: the law uses the stiffnesses, the attraction prefactor and the pull-off
    }
};

// Symmetric table indexed by two material ids.
class PairTable {
public:
    PairTable() = default;
    // properties[i][j] must be given for every i, j and be symmetric.
    PairTable(const std::vector<Material>& materials, const std::vector<std::vector<PairProperties>>& properties,
              TangentialStiffness stiffness = TangentialStiffness::Paper);

    const PairCoefficients& operator()(int i, int j) const { return table_[index(i, j)]; }
    int size() const { return n_; }
    // Where the pair (i, j) is in columns().
    std::uint32_t index(int i, int j) const { return static_cast<std::uint32_t>(i * n_ + j); }
    const PairColumns& columns() const { return columns_; }

private:
    int n_ = 0;
    std::vector<PairCoefficients> table_;
    PairColumns columns_;
};

}  // namespace tumble
