// SPDX-License-Identifier: MIT
#include "tumble/materials/pair_table.hpp"

#include <cmath>
#include <string>

#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"

namespace tumble {

double viscous_modulus(const Material& m) { return 9.0 * m.xi * m.eta / (3.0 * m.xi + m.eta); }

double viscous_poisson_ratio(const Material& m) {
    return (3.0 * m.xi - 2.0 * m.eta) / (2.0 * (3.0 * m.xi + m.eta));
}

std::string material_problem(const Material& m) {
    for (double value : {m.E, m.G, m.nu, m.xi, m.eta, m.rho, m.radius})
        if (!std::isfinite(value)) return "every parameter must be a finite number";
    if (!(m.E > 0.0)) return "Young's modulus E must be > 0";
    if (!(m.G > 0.0)) return "shear modulus G must be > 0";
    if (!(m.nu > -1.0 && m.nu < 0.5)) return "Poisson ratio nu must lie in (-1, 0.5)";
    if (!(m.xi >= 0.0)) return "bulk viscosity xi must be >= 0";
    if (!(m.eta >= 0.0)) return "shear viscosity eta must be >= 0";
    if (m.xi + m.eta > 0.0 && !(m.xi > 0.0 && m.eta > 0.0))
        return "viscosities xi and eta must be both zero (no internal friction) or both > 0";
    if (!(m.rho > 0.0)) return "density rho must be > 0";
    if (!(m.radius > 0.0)) return "radius must be > 0";
    return {};
}

namespace {
// The paper's mixing rule X* = X_i X_j / (X_i f_j + X_j f_i); zero if either is zero.
double mix(double xi, double fi, double xj, double fj) {
    const double denominator = xi * fj + xj * fi;
    return denominator > 0.0 ? xi * xj / denominator : 0.0;
}
}  // namespace

PairCoefficients make_pair_coefficients(const Material& a, const Material& b, const PairProperties& p,
                                        TangentialStiffness stiffness) {
    PairCoefficients c;
    c.E_star = mix(a.E, 1.0 - a.nu * a.nu, b.E, 1.0 - b.nu * b.nu);  // eq. 1
    c.G_star = mix(a.G, 2.0 - a.nu, b.G, 2.0 - b.nu);                // eq. 8
    // Tangential spring k_t = shear_stiffness a (N/m), twisting spring
    // k_twist = twist_stiffness a^3 (N m/rad): pair_table.hpp.
    const bool mindlin = stiffness == TangentialStiffness::Mindlin;
    c.shear_stiffness = (mindlin ? 8.0 : 16.0 / 3.0) * c.G_star;
    c.twist_stiffness = mindlin ? 16.0 / 3.0 * mix(a.G, 1.0, b.G, 1.0) : 8.0 / 3.0 * c.G_star;
    const double sa = a.xi > 0.0 ? viscous_poisson_ratio(a) : 0.0;
    const double sb = b.xi > 0.0 ? viscous_poisson_ratio(b) : 0.0;
    const double Ba = a.xi > 0.0 ? viscous_modulus(a) : 0.0;
    const double Bb = b.xi > 0.0 ? viscous_modulus(b) : 0.0;
    c.B_star = mix(Ba, 1.0 - sa * sa, Bb, 1.0 - sb * sb);  // eq. 4
    c.mu = p.mu;
    c.W = p.W;
    c.attraction = std::sqrt(4.0 / 3.0 * 8.0 * pi * p.W * c.E_star);  // eq. 7
    c.pull_off = 2.0 * pi * p.W;  // = 3 attraction^2 / (16 E*), the deepest pull of eqs. 1 + 7 per R*
    return c;
}

PairTable::PairTable(const std::vector<Material>& materials,
                     const std::vector<std::vector<PairProperties>>& properties, TangentialStiffness stiffness)
    : n_(static_cast<int>(materials.size())), table_(materials.size() * materials.size()) {
    if (properties.size() != materials.size())
        throw Error("pair table: expected properties for " + std::to_string(n_) + " materials");
    for (int i = 0; i < n_; ++i) {
        if (properties[i].size() != materials.size())
            throw Error("pair table: row " + std::to_string(i) + " is incomplete");
        for (int j = 0; j < n_; ++j) {
            const auto& pij = properties[i][j];
            const auto& pji = properties[j][i];
            if (pij.mu != pji.mu || pij.W != pji.W)
                throw Error("pair table: properties of " + materials[i].name + "-" + materials[j].name +
                            " are not symmetric");
            table_[index(i, j)] = make_pair_coefficients(materials[i], materials[j], pij, stiffness);
        }
    }
    for (const PairCoefficients& c : table_) {
        columns_.E_star.push_back(c.E_star);
        columns_.shear_stiffness.push_back(c.shear_stiffness);
        columns_.twist_stiffness.push_back(c.twist_stiffness);
        columns_.B_star.push_back(c.B_star);
        columns_.mu.push_back(c.mu);
        columns_.attraction.push_back(c.attraction);
        columns_.pull_off.push_back(c.pull_off);
    }
}

}  // namespace tumble
