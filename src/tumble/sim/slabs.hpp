// SPDX-License-Identifier: MIT
// One simulation shared among the ranks of the MPI world (docs/PARALLEL.md):
// the domain cut into slabs along one axis, one slab per rank. A rank owns
// the spheres whose centre lies in its slab, integrates them, and holds
// copies (ghosts) of the other ranks' spheres within `reach` = 2 R_max +
// skin of its slab, refreshed every step. A pair of an own sphere and a ghost
// is computed on both ranks, each keeping the force on its own sphere: no
// forces travel back. At each neighbour-list rebuild the spheres that left a
// slab migrate to the neighbour's, with their contact histories keyed by
// global id (neighbor/keyed_history.hpp), and the ghosts are chosen anew.
//
// The store of a rank: its own spheres first (sorted in cell order as in one
// rank), then the ghosts from the rank below, then those from the rank
// above. Slabs are at least `reach` wide, so ghosts come from the two
// neighbours only, and a sphere, which moves less than skin/2 between
// rebuilds, migrates at most one slab. Along a periodic axis the first and
// last slabs are neighbours and what crosses the period is shifted by its
// length.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "tumble/contact/history.hpp"
#include "tumble/core/domain.hpp"
#include "tumble/neighbor/keyed_history.hpp"
#include "tumble/neighbor/pair_list.hpp"
#include "tumble/particles/particle_store.hpp"

namespace tumble {

// What a checkpoint of one rank keeps of its slab: the cuts (they move, see
// rebalance()), the ghosts it sends each step and where those it receives
// lie in its store (below, above).
struct SlabState {
    std::vector<double> cuts;  // ranks + 1, m
    std::array<std::vector<std::uint32_t>, 2> send;
    std::array<std::size_t, 2> receive_begin{}, receive_count{};
};

class Slabs {
public:
    // Cuts along `axis` placed at the quantiles of the spheres' coordinates
    // in `all` (the whole scenario, the same on every rank), a grain
    // weighing 1 and a kinematic sphere 0.2 (what it costs, measured), so
    // that every slab starts with as much work as can be. The end slabs reach to
    // infinity on an open axis and to the box on a periodic one. Throws
    // tumble::Error if a slab with two cuts would be narrower than `reach`.
    Slabs(const Domain& domain, int axis, const ParticleStore& all, double reach);

    int axis() const { return axis_; }
    const std::vector<double>& cuts() const { return state_.cuts; }
    double lo() const { return state_.cuts[static_cast<std::size_t>(rank_)]; }
    double hi() const { return state_.cuts[static_cast<std::size_t>(rank_) + 1]; }

    // Collective, at a rebuild before migrate(), with the pairs of the
    // list about to be replaced (their first sphere is an own one): if the
    // heaviest slab is more than 2 % above the mean, the inner cuts move to
    // the weighted quantiles of the spheres' present coordinates. A sphere
    // weighs what its step costs (measured, slabs.cpp): a grain 1, a
    // kinematic sphere 0.85, plus 0.85 for each pair it is the first of.
    // The weights come from a histogram of 1,024 bins summed over the ranks
    // in whole counts, so that every rank finds the same cuts. Each cut
    // moves by at most half the narrower slab beside it (a sphere then
    // changes owner only to a neighbour) and never to a slab narrower than
    // the reach. Returns whether the cuts moved. The simulation calls it
    // every `rebalance_every` rebuilds.
    static constexpr int rebalance_every = 50;
    bool rebalance(const ParticleStore& p, std::size_t owned, const PairList& pairs);
    // The domain a rank's neighbour search sees: not periodic along the
    // axis (ghosts carry their image).
    Domain local_domain() const;

    // The spheres of the slab, from a store of all spheres.
    void keep_own(ParticleStore& p) const;
    // At a rebuild, on the own spheres (no ghosts in p): those that left the
    // slab go to the neighbour with their histories (of pairs and of the
    // walls, wall_slots per sphere at wall_slots id + slot); those that arrive are appended, their
    // histories to `histories` (after the rank's own: a pair it computed
    // itself keeps its record, HistoryTable) and into `wall_history` and
    // `wall_feature` (the mesh feature each wall slot follows).
    void migrate(ParticleStore& p, std::vector<KeyedHistory>& histories, std::vector<ContactHistory>& wall_history,
                 std::vector<std::uint32_t>& wall_feature, std::size_t wall_slots);
    // After the sort: copies of the own spheres within reach of each cut go
    // to the neighbours; theirs are appended as ghosts.
    void make_ghosts(ParticleStore& p);
    // Every step, after the drift: the ghosts' positions, velocities and
    // half kicks from their owners; their forces zero (never used).
    void update_ghosts(ParticleStore& p, std::size_t owned);

    // What this rank has sent, for the measurement of the communication
    // (docs/BENCHMARKS.md): the ghost updates of the steps, and the
    // migrations and ghost lists of the rebuilds.
    struct Traffic {
        std::int64_t updates = 0, update_bytes = 0;
        std::int64_t rebuilds = 0, rebuild_bytes = 0;
    };
    const Traffic& traffic() const { return traffic_; }

    // Collective: the own spheres of every rank (the first `owned` of each
    // store), on rank 0 in the order of their global ids; empty elsewhere.
    // With `which`, only the spheres it picks (by index in the store), and
    // with Everywhere::yes on every rank.
    enum class Everywhere { no, yes };
    ParticleStore gather_own(const ParticleStore& p, std::size_t owned,
                             const std::function<bool(std::size_t)>& which = {},
                             Everywhere everywhere = Everywhere::no) const;

    SlabState state() const { return state_; }
    void restore(SlabState state) { state_ = std::move(state); }

private:
    struct Side {
        int rank = -1;       // neighbour rank, -1: none
        double shift = 0.0;  // added to the axis coordinate of what is sent (periodic wrap), m
    };
    Domain domain_;
    int axis_ = 2;
    double reach_ = 0.0;
    int rank_ = 0, ranks_ = 1;
    std::array<Side, 2> side_{};    // 0: below, 1: above
    SlabState state_;
    Traffic traffic_;
};

}  // namespace tumble
