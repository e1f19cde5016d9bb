// SPDX-License-Identifier: MIT
// Contact histories keyed by the global ids of the two spheres, for a
// neighbour list whose spheres change between builds (one simulation shared
// among ranks, sim/slabs.hpp: spheres arrive from and leave for other
// ranks, ghosts come and go). Within one rank VerletList carries the history
// over by array index, which is faster and needs no table.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "tumble/contact/history.hpp"
#include "tumble/neighbor/pair_list.hpp"
#include "tumble/particles/particle_store.hpp"

namespace tumble {

// The history of the contact of spheres lo < hi (global ids), seen from lo.
struct KeyedHistory {
    std::int64_t lo = 0, hi = 0;
    ContactHistory history;
    bool operator<(const KeyedHistory& o) const { return lo != o.lo ? lo < o.lo : hi < o.hi; }
};

// Sorted by (lo, hi), each key once.
using KeyedHistories = std::vector<KeyedHistory>;

// The non-zero histories of a list over the spheres of p.
inline KeyedHistories keyed_histories(const ParticleStore& p, const PairList& pairs) {
    KeyedHistories all;
    for (std::size_t k = 0; k < pairs.size(); ++k) {
        const ContactHistory h = pairs.history(k);
        if (h.is_zero()) continue;
        const std::int64_t a = p.id[pairs.first[k]], b = p.id[pairs.second[k]];
        all.push_back(a < b ? KeyedHistory{a, b, h} : KeyedHistory{b, a, h.swapped()});
    }
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end(),
                          [](const KeyedHistory& x, const KeyedHistory& y) { return x.lo == y.lo && x.hi == y.hi; }),
              all.end());
    return all;
}

// Records of `more` whose key `into` lacks join it (those it has are kept
// as they are); `into` stays sorted.
inline void merge_histories(KeyedHistories& into, const KeyedHistories& more) {
    const std::size_t had = into.size();
    for (const KeyedHistory& r : more)
        if (!std::binary_search(into.begin(), into.begin() + static_cast<std::ptrdiff_t>(had), r)) into.push_back(r);
    std::sort(into.begin(), into.end());
}

// The history of spheres a and b (global ids) seen from a; zero if none.
inline ContactHistory find_history(const KeyedHistories& all, std::int64_t a, std::int64_t b) {
    const KeyedHistory key{std::min(a, b), std::max(a, b), {}};
    const auto found = std::lower_bound(all.begin(), all.end(), key);
    if (found == all.end() || found->lo != key.lo || found->hi != key.hi) return {};
    return a < b ? found->history : found->history.swapped();
}

}  // namespace tumble
