// SPDX-License-Identifier: MIT
// The neighbour-search interface: all pairs (i < j by array index, not both
// kinematic) whose surfaces are closer than `skin`, i.e.
// |X_i - X_j + shift| < R_i + R_j + skin, with the periodic image of j.
// Two implementations: linked cells (fast) and brute force (reference).
#pragma once

#include <vector>

#include "tumble/neighbor/pair_list.hpp"
#include "tumble/neighbor/periodic_images.hpp"
#include "tumble/particles/particle_store.hpp"
#include "tumble/core/domain.hpp"

namespace tumble {

// O(N^2), for tests and debugging. Periodic axes use the minimum image.
void brute_force_pairs(const ParticleStore& p, const Domain& domain, double skin, PairList& out);

// Linked cells of edge >= 2 R_max + skin. Periodic axes need at least three
// cells (box length >= 3 (2 R_max + skin)), else tumble::Error. Positions on
// periodic axes must lie in [lo, hi). Pairs come grouped by first index, in
// increasing order of it, and by increasing second index within a group.
void cell_list_pairs(const ParticleStore& p, const Domain& domain, double skin, PairList& out);

// The particle indices sorted by the cell they lie in, the free particles
// first and then the kinematic ones: the order in which to store them so
// that neighbours are near in memory, and loops that treat the two kinds
// differently (the integrator, Simulation::move_kinematic) meet one kind,
// then the other, instead of a random mix their branches cannot predict.
std::vector<std::uint32_t> cell_order(const ParticleStore& p, const Domain& domain, double skin);

}  // namespace tumble
