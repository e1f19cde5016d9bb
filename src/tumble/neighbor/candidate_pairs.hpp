// SPDX-License-Identifier: MIT
// The neighbour-search interface: all pairs (i < j by array index, not both
// kinematic) whose surfaces are closer than `skin`, i.e.
// |X_i - X_j + shift| < R_i + R_j + skin, with the periodic image of j.
// Two implementations: linked cells (fast) and brute force (reference).
#pragma once

#include <cstdint>
#include <vector>

#include "tumble/core/parallel.hpp"
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
// increasing order of it, and by increasing second index within a group;
// every pair's history is zero. The work is split into `chunks` parts (run
// on as many threads); the list is the same for every count.
void cell_list_pairs(const ParticleStore& p, const Domain& domain, double skin, PairList& out, int chunks = 1);

// The particle indices sorted by the cell they lie in, the free particles
// first and then the kinematic ones: the order in which to store them so
// that neighbours are near in memory, and loops that treat the two kinds
// differently (the integrator, Simulation::move_kinematic) meet one kind,
// then the other, instead of a random mix their branches cannot predict.
// The same for every chunk count.
std::vector<std::uint32_t> cell_order(const ParticleStore& p, const Domain& domain, double skin, int chunks = 1);

// The two above as phases of a team (core/parallel.hpp), with the working
// arrays they share kept from one build to the next. Both are counting
// sorts by cell done in parallel: each chunk counts its particles per cell,
// the counts are added up in (cell, chunk) order, and each chunk places its
// particles in that order, so the result is the serial sort's whatever the
// number of chunks. The pairs of each part of the particles are then found
// on their own and joined in the order of the parts.
class CellSearch {
public:
    // The pairs whose first particle is one of the first `first_end` (an
    // MPI rank's own spheres: the ghosts after them pair only with those).
    void find_pairs(const ParticleStore& p, const Domain& domain, double skin, std::size_t first_end, Team& team,
                    PairList& out);
    void sort_order(const ParticleStore& p, const Domain& domain, double skin, Team& team,
                    std::vector<std::uint32_t>& order);

    // What a chunk of the particles spans (for the cell grid).
    struct Extent {
        bool empty = true;  // no own particle (lo, hi unset)
        Vec3 lo, hi;
        bool finite = true;
        double largest_radius = 0.0;
        std::size_t free_end = 0;  // one past its last free particle (0: none)
        std::size_t first_kinematic = SIZE_MAX;  // its first kinematic particle (SIZE_MAX: none)
    };

private:
    // The pairs found in one part of the particles. Each on its own cache
    // lines: the chunks' threads push onto their parts at once, and two
    // parts' vectors sharing a line (96 bytes each) had the threads take
    // it from each other at every pair found, which made the search 1.5
    // times slower per thread on two threads than on one
    // (studies/performance/LOG.md, "The search's parts on one cache line").
    struct alignas(64) Part {
        std::vector<std::uint32_t> first, second;
        std::vector<std::uint8_t> image;
        std::vector<std::uint64_t> near;  // working array: the candidates of one particle
    };
    // The particles 0 .. particles-1 sorted by bin (key_, set before),
    // stably, into `sorted`; start_ gets each bin's first place in it.
    void counting_sort(std::size_t particles, std::size_t bins, Team& team, std::vector<std::uint32_t>& sorted);
    // Sizes the arrays; extents_ of each chunk of the particles, their
    // bounding box that of the first own_end only (an MPI rank's own
    // spheres: the grid is then the one its own were sorted in, and a
    // ghost outside it falls in a cell at its edge, which is next to the
    // cell of every own sphere within one cell width of it).
    void measure(const ParticleStore& p, std::size_t own_end, Team& team);

    std::vector<Extent> extents_;                  // per chunk
    std::vector<std::uint32_t> key_;               // per particle: its bin
    std::vector<std::vector<std::uint32_t>> count_;  // per chunk, per bin: its particles, then where they go
    std::vector<std::size_t> chunk_total_;         // per chunk of the bins: the particles in them
    std::vector<char> chunk_in_order_;             // per chunk: its particles' bins do not decrease
    std::vector<std::uint32_t> start_, members_;   // per bin: first place in members_; particles by bin
    std::vector<std::uint8_t> near_late_free_;     // per cell: next to a free particle after a kinematic one
    std::vector<Part> parts_;                      // per chunk
};

}  // namespace tumble
