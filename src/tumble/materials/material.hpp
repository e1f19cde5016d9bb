// SPDX-License-Identifier: MIT
// A material: the paper's eight parameters (section 2.5: "eight material
// parameters"), in SI units. 1 poise = 0.1 Pa s.
#pragma once

#include <string>

namespace tumble {

struct Material {
    std::string name;
    double E = 0.0;       // Young's modulus, Pa
    double G = 0.0;       // shear modulus, Pa
    double nu = 0.0;      // Poisson ratio, in (-1, 0.5)
    double xi = 0.0;      // bulk (volume) viscosity, Pa s
    double eta = 0.0;     // shear viscosity, Pa s
    double rho = 0.0;     // density, kg/m^3
    double radius = 0.0;  // default radius of its grains, m
};

// Tribological parameters of a pair of materials (paper, table 3).
struct PairProperties {
    double mu = 0.0;  // static friction coefficient
    double W = 0.0;   // surface energy, J/m^2
};

// Viscous modulus B = 9 xi eta / (3 xi + eta) (paper, after eq. 4).
double viscous_modulus(const Material& m);

// Viscous Poisson ratio s = (3 xi - 2 eta) / (2 (3 xi + eta)).
// The paper prints (3 xi - 3 eta); SPEC-NOTES corrects it: B mirrors Young's
// modulus written with bulk and shear moduli, whose Poisson ratio is
// (3K - 2 mu) / (2 (3K + mu)).
double viscous_poisson_ratio(const Material& m);

// Reason why a material is physically impossible, or empty if it is fine.
std::string material_problem(const Material& m);

}  // namespace tumble
