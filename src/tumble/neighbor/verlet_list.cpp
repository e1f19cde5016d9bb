// SPDX-License-Identifier: MIT
#include "tumble/neighbor/verlet_list.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "tumble/core/parallel.hpp"
#include "tumble/neighbor/candidate_pairs.hpp"

namespace tumble {

namespace {

// Periodic axes: bring every position of range r back into [lo, hi).
// Kinematic particles remember the shift so their prescribed motion stays
// continuous.
void wrap_into_box(ParticleStore& p, const Domain& domain, IndexRange r) {
    const Vec3 L = domain.length();
    for (std::size_t i = r.begin; i < r.end; ++i)
        for (int k = 0; k < 3; ++k) {
            if (!domain.periodic[k]) continue;
            const double wraps = std::floor((p.position[i][k] - domain.lo[k]) / L[k]);
            if (wraps == 0.0) continue;
            p.position[i][k] -= wraps * L[k];
            if (p.position[i][k] >= domain.hi[k]) p.position[i][k] = domain.lo[k];  // round-off at hi
            p.image_shift[i][k] -= wraps * L[k];
        }
}

}  // namespace

VerletList::VerletList(const Domain& domain, double skin, int sort_every)
    : domain_(domain), skin_(skin), sort_every_(sort_every), images_(domain) {}

// The check as a pass of its own over the store. The time step does not
// use it: the loops that move the particles count those gone far as they
// move them (integrate/velocity_verlet.hpp, DisplacementLimit), with these
// sums.
bool VerletList::needs_rebuild(const ParticleStore& p) const {
    const Vec3* at_build = positions_at_build(p.size());
    if (!at_build) return true;
    for (std::size_t i = 0; i < p.size(); ++i)
        if (norm2(p.position[i] - at_build[i]) > rebuild_limit2()) return true;
    return false;
}

void VerletList::rebuild(ParticleStore& p) {
    run_in_team(1, [&](Team& team) { rebuild(p, team); });
}

bool VerletList::wrap_and_sort(ParticleStore& p, Team& team) {
    const std::size_t n = p.size();
    const bool sort = sort_every_ > 0 && builds_ % sort_every_ == 0;
    team.each([&](int c) {
        wrap_into_box(p, domain_, team.range(c, n));
        if (c == 0 && sort) sorted_.resize(n);  // the arrays to sort into
    });
    if (sort) {
        search_.sort_order(p, domain_, skin_, team, order_);
        team.each([&](int c) { sorted_.gather(p, order_, team.range(c, n)); });
        team.one([&] { std::swap(p, sorted_); });
    }
    return sort;
}

void VerletList::finish_build(const ParticleStore& p, Team& team, int c) {
    const IndexRange particles = team.range(c, p.size());
    std::copy(p.position.begin() + static_cast<std::ptrdiff_t>(particles.begin),
              p.position.begin() + static_cast<std::ptrdiff_t>(particles.end),
              position_at_build_.begin() + static_cast<std::ptrdiff_t>(particles.begin));
    if (c == 0) ++builds_;
}

// Every phase splits particles or pairs between the chunks; none has a part
// that one thread does for all particles. The contact history is carried
// over by array index, not by a table of global ids: the old list is kept,
// with where each particle's pairs begin in it, and the new pair (i, j) finds
// the old pair of the same two particles (their indices before the sort,
// order_) by a binary search among the few pairs of the lower one.
void VerletList::rebuild(ParticleStore& p, Team& team) {
    const std::size_t n = p.size();
    team.one([&] {
        std::swap(pairs_, previous_);
        previous_start_.resize(n + 1);
        position_at_build_.resize(n);
    });
    team.each([&](int c) {  // one search for the chunk's first particle, then a walk along the old list
        const IndexRange r = team.range(c, n);
        const std::vector<std::uint32_t>& first = previous_.first;
        auto k = static_cast<std::size_t>(
            std::lower_bound(first.begin(), first.end(), static_cast<std::uint32_t>(r.begin)) - first.begin());
        for (std::size_t i = r.begin; i < r.end; ++i) {
            while (k < first.size() && first[k] < i) ++k;
            previous_start_[i] = k;
        }
        if (c == team.chunks() - 1) previous_start_[n] = previous_.size();
    });
    const bool sort = wrap_and_sort(p, team);
    search_.find_pairs(p, domain_, skin_, p.size(), team, pairs_);
    team.each([&](int c) {
        const IndexRange r = team.range(c, pairs_.size());
        for (std::size_t k = r.begin; k < r.end; ++k) {
            const std::uint32_t a = sort ? order_[pairs_.first[k]] : pairs_.first[k];
            const std::uint32_t b = sort ? order_[pairs_.second[k]] : pairs_.second[k];
            const std::uint32_t lo = std::min(a, b), hi = std::max(a, b);
            const auto group = previous_.second.begin();
            const auto from = group + static_cast<std::ptrdiff_t>(previous_start_[lo]);
            const auto to = group + static_cast<std::ptrdiff_t>(previous_start_[lo + 1]);
            const auto found = std::lower_bound(from, to, hi);
            if (found == to || *found != hi) continue;  // a new pair: zero history
            // The old pair had the lower old index first; its history is seen
            // from that particle.
            const ContactHistory h = previous_.history(static_cast<std::size_t>(found - group));
            pairs_.set_history(k, a < b ? h : h.swapped());
        }
        finish_build(p, team, c);
    });
}

void VerletList::arrange(ParticleStore& p, Team& team) { wrap_and_sort(p, team); }

// The ghosts lie after the own spheres: the search takes pairs that start
// at an own sphere only (two ghosts' pair is their owners' business).
void VerletList::find_pairs(ParticleStore& p, std::size_t owned, const HistoryTable& histories, Team& team) {
    search_.find_pairs(p, domain_, skin_, owned, team, pairs_);
    team.one([&] { position_at_build_.resize(p.size()); });
    team.each([&](int c) {
        const IndexRange r = team.range(c, pairs_.size());
        for (std::size_t k = r.begin; k < r.end; ++k)
            pairs_.set_history(k, histories.find(pairs_.first[k], pairs_.second[k]));
        finish_build(p, team, c);
    });
}

void VerletList::restore(NeighborState state) {
    pairs_ = std::move(state.pairs);
    position_at_build_ = std::move(state.position_at_build);
    builds_ = state.builds;
}

}  // namespace tumble
