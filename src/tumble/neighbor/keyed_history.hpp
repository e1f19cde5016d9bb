// SPDX-License-Identifier: MIT
// Contact histories keyed by the global ids of the two spheres, for a
// neighbour list whose spheres change between builds (one simulation shared
// among ranks, sim/slabs.hpp: spheres arrive from and leave for other
// ranks, ghosts come and go). Within one rank VerletList carries the history
// over by array index, which needs no table.
#pragma once

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
};

// The non-zero histories of a list over the spheres of p, in list order.
inline std::vector<KeyedHistory> keyed_histories(const ParticleStore& p, const PairList& pairs) {
    std::vector<KeyedHistory> all;
    all.reserve(pairs.size());  // at most one a pair: the room made once, not copied as it grows
    for (std::size_t k = 0; k < pairs.size(); ++k) {
        const ContactHistory h = pairs.history(k);
        if (h.is_zero()) continue;
        const std::int64_t a = p.id[pairs.first[k]], b = p.id[pairs.second[k]];
        all.push_back(a < b ? KeyedHistory{a, b, h} : KeyedHistory{b, a, h.swapped()});
    }
    return all;
}

// The records keyed by the spheres' places in p instead of their global
// ids (`ids` of them, 0 .. ids-1): lo < hi are indices into p and the
// history is seen from lo; the records of a sphere p does not hold are left
// out, the others keep their order. A table of these is read in the order of
// a list found on p (by first index, which is spatial once p is sorted),
// where one keyed by global ids is read at random: the lookups of a rebuild
// across ranks took 19 ns a pair that way (studies/performance/LOG.md, "Time by
// phase").
inline std::vector<KeyedHistory> keyed_by_place(const std::vector<KeyedHistory>& records, const ParticleStore& p,
                                                std::size_t ids) {
    constexpr std::uint32_t absent = UINT32_MAX;
    std::vector<std::uint32_t> place(ids, absent);
    for (std::size_t i = 0; i < p.size(); ++i) place[static_cast<std::size_t>(p.id[i])] = static_cast<std::uint32_t>(i);
    std::vector<KeyedHistory> local;
    local.reserve(records.size());
    for (const KeyedHistory& r : records) {
        const std::uint32_t a = place[static_cast<std::size_t>(r.lo)], b = place[static_cast<std::size_t>(r.hi)];
        if (a == absent || b == absent) continue;
        local.push_back(a < b ? KeyedHistory{a, b, r.history} : KeyedHistory{b, a, r.history.swapped()});
    }
    return local;
}

// Histories looked up by the two global ids (or places, keyed_by_place()): the records grouped by their
// lower id (a counting sort over the ids 0 .. ids-1, which the global ids
// are), each group scanned for the higher id. A sphere has a dozen contacts
// at most, so a lookup reads a few records; building the table is linear in
// the records and the ids, where a sort of the records was the dearest part
// of a rebuild across ranks.
class HistoryTable {
public:
    // Of two records of one pair, the earlier in `records` is kept.
    void build(const std::vector<KeyedHistory>& records, std::size_t ids) {
        start_.assign(ids + 1, 0);
        for (const KeyedHistory& r : records) ++start_[static_cast<std::size_t>(r.lo) + 1];
        for (std::size_t i = 0; i < ids; ++i) start_[i + 1] += start_[i];
        grouped_.resize(records.size());
        std::vector<std::uint32_t> next(start_.begin(), start_.end() - 1);
        for (const KeyedHistory& r : records) grouped_[next[static_cast<std::size_t>(r.lo)]++] = r;
    }
    // The history of spheres a and b (global ids, or places) seen from a; zero if none.
    ContactHistory find(std::int64_t a, std::int64_t b) const {
        const std::int64_t lo = a < b ? a : b, hi = a < b ? b : a;
        const auto l = static_cast<std::size_t>(lo);
        for (std::uint32_t k = start_[l]; k < start_[l + 1]; ++k)
            if (grouped_[k].hi == hi) return a < b ? grouped_[k].history : grouped_[k].history.swapped();
        return {};
    }

private:
    std::vector<std::uint32_t> start_;   // per lower id: its first record in grouped_
    std::vector<KeyedHistory> grouped_;  // the records by lower id, in their order within a group
};

}  // namespace tumble
