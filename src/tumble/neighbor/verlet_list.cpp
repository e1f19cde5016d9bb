// SPDX-License-Identifier: MIT
#include "tumble/neighbor/verlet_list.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <utility>

#include "tumble/core/parallel.hpp"
#include "tumble/neighbor/candidate_pairs.hpp"

namespace tumble {

namespace {

// Key of an unordered pair of global ids (ids are below 2^32, see
// scenario_problem()).
std::uint64_t pair_key(std::int64_t a, std::int64_t b) {
    const auto lo = static_cast<std::uint64_t>(std::min(a, b));
    const auto hi = static_cast<std::uint64_t>(std::max(a, b));
    return (lo << 32) | hi;
}

// Periodic axes: bring every position back into [lo, hi). Kinematic
// particles remember the shift so their prescribed motion stays continuous.
void wrap_into_box(ParticleStore& p, const Domain& domain) {
    const Vec3 L = domain.length();
    for (std::size_t i = 0; i < p.size(); ++i)
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
    : domain_(domain), skin_(skin), sort_every_(sort_every), images_(domain.length()) {}

bool VerletList::needs_rebuild(const ParticleStore& p, int chunks) const {
    if (position_at_build_.size() != p.size()) return true;
    const double limit2 = 0.25 * skin_ * skin_;  // (skin/2)^2
    std::vector<char> moved(static_cast<std::size_t>(chunks), 0);
    for_each_chunk(chunks, [&](int c) {
        const IndexRange r = chunk_range(c, chunks, p.size());
        for (std::size_t i = r.begin; i < r.end; ++i)
            if (norm2(p.position[i] - position_at_build_[i]) > limit2) {
                moved[static_cast<std::size_t>(c)] = 1;
                return;
            }
    });
    return std::find(moved.begin(), moved.end(), 1) != moved.end();
}

void VerletList::rebuild(ParticleStore& p) {
    // Remember the history of every live contact by the global ids of its pair,
    // oriented as (lower id, higher id).
    std::unordered_map<std::uint64_t, ContactHistory> live;
    for (std::size_t k = 0; k < pairs_.size(); ++k) {
        const ContactHistory h = pairs_.history(k);
        if (h.is_zero()) continue;
        const std::int64_t a = p.id[pairs_.first[k]], b = p.id[pairs_.second[k]];
        live.emplace(pair_key(a, b), a < b ? h : h.swapped());
    }

    wrap_into_box(p, domain_);
    if (sort_every_ > 0 && builds_ % sort_every_ == 0) p.permute(cell_order(p, domain_, skin_));
    cell_list_pairs(p, domain_, skin_, pairs_);

    if (!live.empty())
        for (std::size_t k = 0; k < pairs_.size(); ++k) {
            const std::int64_t a = p.id[pairs_.first[k]], b = p.id[pairs_.second[k]];
            const auto found = live.find(pair_key(a, b));
            if (found != live.end()) pairs_.set_history(k, a < b ? found->second : found->second.swapped());
        }

    position_at_build_ = p.position;
    ++builds_;
}

void VerletList::restore(NeighborState state) {
    pairs_ = std::move(state.pairs);
    position_at_build_ = std::move(state.position_at_build);
    builds_ = state.builds;
}

}  // namespace tumble
