// SPDX-License-Identifier: MIT
// Neighbour search against references (STYLE habit 7): the linked-cell list
// against the brute-force list and against an independent all-images search
// written here; the Verlet list's half-skin trigger, its history transfer by
// global id across re-sorts, its periodic wrap; and, in a running
// simulation, that no contact is ever missing from the list.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "tumble/core/error.hpp"
#include "tumble/neighbor/candidate_pairs.hpp"
#include "tumble/neighbor/keyed_history.hpp"
#include "tumble/neighbor/verlet_list.hpp"
#include "tumble/setup/generators.hpp"
#include "tumble/setup/paper_materials.hpp"
#include "tumble/sim/particle_setup.hpp"
#include "tumble/sim/simulation.hpp"

namespace tumble {
namespace {

double uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// A pair as a set element: (lower id, higher id, image code of the higher-id
// particle seen from the lower-id one). A pair (i, j, code) has
// d = X_i - X_j + shift(code); swapped, d' = -d needs shift(-s), code 26 - code.
using PairKey = std::tuple<std::int64_t, std::int64_t, int>;

PairKey key_of(const ParticleStore& p, std::uint32_t i, std::uint32_t j, std::uint8_t code) {
    const std::int64_t a = p.id[i], b = p.id[j];
    return a < b ? PairKey{a, b, code} : PairKey{b, a, 26 - code};
}

std::set<PairKey> key_set(const ParticleStore& p, const PairList& list) {
    std::set<PairKey> keys;
    for (std::size_t k = 0; k < list.size(); ++k) keys.insert(key_of(p, list.first[k], list.second[k], list.image[k]));
    return keys;
}

// Independent reference: every pair not both kinematic, every periodic image
// on the periodic axes, |X_i - X_j + shift| < R_i + R_j + skin.
std::set<PairKey> reference_pairs(const ParticleStore& p, const Domain& domain, double skin) {
    const PeriodicImages images(domain);
    std::set<PairKey> keys;
    for (std::uint32_t i = 0; i < p.size(); ++i)
        for (std::uint32_t j = i + 1; j < p.size(); ++j) {
            if (p.is_kinematic(i) && p.is_kinematic(j)) continue;
            const double range = p.radius[i] + p.radius[j] + skin;
            for (int sz = -1; sz <= 1; ++sz)
                for (int sy = -1; sy <= 1; ++sy)
                    for (int sx = -1; sx <= 1; ++sx) {
                        if ((sx && !domain.periodic[0]) || (sy && !domain.periodic[1]) || (sz && !domain.periodic[2]))
                            continue;
                        const std::uint8_t code = image_code(sx, sy, sz);
                        if (norm2(p.position[i] - p.position[j] + images[code]) < range * range)
                            keys.insert(key_of(p, i, j, code));
                    }
        }
    return keys;
}

// A random cloud of `count` spheres (overlaps allowed) with radii in
// [r_min, r_max], about a tenth of them kinematic, ids shuffled against the
// array order.
ParticleStore random_store(const Domain& domain, std::size_t count, double r_min, double r_max, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    Scenario s;
    s.materials = paper::materials();
    s.motions = {RigidMotion{}};
    for (std::size_t k = 0; k < count; ++k) {
        ParticleSpec spec;
        for (int a = 0; a < 3; ++a) spec.position[a] = domain.lo[a] + uniform(rng) * (domain.hi[a] - domain.lo[a]);
        for (int a = 0; a < 3; ++a)  // round-off may land on hi; keep [lo, hi)
            if (spec.position[a] >= domain.hi[a]) spec.position[a] = domain.lo[a];
        spec.radius = r_min + (r_max - r_min) * uniform(rng);
        spec.material = static_cast<std::int32_t>(k % 2);
        if (uniform(rng) < 0.1) spec.motion = 0;
        s.particles.push_back(spec);
    }
    ParticleStore p = make_particle_store(s);
    std::vector<std::uint32_t> order(p.size());
    std::iota(order.begin(), order.end(), 0u);
    std::shuffle(order.begin(), order.end(), rng);
    p.permute(order);
    return p;
}

Domain box(double edge, std::array<bool, 3> periodic) {
    Domain d;
    d.lo = {-0.5 * edge, 0.0, 0.3 * edge};
    d.hi = d.lo + Vec3{edge, edge, edge};
    d.periodic = periodic;
    return d;
}

void expect_same_pairs(const ParticleStore& p, const Domain& domain, double skin) {
    PairList cells, brute;
    cell_list_pairs(p, domain, skin, cells);
    brute_force_pairs(p, domain, skin, brute);
    const std::set<PairKey> reference = reference_pairs(p, domain, skin);
    // Pairs must exist at all, or the comparison proves nothing.
    ASSERT_GT(reference.size(), p.size() / 4);

    const std::set<PairKey> cell_keys = key_set(p, cells);
    EXPECT_EQ(cell_keys.size(), cells.size()) << "duplicate pairs in the cell list";
    EXPECT_EQ(cell_keys, reference);
    EXPECT_EQ(key_set(p, brute), reference);
    EXPECT_EQ(brute.size(), reference.size());

    for (std::size_t k = 0; k < cells.size(); ++k) {
        EXPECT_LT(cells.first[k], cells.second[k]);
        EXPECT_FALSE(p.is_kinematic(cells.first[k]) && p.is_kinematic(cells.second[k]));
        EXPECT_TRUE(cells.history(k).is_zero());
        if (k > 0) {
            EXPECT_LE(cells.first[k - 1], cells.first[k]) << "pairs not grouped by first index";
        }
    }
}

// Sphere radii 0.5-1.5 mm, skin 0.3 mm: cutoff 3.3 mm, a 30 mm box has 9
// cells per axis; 1000 spheres give a few thousand candidate pairs.
constexpr double r_min = 0.5e-3, r_max = 1.5e-3, skin = 0.3e-3, edge = 30e-3;

TEST(Neighbor, CellListMatchesBruteForceOpen) {
    ParticleStore p = random_store(box(edge, {false, false, false}), 1000, r_min, r_max, 1);
    expect_same_pairs(p, box(edge, {false, false, false}), skin);
    // A stray particle far away must not break the grid.
    p.position[17] = {1.0, -2.0, 3.0};
    expect_same_pairs(p, box(edge, {false, false, false}), skin);
}

TEST(Neighbor, CellListMatchesBruteForcePeriodicInX) {
    const Domain d = box(edge, {true, false, false});
    expect_same_pairs(random_store(d, 1000, r_min, r_max, 2), d, skin);
}

TEST(Neighbor, CellListMatchesBruteForcePeriodicInXAndZ) {
    const Domain d = box(edge, {true, false, true});
    expect_same_pairs(random_store(d, 1000, r_min, r_max, 3), d, skin);
}

TEST(Neighbor, CellListMatchesBruteForcePeriodicInAllAxes) {
    const Domain d = box(edge, {true, true, true});
    expect_same_pairs(random_store(d, 1000, r_min, r_max, 4), d, skin);
}

TEST(Neighbor, CellListMatchesBruteForceInTheSmallestPeriodicBox) {
    // Three cells per axis (10 mm >= 3 x 3.3 mm): every neighbour cell is
    // reached through an image, and a dense cloud so pairs are plentiful.
    const Domain d = box(10e-3, {true, true, true});
    expect_same_pairs(random_store(d, 150, r_min, r_max, 5), d, skin);
}

TEST(Neighbor, CellListMatchesBruteForceInAVastPeriodicBox) {
    // A cloud of 1000 in 30 mm, split across the corner of a box periodic
    // in x and y 100 m wide: cells of one cutoff would be 9 x 10^8 (it asked
    // for gigabytes, std::bad_alloc); fewer, wider cells find the same pairs.
    ParticleStore p = random_store(box(edge, {false, false, false}), 1000, r_min, r_max, 14);
    Domain d;
    d.lo = {-50.0, -50.0, 0.3 * edge};
    d.hi = {50.0, 50.0, 1.3 * edge};
    d.periodic = {true, true, false};
    const double middle[2] = {0.0, 0.5 * edge};  // of the cloud, in x and y
    for (Vec3& x : p.position)
        for (int a = 0; a < 2; ++a) {
            x[a] -= middle[a];
            x[a] += x[a] < 0.0 ? 50.0 : -50.0;  // the cloud's halves at the box's two ends
            if (x[a] >= d.hi[a]) x[a] = d.lo[a];
        }
    expect_same_pairs(p, d, skin);
}

// The store as the Verlet list leaves it at every build (sorted by cell,
// the free particles first): the search then takes the particles of a row
// of cells as one stretch of the store, which the shuffled stores above
// never reach. The order is checked to be the search's own (cell_order() of
// the sorted store is the identity), so that the test cannot pass on the
// cell-by-cell path alone.
ParticleStore in_cell_order(const ParticleStore& shuffled, const Domain& domain) {
    ParticleStore p = shuffled;
    p.permute(cell_order(shuffled, domain, skin));
    std::vector<std::uint32_t> identity(p.size());
    std::iota(identity.begin(), identity.end(), 0u);
    EXPECT_EQ(cell_order(p, domain, skin), identity);
    return p;
}

TEST(Neighbor, CellListMatchesBruteForceOnAStoreInCellOrder) {
    for (const auto periodic : {std::array<bool, 3>{false, false, false}, std::array<bool, 3>{true, false, false},
                                std::array<bool, 3>{true, true, true}}) {
        const Domain d = box(edge, periodic);
        expect_same_pairs(in_cell_order(random_store(d, 1000, r_min, r_max, 12), d), d, skin);
    }
    const Domain smallest = box(10e-3, {true, true, true});  // every row of cells wraps somewhere
    expect_same_pairs(in_cell_order(random_store(smallest, 150, r_min, r_max, 13), smallest), smallest, skin);
}

// An MPI rank's search (CellSearch::find_pairs with first_end): its own
// spheres, then ghosts, some beyond the own spheres' bounding box, which
// the grid spans. Every pair with an own sphere is found, no pair of two
// ghosts, whether the own spheres are in cell order (runs of cells) or
// shuffled (cell by cell), on 1 and 3 chunks.
TEST(Neighbor, CellListOfARankPairsItsOwnSpheresWithGhostsBeyondItsGrid) {
    for (const auto periodic : {std::array<bool, 3>{false, false, false}, std::array<bool, 3>{true, true, false}}) {
        const Domain d = box(edge, periodic);
        const ParticleStore cloud = random_store(d, 1000, r_min, r_max, 14);
        const double cut = d.lo.z + 0.6 * edge;  // own below, ghosts in the 3 interaction ranges above
        std::vector<std::uint32_t> own_indices;
        for (std::uint32_t i = 0; i < cloud.size(); ++i)
            if (cloud.position[i].z < cut) own_indices.push_back(i);
        ParticleStore own = cloud;
        own.keep(own_indices);
        for (const ParticleStore& mine : {own, in_cell_order(own, d)}) {
            ParticleStore p = mine;
            std::set<std::int64_t> own_ids(p.id.begin(), p.id.end());
            for (std::uint32_t i = 0; i < cloud.size(); ++i)
                if (cloud.position[i].z >= cut && cloud.position[i].z < cut + 3 * (2 * r_max + skin)) p.append(cloud, i);
            const std::size_t first_end = mine.size();
            ASSERT_GT(p.size(), first_end + 50);  // ghosts must exist, or the test proves nothing
            std::set<PairKey> expected;
            for (const PairKey& k : reference_pairs(p, d, skin))
                if (own_ids.count(std::get<0>(k)) || own_ids.count(std::get<1>(k))) expected.insert(k);
            ASSERT_GT(expected.size(), first_end / 4);
            for (int chunks : {1, 3}) {
                PairList found;
                CellSearch search;
                run_in_team(chunks, [&](Team& team) { search.find_pairs(p, d, skin, first_end, team, found); });
                EXPECT_EQ(key_set(p, found), expected) << chunks << " chunks";
                EXPECT_EQ(found.size(), expected.size()) << chunks << " chunks";
                for (std::size_t k = 0; k < found.size(); ++k) EXPECT_LT(found.first[k], first_end);
            }
        }
    }
}

TEST(Neighbor, CellListRefusesAPeriodicAxisShorterThanThreeRanges) {
    const Domain d = box(9e-3, {false, true, false});  // 9 mm < 3 x 3.3 mm
    const ParticleStore p = random_store(d, 20, r_min, r_max, 6);
    PairList out;
    EXPECT_THROW(cell_list_pairs(p, d, skin, out), Error);
}

// A blown-up run reaching a rebuild before its health check: NaN positions
// would ask for a grid of ~10^18 cells (std::bad_alloc); a clear error instead.
// The parallel build: split into 2, 3 or 7 chunks (threads), the list and
// the sort order are those of one chunk, element for element (each chunk
// counts and places its own particles, the parts are joined in order). The
// store is shuffled, with kinematic particles among the free ones, so that
// the pairs of a part start anywhere, and then in cell order (the search's
// path by rows of cells, whose check of the order spans the chunks).
TEST(Neighbor, CellListAndOrderDoNotDependOnTheChunkCount) {
    for (const auto periodic : {std::array<bool, 3>{false, false, false}, std::array<bool, 3>{true, false, true}}) {
        const Domain d = box(edge, periodic);
        const ParticleStore shuffled = random_store(d, 1000, r_min, r_max, 11);
        for (const ParticleStore& p : {shuffled, in_cell_order(shuffled, d)}) {
            PairList one;
            cell_list_pairs(p, d, skin, one);
            ASSERT_GT(one.size(), p.size() / 4);  // pairs must exist, or the comparison proves nothing
            const std::vector<std::uint32_t> order = cell_order(p, d, skin);
            for (int chunks : {2, 3, 7}) {
                PairList many;
                cell_list_pairs(p, d, skin, many, chunks);
                EXPECT_EQ(many.first, one.first) << chunks << " chunks";
                EXPECT_EQ(many.second, one.second) << chunks << " chunks";
                EXPECT_EQ(many.image, one.image) << chunks << " chunks";
                EXPECT_EQ(cell_order(p, d, skin, chunks), order) << chunks << " chunks";
            }
        }
    }
}

TEST(Neighbor, CellListRefusesANonFinitePosition) {
    const Domain d = box(edge, {false, false, false});
    ParticleStore p = random_store(d, 20, r_min, r_max, 8);
    p.position[7].y = std::nan("");
    PairList out;
    for (int chunks : {1, 3}) {  // 3: thrown on every thread of a team, caught and thrown again once
        try {
            cell_list_pairs(p, d, skin, out, chunks);
            FAIL() << "a NaN position was accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("a particle position is not finite"), std::string::npos) << e.what();
        }
    }
}

TEST(Neighbor, VerletListRebuildsOnlyAfterHalfTheSkin) {
    const Domain d = box(edge, {true, true, false});
    ParticleStore p = random_store(d, 200, r_min, r_max, 7);
    VerletList list(d, skin, 1);
    EXPECT_TRUE(list.needs_rebuild(p));  // never built
    list.rebuild(p);
    EXPECT_FALSE(list.needs_rebuild(p));
    EXPECT_EQ(list.builds(), 1);

    const Vec3 diagonal = (1.0 / std::sqrt(3.0)) * Vec3{1.0, -1.0, 1.0};
    // Everybody moves 0.49 skin: still safe (no pair can have closed more
    // than 0.98 skin). 1 % margins are far above round-off.
    for (Vec3& x : p.position) x += 0.49 * skin * diagonal;
    EXPECT_FALSE(list.needs_rebuild(p));
    // One particle goes past half the skin.
    p.position[42] += 0.02 * skin * diagonal;
    EXPECT_TRUE(list.needs_rebuild(p));
    list.rebuild(p);
    EXPECT_FALSE(list.needs_rebuild(p));
    EXPECT_EQ(list.builds(), 2);
    // After the rebuild the list is the reference list again.
    EXPECT_EQ(key_set(p, list.pairs()), reference_pairs(p, d, skin));
}

// Distinctive history of the pair of ids (lo, hi), as seen from lo.
ContactHistory history_of(std::int64_t lo, std::int64_t hi) {
    ContactHistory h;
    h.angular_slip = 1e-6 * static_cast<double>(hi * 4096 + lo + 1);
    h.slip = 1e-9 * Vec3{static_cast<double>(lo + 1), static_cast<double>(hi + 1), 0.5};
    h.viscous_force = 1e-3 * static_cast<double>(lo * 4096 + hi + 1);
    return h;
}

void expect_history_equal(const ContactHistory& a, const ContactHistory& b) {
    EXPECT_EQ(a.angular_slip, b.angular_slip);
    EXPECT_EQ(a.slip, b.slip);
    EXPECT_EQ(a.viscous_force, b.viscous_force);
}

// Give every pair of the list its distinctive history (oriented from the
// pair's first particle) and return, per unordered pair, whether the lower id
// was first.
std::map<std::pair<std::int64_t, std::int64_t>, bool> stamp_histories(const ParticleStore& p, PairList& list) {
    std::map<std::pair<std::int64_t, std::int64_t>, bool> lower_first;
    for (std::size_t k = 0; k < list.size(); ++k) {
        const std::int64_t a = p.id[list.first[k]], b = p.id[list.second[k]];
        const ContactHistory h = history_of(std::min(a, b), std::max(a, b));
        list.set_history(k, a < b ? h : h.swapped());
        lower_first[{std::min(a, b), std::max(a, b)}] = a < b;
    }
    return lower_first;
}

// Check each pair of the rebuilt list carries the history stamped on the same
// two ids (zero for new pairs); return how many pairs changed orientation.
std::size_t check_histories(const ParticleStore& p, const PairList& list,
                            const std::map<std::pair<std::int64_t, std::int64_t>, bool>& before,
                            std::size_t& carried) {
    std::size_t flipped = 0;
    carried = 0;
    for (std::size_t k = 0; k < list.size(); ++k) {
        const std::int64_t a = p.id[list.first[k]], b = p.id[list.second[k]];
        const auto found = before.find({std::min(a, b), std::max(a, b)});
        if (found == before.end()) {
            EXPECT_TRUE(list.history(k).is_zero()) << "new pair " << a << "-" << b << " has history";
            continue;
        }
        ++carried;
        if (found->second != (a < b)) ++flipped;
        const ContactHistory h = history_of(std::min(a, b), std::max(a, b));
        SCOPED_TRACE("pair of ids " + std::to_string(a) + ", " + std::to_string(b));
        expect_history_equal(list.history(k), a < b ? h : h.swapped());
    }
    return flipped;
}

TEST(Neighbor, VerletListCarriesHistoryByIdAcrossSortAndSmallMoves) {
    const Domain d = box(edge, {true, true, false});
    ParticleStore p = random_store(d, 1000, r_min, r_max, 8);
    VerletList list(d, skin, 1);  // sort at every build
    list.rebuild(p);
    const auto before = stamp_histories(p, list.pairs());

    // Small random moves (up to 0.1 mm per axis, some across cell borders
    // and periodic faces), then a rebuild that re-sorts the store.
    std::mt19937_64 rng(80);
    for (Vec3& x : p.position)
        for (int a = 0; a < 3; ++a) x[a] += 0.2e-3 * (uniform(rng) - 0.5);
    const std::vector<std::int64_t> ids_before = p.id;
    list.rebuild(p);
    ASSERT_NE(p.id, ids_before) << "the store was not re-sorted; the test needs a re-sort";

    std::size_t carried = 0;
    const std::size_t flipped = check_histories(p, list.pairs(), before, carried);
    // Most pairs survive moves this small, and some must change orientation
    // for the spring flip to be exercised.
    EXPECT_GT(carried, 8 * before.size() / 10);
    EXPECT_GT(flipped, 0u);
    EXPECT_EQ(key_set(p, list.pairs()), reference_pairs(p, d, skin));
}

TEST(Neighbor, VerletListCarriesHistoryWhenEveryPairFlips) {
    // Mirroring the cloud (z -> -z) keeps every distance, so every pair
    // survives, while the cell order along z reverses: most pairs change
    // which particle comes first in the array, and their spring must flip.
    const Domain d = box(edge, {false, false, false});
    ParticleStore p = random_store(d, 1000, r_min, r_max, 9);
    VerletList list(d, skin, 1);
    list.rebuild(p);
    const auto before = stamp_histories(p, list.pairs());
    for (Vec3& x : p.position) x.z = -x.z;
    list.rebuild(p);
    std::size_t carried = 0;
    const std::size_t flipped = check_histories(p, list.pairs(), before, carried);
    EXPECT_EQ(carried, before.size());
    EXPECT_EQ(list.pairs().size(), before.size());
    EXPECT_GT(flipped, before.size() / 8);  // about 27 % flip with this seed
}

TEST(Neighbor, VerletListWrapsPositionsIntoThePeriodicBox) {
    const Domain d = box(edge, {true, true, true});
    ParticleStore p = random_store(d, 300, r_min, r_max, 10);
    VerletList list(d, skin, 1);
    list.rebuild(p);
    // Push particles out across every face, by up to half a box length.
    const Vec3 L = d.length();
    std::mt19937_64 rng(100);
    std::map<std::int64_t, Vec3> wanted;  // where each id must end up
    std::map<std::int64_t, Vec3> kinematic_shift;
    std::size_t outside = 0;  // particles pushed out of the box
    for (std::size_t i = 0; i < p.size(); ++i) {
        const Vec3 original = p.position[i];
        Vec3 moved = original;
        for (int a = 0; a < 3; ++a) moved[a] += (uniform(rng) - 0.5) * L[a];
        p.position[i] = moved;
        Vec3 inside = moved, shift;
        for (int a = 0; a < 3; ++a) {
            if (inside[a] >= d.hi[a]) { inside[a] -= L[a]; shift[a] = -L[a]; }
            if (inside[a] < d.lo[a]) { inside[a] += L[a]; shift[a] = L[a]; }
        }
        wanted[p.id[i]] = inside;
        if (norm(shift) > 0.0) ++outside;
        if (p.is_kinematic(i)) kinematic_shift[p.id[i]] = p.image_shift[i] + shift;
    }
    list.rebuild(p);
    for (std::size_t i = 0; i < p.size(); ++i) {
        for (int a = 0; a < 3; ++a) {
            EXPECT_GE(p.position[i][a], d.lo[a]);
            EXPECT_LT(p.position[i][a], d.hi[a]);
        }
        // Subtracting one box length (30 mm) costs ~1e-17 m of round-off.
        const Vec3 expected = wanted[p.id[i]];
        EXPECT_NEAR(p.position[i].x, expected.x, 1e-15);
        EXPECT_NEAR(p.position[i].y, expected.y, 1e-15);
        EXPECT_NEAR(p.position[i].z, expected.z, 1e-15);
        if (p.is_kinematic(i)) {
            // A kinematic particle remembers its wrap to stay on its path.
            const Vec3 s = kinematic_shift[p.id[i]];
            EXPECT_NEAR(p.image_shift[i].x, s.x, 1e-15);
            EXPECT_NEAR(p.image_shift[i].y, s.y, 1e-15);
            EXPECT_NEAR(p.image_shift[i].z, s.z, 1e-15);
        }
    }
    EXPECT_GT(outside, p.size() / 3);  // the wrap was really exercised (expect ~58 %)
    EXPECT_EQ(key_set(p, list.pairs()), reference_pairs(p, d, skin));
}

TEST(Neighbor, NoContactIsMissedDuringASimulation) {
    // 80 grains of materials 1 and 2 with 4 kinematic ones in a periodic
    // box, the grains flying at 1 m/s, the kinematic ones carried along x at
    // 0.5 m/s and turned about z at 20 rad/s (a rigid body), with a small
    // skin (5 % of the largest radius), so the list is rebuilt often and the
    // half-skin trigger is exercised many times, by both kinds of sphere.
    // Whenever we look, every touching pair must be in the list with the
    // right image.
    Scenario s;
    s.materials = paper::materials();
    s.pair_properties = paper::pair_properties();
    s.domain = box(36e-3, {true, true, true});
    s.motions = {RigidMotion{{18e-3, 18e-3, 18e-3}, {0.0, 0.0, 1.0}, 20.0, {0.5, 0.0, 0.0}}};
    s.particles = random_fill(s.domain.lo, s.domain.hi, 84, 2.4e-3, 3.6e-3, 0, 21, {});
    for (std::size_t k = 0; k < s.particles.size(); ++k) {
        s.particles[k].material = static_cast<std::int32_t>(k % 2);
        if (k >= 80) s.particles[k].motion = 0;
    }
    randomize_velocities(s.particles, 1.0, 22);
    for (std::size_t k = 80; k < s.particles.size(); ++k) s.particles[k].velocity = {};
    s.neighbor.skin = 0.05 * 3.6e-3;
    s.neighbor.sort_every = 3;
    Simulation sim(s);

    // Look after every call: a contact missed by a late rebuild lives only
    // until the next rebuild, a few steps. One step at a time, and three
    // in one advance(), whose steps after the first begin with the drift the
    // step before did, and its count of the spheres gone far.
    std::size_t contacts_seen = 0;
    for (int check = 0; check < 1000; ++check) {
        sim.advance(check % 2 == 0 ? 1 : 3);
        const ParticleStore& p = sim.particles();
        // No sphere farther from where the list saw it than half the skin.
        EXPECT_FALSE(sim.neighbors().needs_rebuild(p)) << "at step " << sim.step_count();
        const std::set<PairKey> listed = key_set(p, sim.neighbors().pairs());
        for (const PairKey& contact : reference_pairs(p, s.domain, 0.0)) {
            ++contacts_seen;
            EXPECT_TRUE(listed.count(contact)) << "contact " << std::get<0>(contact) << "-" << std::get<1>(contact)
                                               << " missing at step " << sim.step_count();
        }
    }
    // The run must have collided and rebuilt, or it proves nothing.
    EXPECT_GT(contacts_seen, 1000u);
    EXPECT_GT(sim.neighbors().builds(), 20);
    std::printf("  [measured] %lld list builds in %lld steps, %zu contacts seen\n",
                static_cast<long long>(sim.neighbors().builds()), static_cast<long long>(sim.step_count()),
                contacts_seen);
}

// The histories re-keyed by place for a rebuild across ranks: a record of
// a sphere the store does not hold is dropped, one whose lower id lies at
// the higher place is turned to be seen from the lower place (the slip
// flips), and of two records of one pair the table still finds the first.
TEST(KeyedHistory, KeyedByPlaceFollowsTheStoreAndKeepsTheOrder) {
    ParticleStore p;
    p.resize(3);
    p.id = {7, 2, 5};  // places 0, 1, 2; ids 0 .. 9
    ContactHistory h;
    h.slip = {1.0, 2.0, 3.0};
    h.angular_slip = 0.5;
    h.viscous_force = -4.0;
    ContactHistory second = h;
    second.viscous_force = 9.0;
    const std::vector<KeyedHistory> records{
        {2, 7, h},       // ids 2 (place 1) and 7 (place 0): seen from place 0, swapped
        {5, 9, h},       // id 9 is not held: dropped
        {2, 5, h},       // places 1 and 2: as it is
        {2, 5, second},  // the same pair again: the table keeps finding the first
    };
    const std::vector<KeyedHistory> local = keyed_by_place(records, p, 10);
    ASSERT_EQ(local.size(), 3u);
    EXPECT_EQ(local[0].lo, 0);
    EXPECT_EQ(local[0].hi, 1);
    EXPECT_EQ(local[0].history.slip, h.swapped().slip);
    EXPECT_EQ(local[1].lo, 1);
    EXPECT_EQ(local[1].hi, 2);
    HistoryTable table;
    table.build(local, p.size());
    EXPECT_EQ(table.find(1, 0).slip, h.slip);  // seen from place 1 (id 2), as recorded
    EXPECT_EQ(table.find(0, 1).slip, h.swapped().slip);
    EXPECT_EQ(table.find(2, 1).viscous_force, h.viscous_force);  // the first record of the pair
    EXPECT_TRUE(table.find(0, 2).is_zero());  // no record: a new contact
}

}  // namespace
}  // namespace tumble
