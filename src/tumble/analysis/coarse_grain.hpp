// SPDX-License-Identifier: MIT
// Continuum fields from grains by coarse-graining (Goldhirsch 2010,
// Granular Matter 12:239; Weinhart, Thornton, Luding & Bokhove 2012,
// Granular Matter 14:289): every grain spreads its mass, momentum and
// velocity fluctuations over space with a kernel W of width w, every
// contact its force along its branch vector. The fields satisfy mass and
// momentum balance exactly (to the quadrature of the branch integral,
// below), whatever w. docs/FIELDS.md explains them and shows the width
// dependence.
//
// Units: SI throughout. W has units 1/m^D, D the number of axes the grid
// resolves (the others are averaged over the grid's extent along them).
//
// Sign conventions: stresses are positive in compression (the granular
// convention), so that the pressure of a bed at rest is p > 0 and its
// momentum balance reads div(sigma) = rho g. A contact's force f is the
// force ON grain i; its branch vector b points from the other end (the
// centre of grain j, or the contact point with a wall) TO the centre of i:
// b = r_i - r_j = (R_i + R_j - h) n for a pair, with n the unit normal
// from j to i of the contact law (contact/geometry.hpp). A repulsive
// contact has f . b > 0 and adds compression.
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "tumble/core/vec3.hpp"

namespace tumble::analysis {

enum class CgKernel {
    // exp(-r^2 / 2w^2), cut off at r = 3w, normalised over the ball of
    // radius 3w (not over all space), so that the integral of W is exactly 1.
    gaussian,
    // Lucy's polynomial (1 + 3u)(1 - u)^3, u = r / c, with the same reach
    // c = 3w: smooth (its value and slope vanish at c); per axis its standard
    // deviation is c / sqrt(12) = 0.87 w in 3-D.
    lucy,
};

// The grid of the fields: nodes at the centres of cells[k] equal cells
// between lo[k] and hi[k] along each axis k. An averaged axis has one cell:
// the fields are averages over [lo, hi) along it (each grain and each point
// of a branch counts if it lies there, with the weight 1 / (hi - lo)), and
// the kernel acts in the other axes only.
//
// A periodic averaged axis: [lo, hi) is a period of the grains (a periodic
// domain's box), and every grain and every point of a branch counts at its
// position taken into [lo, hi) by whole periods, so that a branch across
// the boundary counts whole. (Along a resolved axis the grid is not
// wrapped: within 3w of a periodic boundary the fields miss the images.)
struct CgGrid {
    Vec3 lo, hi;                        // m
    std::array<std::size_t, 3> cells{};  // >= 1 each; 1 on an averaged axis
    std::array<bool, 3> averaged{};
    std::array<bool, 3> periodic{};     // only on an averaged axis

    std::size_t nodes() const { return cells[0] * cells[1] * cells[2]; }
    double spacing(int k) const { return (hi[k] - lo[k]) / static_cast<double>(cells[k]); }
    // Node (a, b, c) is a + cells[0] (b + cells[1] c).
    Vec3 node(std::size_t a, std::size_t b, std::size_t c) const;
};

struct CgSettings {
    CgGrid grid;
    CgKernel kernel = CgKernel::gaussian;
    double width = 0.0;  // w, m (the Gaussian's standard deviation)
};

// What is wrong with the settings, naming the setting ("width", "hi",
// "cells"), the reason and the value; "" if nothing. Checked by
// FieldAccumulator before it allocates anything.
std::string cg_settings_problem(const CgSettings& s);

// The bytes FieldAccumulator and the Fields it finishes hold at most for a
// grid of `nodes` nodes (what the memory limits compare), before any is
// allocated.
double cg_memory_bytes(std::size_t nodes);

// The grains of one state. Every span has one entry per grain.
struct CgGrains {
    std::span<const Vec3> position;  // m
    std::span<const Vec3> velocity;  // m/s
    std::span<const double> mass;    // kg
    std::span<const double> radius;  // m (the solid volume 4/3 pi R^3, the diameter 2R)
};

// One contact: the force on grain i, and its branch vector b (above). For
// a contact of two grains `j` is the other grain, and the branch runs from
// r_i - b (the centre of j, or of its periodic image) to r_i; for a wall
// contact j = wall and the branch runs from the contact point r_i - b.
struct CgContact {
    static constexpr std::size_t wall = std::numeric_limits<std::size_t>::max();
    std::size_t i = 0;
    std::size_t j = wall;
    Vec3 force;   // on i, N
    Vec3 branch;  // m
};

// A tensor by its nine components, row by row: (a, b) = c[3a + b], a and b
// 0, 1, 2 for x, y, z.
struct Tensor {
    std::array<double, 9> c{};
    double operator()(int a, int b) const { return c[static_cast<std::size_t>(3 * a + b)]; }
    double trace() const { return c[0] + c[4] + c[8]; }
};

// a += w t, component by component.
inline void add_scaled(Tensor& a, double w, const Tensor& t) {
    for (std::size_t k = 0; k < 9; ++k) a.c[k] += w * t.c[k];
}

// The fields on the grid's nodes (index as CgGrid::node), averaged over the
// samples given. The sums over grains and contacts are time-averaged
// (density, momentum, the stresses); the rest is derived from the averages.
struct Fields {
    CgGrid grid;
    std::size_t samples = 0;
    std::vector<double> density;         // rho = sum m_i W(r - r_i), kg/m^3
    std::vector<double> solid_fraction;  // phi = sum V_i W(r - r_i), V_i = 4/3 pi R_i^3, 1
    std::vector<double> diameter;        // mass-weighted mean grain diameter, sum m_i 2R_i W / rho, m
    std::vector<Vec3> momentum;          // j = sum m_i v_i W(r - r_i), kg/(m^2 s)
    std::vector<Vec3> velocity;          // V = j / rho, m/s (0 where rho = 0)
    // sum m_i v'_i v'_i W(r - r_i), v'_i = v_i - V(r_i) of the grain's own
    // sample (V carried to r_i by multilinear interpolation between the
    // nodes: a linear flow is reproduced, so a rigid rotation has none), Pa
    std::vector<Tensor> kinetic_stress;
    // sum over contacts f (x) b psi, (a, b) = f_a b_b psi, psi the integral
    // of W along the branch; not symmetric where the grains turn each other
    // (the tangential forces' couples), Pa
    std::vector<Tensor> contact_stress;
    std::vector<Tensor> stress;          // kinetic + contact, Pa
    std::vector<double> pressure;        // p = tr(stress) / 3, Pa
    // tau = sqrt(s:s / 2), s the deviatoric part of the symmetric part of
    // the stress, Pa
    std::vector<double> shear_stress;
    std::vector<double> temperature;     // T = tr(kinetic) / (3 rho), m^2/s^2
    // gamma_dot = sqrt(2 D':D'), D' the deviatoric part of the strain rate
    // (grad V + grad V^T) / 2 (central differences between nodes, one-sided
    // at the grid's edges; no gradient along an averaged axis), 1/s
    std::vector<double> shear_rate;
    // I = gamma_dot d / sqrt(p / rho_s), rho_s = rho / phi the grains' own
    // density; 0 where p <= 0
    std::vector<double> inertial_number;
    std::vector<double> friction;        // mu = tau / p; 0 where p <= 0
};

// gamma_dot = sqrt(2 D':D') of a velocity gradient G[k][l] = dV_l / dx_k, D'
// the deviatoric part of the strain rate D = (G + G^T) / 2, 1/s. A rigid
// rotation has none; a simple shear du_x/dy = g has |g|.
double shear_rate_of(const std::array<Vec3, 3>& G);

// I = gamma_dot d / sqrt(p / rho_s) at a node of `f` (rho_s = rho / phi the
// grains' own density), with the node's mean diameter d and pressure p; 0
// where p <= 0 or phi <= 0.
double inertial_number_at(const Fields& f, std::size_t node, double shear_rate);

// Sums the samples of a time average: add() one state at a time, finish()
// the fields of all added (the sums become the fields: the accumulator is
// left empty). The constructor checks the settings (cg_settings_problem;
// tumble::Error with the reason) and allocates its part of
// cg_memory_bytes(nodes).
class FieldAccumulator {
public:
    explicit FieldAccumulator(const CgSettings& settings);
    // One state: its grains and contacts (each contact's i and j index
    // `grains`). tumble::Error if an index is out of range, a span's length
    // differs from the positions', a number is not finite or a mass or
    // radius is negative.
    void add(const CgGrains& grains, std::span<const CgContact> contacts);
    Fields finish() &&;

    // The sums so far, to go on from elsewhere (a checkpoint): per node its
    // mass, volume, mass x diameter, momentum (3), kinetic (9) and contact
    // (9) stress sums, 24 numbers, node after node; and the samples added.
    std::vector<double> sums() const;
    static constexpr std::size_t sums_per_node = 24;
    std::size_t samples() const { return samples_; }
    // Goes on from sums() and samples() of an accumulator of the same
    // settings: the fields finished later are bit for bit those of one
    // accumulator that took every sample. tumble::Error if the length does
    // not fit the grid or a number is not finite.
    void restore(std::span<const double> sums, std::size_t samples);

private:
    CgSettings s_;
    std::size_t samples_ = 0;
    // The sums over samples: mass, volume, mass x diameter, momentum,
    // kinetic and contact stress (per node).
    std::vector<double> mass_, volume_, mass_diameter_;
    std::vector<Vec3> momentum_;
    std::vector<Tensor> kinetic_, contact_;
    // The sample at hand: its own density and momentum (its velocity field).
    std::vector<double> sample_mass_;
    std::vector<Vec3> sample_momentum_;
};

// The fields of one state.
Fields coarse_grain(const CgSettings& settings, const CgGrains& grains, std::span<const CgContact> contacts);

}  // namespace tumble::analysis
