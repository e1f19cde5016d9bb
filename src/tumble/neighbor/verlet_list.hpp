// SPDX-License-Identifier: MIT
// Verlet list with a skin over linked cells. Rebuilt only when some particle
// has moved more than half the skin since the last build (then no pair can
// have come into contact unseen). At a rebuild the particles may be re-sorted
// in cell order for cache reuse; contact history is carried over from the
// pair of the same two particles in the old list, so neither re-sorting nor
// rebuilding loses it.
#pragma once

#include <cstdint>
#include <vector>

#include "tumble/core/parallel.hpp"
#include "tumble/neighbor/candidate_pairs.hpp"
#include "tumble/neighbor/keyed_history.hpp"
#include "tumble/neighbor/pair_list.hpp"
#include "tumble/neighbor/periodic_images.hpp"
#include "tumble/core/domain.hpp"
#include "tumble/particles/particle_store.hpp"

namespace tumble {

// The neighbour list as it stands: the pairs refer to array indices of the
// particle store, in its current (sorted) order, so that the force loop
// visits the pairs in the same order after a restore.
struct NeighborState {
    PairList pairs;
    std::vector<Vec3> position_at_build;  // per array index, m
    std::int64_t builds = 0;
};

class VerletList {
public:
    VerletList() = default;
    VerletList(const Domain& domain, double skin, int sort_every);

    // Whether some particle has moved more than skin/2 since the last build
    // (true before the first build).
    bool needs_rebuild(const ParticleStore& p) const;
    // What needs_rebuild() compares, for loops that move the particles and
    // check them in the same pass: the positions at the last build, per
    // array index of a store of n particles (null before the first build,
    // or if the store then had another size: every particle has moved far),
    // and the square of the distance beyond which one has, (skin/2)^2.
    const Vec3* positions_at_build(std::size_t n) const {
        return position_at_build_.size() == n ? position_at_build_.data() : nullptr;
    }
    double rebuild_limit2() const { return 0.25 * skin_ * skin_; }
    // Wraps positions into periodic axes, sorts (every sort_every-th build),
    // rebuilds the pairs and carries the contact history over: as phases of
    // a team (core/parallel.hpp), or on one thread. The list and the
    // particle order are the same for every number of chunks.
    void rebuild(ParticleStore& p, Team& team);
    void rebuild(ParticleStore& p);

    // The rebuild of a simulation shared among ranks (sim/slabs.hpp), in two
    // calls between which the caller appends the ghosts (copies of other
    // ranks' spheres) after the rank's own spheres. arrange(): wraps and
    // sorts the store (the own spheres only). find_pairs(): the pairs among
    // the first `owned` spheres and between them and the ghosts (none
    // between two ghosts), each with its history from `histories`, a table
    // keyed by the spheres' places in p (keyed_by_place()).
    void arrange(ParticleStore& p, Team& team);
    void find_pairs(ParticleStore& p, std::size_t owned, const HistoryTable& histories, Team& team);

    PairList& pairs() { return pairs_; }
    const PairList& pairs() const { return pairs_; }
    const PeriodicImages& images() const { return images_; }
    double skin() const { return skin_; }
    std::int64_t builds() const { return builds_; }

    // The list as it stands, and its restoration (for checkpoints).
    NeighborState state() const { return {pairs_, position_at_build_, builds_}; }
    void restore(NeighborState state);

private:
    // Wraps positions into the periodic axes, then sorts the store in cell
    // order if this build sorts; returns whether it did (order_ then maps
    // new indices to old).
    bool wrap_and_sort(ParticleStore& p, Team& team);
    // The build done: the positions it saw, counted (phase of chunk c).
    void finish_build(const ParticleStore& p, Team& team, int c);

    Domain domain_;
    double skin_ = 0.0;
    int sort_every_ = 1;
    PeriodicImages images_;
    PairList pairs_;
    std::vector<Vec3> position_at_build_;
    std::int64_t builds_ = 0;
    // Working arrays of a build, kept for the next: the cell search's, the
    // list before the build with where each particle's pairs begin in it,
    // the sort's order and the store it sorts into.
    CellSearch search_;
    PairList previous_;
    std::vector<std::size_t> previous_start_;
    std::vector<std::uint32_t> order_;
    ParticleStore sorted_;
};

}  // namespace tumble
