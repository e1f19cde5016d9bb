// SPDX-License-Identifier: MIT
// The drum's starting arrangements and fill options (setup/drum.hpp,
// DrumFill): bands of the requested widths and species, a list of
// boundaries, the small grains' volume fraction, a mixed start uniform along
// the axis, the caps' own friction, the periodic axis keeping its grains,
// and the refusal of impossible fills naming the key.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "io/drum_config.hpp"
#include "io/toml_reader.hpp"
#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"
#include <tuple>

#include "tumble/setup/drum.hpp"
#include "tumble/sim/simulation.hpp"

namespace tumble {
namespace {

constexpr double R_large = 3.6e-3, R_small = 2.4e-3;  // material-1, material-2

double ball(double R) { return 4.0 / 3.0 * pi * R * R * R; }

std::vector<ParticleSpec> grains_of(const DrumSetup& d) {
    std::vector<ParticleSpec> out;
    for (const ParticleSpec& p : d.scenario.particles)
        if (p.motion == free_motion) out.push_back(p);
    return out;
}

// Every grain a whole sphere inside the band its z names, of that band's
// species (material and tag), none overlapping another or the wall; returns
// the grains per band.
std::vector<std::size_t> check_bands(const DrumSetup& d, const std::vector<double>& edges,
                                     const std::vector<Species>& species) {
    const std::vector<ParticleSpec> grains = grains_of(d);
    std::vector<std::size_t> per_band(species.size(), 0);
    for (std::size_t a = 0; a < grains.size(); ++a) {
        const ParticleSpec& p = grains[a];
        const auto band = static_cast<std::size_t>(
            std::upper_bound(edges.begin() + 1, edges.end() - 1, p.position.z) - (edges.begin() + 1));
        ++per_band[band];
        EXPECT_GE(p.position.z - p.radius, edges[band] - 1e-15) << a;
        EXPECT_LE(p.position.z + p.radius, edges[band + 1] + 1e-15) << a;
        const bool small = species[band] == Species::small;
        EXPECT_EQ(p.material, small ? 1 : 0) << a;
        EXPECT_EQ(p.tag, small ? 1 : 0) << a;
        EXPECT_EQ(p.radius, small ? R_small : R_large) << a;
        for (std::size_t b = a + 1; b < grains.size(); ++b)
            EXPECT_GE(norm(p.position - grains[b].position), p.radius + grains[b].radius) << a << " " << b;
        for (const ParticleSpec& q : d.wall.particles) EXPECT_GE(norm(p.position - q.position), p.radius + q.radius);
    }
    return per_band;
}

// Fills with some fields set, the rest as the defaults.
DrumFill fill_of(Arrangement a, int bands = 0, std::vector<double> widths = {}) {
    DrumFill f;
    f.arrangement = a;
    f.bands = bands;
    f.band_widths = std::move(widths);
    return f;
}
DrumFill boundaries_fill(std::vector<double> z, Arrangement a = Arrangement::boundaries) {
    DrumFill f;
    f.arrangement = a;
    f.boundaries = std::move(z);
    return f;
}
const DrumFill mixed = fill_of(Arrangement::mixed);

DrumGeometry long_drum(double length) {
    DrumGeometry g;
    g.length = length;
    return g;
}

// The default (halves) is the fill of tumble before the arrangements, grain
// for grain: the left half's large grains from the seed's first stream, then
// the right half's small ones from its second, around the wall and the left
// grains (so existing runs give the same bytes).
TEST(DrumArrangement, HalvesIsTheFillOfBefore) {
    const DrumGeometry g;
    const DrumSetup d = build_drum_scenario(g, "two-component", 1000, 5);
    std::mt19937_64 seeds(5);
    const std::uint64_t left_seed = seeds(), right_seed = seeds();
    std::vector<ParticleSpec> expected = fill_drum_region(g, -0.06, 0.0, 229, R_large, 0, 0, left_seed, d.wall.particles);
    std::vector<ParticleSpec> around = d.wall.particles;
    around.insert(around.end(), expected.begin(), expected.end());
    const auto right = fill_drum_region(g, 0.0, 0.06, 771, R_small, 1, 1, right_seed, around);
    expected.insert(expected.end(), right.begin(), right.end());
    ASSERT_EQ(d.scenario.particles.size(), 1000 + d.wall.particles.size());
    for (std::size_t i = 0; i < 1000; ++i) {
        ASSERT_EQ(d.scenario.particles[i].position, expected[i].position) << i;
        ASSERT_EQ(d.scenario.particles[i].tag, expected[i].tag) << i;
    }
    EXPECT_EQ(d.scenario.materials.size(), 3u);
}

// Three bands of 1/4, 1/2, 1/4 of a 24 cm drum, small grains at the ends:
// small | large | small, the small grains split equally between their two
// equal bands (counts_per_band: exact totals, the rest to the left band).
TEST(DrumArrangement, BandsOfTheRequestedWidthsAndSpecies) {
    DrumFill fill;
    fill.arrangement = Arrangement::bands;
    fill.bands = 3;
    fill.band_widths = {0.25, 0.5, 0.25};
    fill.ends = Species::small;
    const DrumGeometry g = long_drum(0.24);
    const DrumSetup d = build_drum_scenario(g, "two-component", 1201, 4, fill);
    const std::vector<double> edges = band_edges(g, fill);
    ASSERT_EQ(edges.size(), 4u);
    EXPECT_DOUBLE_EQ(edges[1], -0.06);
    EXPECT_DOUBLE_EQ(edges[2], 0.06);
    const auto per_band = check_bands(d, edges, {Species::small, Species::large, Species::small});
    EXPECT_EQ(per_band[0] + per_band[2], d.grains_right);
    EXPECT_EQ(per_band[1], d.grains_left);
    EXPECT_LE(std::max(per_band[0], per_band[2]) - std::min(per_band[0], per_band[2]), 1u);
    EXPECT_EQ(d.grains_left + d.grains_right, 1201u);
}

// Bands without widths fill the bed evenly: each band holds the same grain
// volume per length (to within the rounding of counts, a grain per band).
// Three bands, small at the ends, of equal masses: 1/4, 1/2, 1/4 (equal
// widths would put twice the volume per length into the middle band); five,
// large at the ends: large bands 1/6, small bands 1/4.
TEST(DrumArrangement, BandsWithoutWidthsFillTheBedEvenly) {
    const DrumGeometry g = long_drum(0.24);
    for (auto [k, ends, widths] :
         {std::tuple{3, Species::small, std::vector<double>{0.25, 0.5, 0.25}},
          std::tuple{5, Species::large, std::vector<double>{1.0 / 6, 0.25, 1.0 / 6, 0.25, 1.0 / 6}}}) {
        DrumFill fill;
        fill.arrangement = Arrangement::bands;
        fill.bands = k;
        fill.ends = ends;
        const std::vector<double> w = band_widths(fill);
        ASSERT_EQ(w.size(), widths.size());
        for (std::size_t i = 0; i < w.size(); ++i) EXPECT_NEAR(w[i], widths[i], 1e-15) << "band " << i;
        const DrumSetup d = build_drum_scenario(g, "two-component", 1500, 5, fill);
        const std::vector<double> edges = band_edges(g, fill);
        std::vector<double> volume(static_cast<std::size_t>(k), 0.0);
        for (const ParticleSpec& p : grains_of(d))
            volume[static_cast<std::size_t>(std::upper_bound(edges.begin() + 1, edges.end() - 1, p.position.z) -
                                            (edges.begin() + 1))] += ball(p.radius);
        for (int i = 0; i < k; ++i) {
            const double per_length = volume[i] / (edges[i + 1] - edges[i]), first = volume[0] / (edges[1] - edges[0]);
            EXPECT_NEAR(per_length, first, ball(R_large) / (edges[i + 1] - edges[i])) << "k = " << k << ", band " << i;
        }
        EXPECT_NE(describe(fill).find("an even fill"), std::string::npos) << describe(fill);
    }
}

// Four equal bands, large grains at the left end: an even count ends with
// the other species on the right (large | small | large | small).
TEST(DrumArrangement, EvenBandCountStartsWithTheNamedSpeciesOnTheLeft) {
    DrumFill fill;
    fill.arrangement = Arrangement::bands;
    fill.bands = 4;
    fill.ends = Species::large;
    const DrumGeometry g = long_drum(0.24);
    const DrumSetup d = build_drum_scenario(g, "two-component", 1000, 9, fill);
    const std::vector<double> edges = band_edges(g, fill);
    for (std::size_t i = 0; i < edges.size(); ++i) EXPECT_NEAR(edges[i], -0.12 + 0.06 * i, 1e-15);
    const auto per_band = check_bands(d, edges, {Species::large, Species::small, Species::large, Species::small});
    // Equal widths: each species' grains split evenly, to one grain.
    EXPECT_LE(std::max(per_band[0], per_band[2]) - std::min(per_band[0], per_band[2]), 1u);
    EXPECT_LE(std::max(per_band[1], per_band[3]) - std::min(per_band[1], per_band[3]), 1u);
}

// Any list of boundaries: bands between them, species alternating from the
// left end's, each species' grains shared in proportion to its bands'
// widths (to within one grain).
TEST(DrumArrangement, BoundariesListMakesBandsBetweenThem) {
    DrumFill fill;
    fill.arrangement = Arrangement::boundaries;
    fill.boundaries = {-0.03, 0.01, 0.03};
    const DrumGeometry g;  // 12 cm
    const DrumSetup d = build_drum_scenario(g, "two-component", 1000, 3, fill);
    const std::vector<double> edges = band_edges(g, fill);
    EXPECT_EQ(edges, (std::vector<double>{-0.06, -0.03, 0.01, 0.03, 0.06}));
    const auto per_band = check_bands(d, edges, {Species::small, Species::large, Species::small, Species::large});
    // Small bands 3 cm and 2 cm wide: 3/5 and 2/5 of the small grains;
    // large bands 4 cm and 3 cm: 4/7 and 3/7 of the large.
    const double small = static_cast<double>(d.grains_right);
    EXPECT_LE(std::abs(static_cast<double>(per_band[0]) - 0.6 * small), 1.0);
    EXPECT_LE(std::abs(static_cast<double>(per_band[2]) - 0.4 * small), 1.0);
    const double large = static_cast<double>(d.grains_left);
    EXPECT_LE(std::abs(static_cast<double>(per_band[1]) - 4.0 / 7.0 * large), 1.0);
    EXPECT_LE(std::abs(static_cast<double>(per_band[3]) - 3.0 / 7.0 * large), 1.0);
}

TEST(DrumArrangement, CountsPerBandAreProportionalWithExactTotals) {
    EXPECT_EQ(counts_per_band(10, {1.0, 1.0, 1.0}), (std::vector<std::size_t>{4, 3, 3}));
    EXPECT_EQ(counts_per_band(7, {0.5, 0.0, 0.5}), (std::vector<std::size_t>{4, 0, 3}));
    EXPECT_EQ(counts_per_band(100, {0.2, 0.3, 0.5}), (std::vector<std::size_t>{20, 30, 50}));
    const std::vector<std::size_t> c = counts_per_band(1001, {0.17, 0.29, 0.31, 0.23});
    std::size_t sum = 0;
    for (std::size_t k : c) sum += k;
    EXPECT_EQ(sum, 1001u);
}

// The small grains' share of the grains' volume is the request to within
// one large grain's volume (the count is the whole number nearest to it).
TEST(DrumArrangement, SmallVolumeFractionAsAsked) {
    for (const double F : {0.2, 0.5, 0.75}) {
        DrumFill fill;
        fill.arrangement = Arrangement::mixed;
        fill.small_volume_fraction = F;
        const DrumSetup d = build_drum_scenario({}, "two-component", 800, 2, fill);
        const double v_large = static_cast<double>(d.grains_left) * ball(R_large);
        const double v_small = static_cast<double>(d.grains_right) * ball(R_small);
        EXPECT_LE(std::abs(v_small / (v_small + v_large) - F), ball(R_large) / (v_small + v_large)) << F;
    }
    // Unset: equal masses, as before the option.
    const DrumSetup d = build_drum_scenario({}, "two-component", 1000, 5, mixed);
    EXPECT_EQ(d.grains_left, 229u);
}

// A mixed start puts both species anywhere along the axis: z uniform over
// the centres' range L' = L - 2 r (1 + clearance), mean 0 and standard
// deviation L'/sqrt(12). Tolerances: 4 standard errors of the mean,
// L'/sqrt(12 n), and of the standard deviation, about sqrt(0.2/n) of it for
// a uniform distribution (n = 457 large, 1543 small grains); random
// sequential placement of the second species around the first keeps it
// uniform at this dilute start (solid fraction 0.2).
TEST(DrumArrangement, MixedStartIsUniformAlongTheAxis) {
    const DrumGeometry g = long_drum(0.24);
    const DrumSetup d = build_drum_scenario(g, "two-component", 2000, 6, mixed);
    for (const int tag : {0, 1}) {
        double sum = 0.0, sum2 = 0.0, n = 0.0;
        for (const ParticleSpec& p : grains_of(d))
            if (p.tag == tag) {
                sum += p.position.z;
                sum2 += p.position.z * p.position.z;
                n += 1.0;
            }
        const double R = tag == 0 ? R_large : R_small;
        const double span = g.length - 2.0 * R * (1.0 + fill_wall_clearance);
        const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
        EXPECT_NEAR(mean, 0.0, 4.0 * span / std::sqrt(12.0 * n)) << tag;
        EXPECT_NEAR(sd, span / std::sqrt(12.0), 4.0 * std::sqrt(0.2 / n) * span / std::sqrt(12.0)) << tag;
    }
    EXPECT_EQ(d.grains_left, 457u);  // equal masses: 2000 / 4.375
}

// Self mode, mixed: material-1 everywhere, tagged by the half it starts in.
TEST(DrumArrangement, SelfModeMixedIsTaggedByStartingHalf) {
    const DrumSetup d = build_drum_scenario({}, "self", 600, 8, mixed);
    std::size_t per_tag[2] = {0, 0};
    for (const ParticleSpec& p : grains_of(d)) {
        EXPECT_EQ(p.material, 0);
        EXPECT_EQ(p.tag, p.position.z < 0.0 ? 0 : 1);
        ++per_tag[p.tag];
    }
    EXPECT_EQ(per_tag[0], d.grains_left);
    EXPECT_EQ(per_tag[1], d.grains_right);
    EXPECT_GT(per_tag[0], 250u);  // about 300 each
    EXPECT_GT(per_tag[1], 250u);
}

TEST(DrumArrangement, SameSeedSameBands) {
    const DrumFill fill = fill_of(Arrangement::bands, 5);
    const DrumSetup a = build_drum_scenario(long_drum(0.3), "two-component", 700, 21, fill);
    const DrumSetup b = build_drum_scenario(long_drum(0.3), "two-component", 700, 21, fill);
    ASSERT_EQ(a.scenario.particles.size(), b.scenario.particles.size());
    for (std::size_t i = 0; i < a.scenario.particles.size(); ++i)
        ASSERT_EQ(a.scenario.particles[i].position, b.scenario.particles[i].position) << i;
}

// The caps' friction: a fourth material "cap", the wall's with the given mu
// against both grain materials, on every wall sphere in the cap planes;
// the mantle keeps the wall's. Unset: three materials, as before.
TEST(DrumArrangement, CapFrictionGivesTheCapsTheirOwnMaterial) {
    const DrumSetup plain = build_drum_scenario({}, "two-component", 300, 1);
    EXPECT_EQ(plain.scenario.materials.size(), 3u);
    DrumFill fill;
    fill.cap_friction = 0.7;
    const DrumSetup d = build_drum_scenario({}, "two-component", 300, 1, fill);
    const Scenario& s = d.scenario;
    ASSERT_EQ(s.materials.size(), 4u);
    EXPECT_EQ(s.materials[3].name, "cap");
    EXPECT_EQ(s.materials[3].E, s.materials[2].E);
    EXPECT_EQ(s.materials[3].radius, s.materials[2].radius);
    for (int grain : {0, 1}) {
        EXPECT_EQ(s.pair_properties[grain][3].mu, 0.7);
        EXPECT_EQ(s.pair_properties[3][grain].mu, 0.7);
        EXPECT_EQ(s.pair_properties[grain][3].W, s.pair_properties[grain][2].W);
        EXPECT_EQ(s.pair_properties[grain][2].mu, 0.2);  // the mantle: the wall's
    }
    EXPECT_TRUE(scenario_problem(s).empty()) << scenario_problem(s);
    const double cap_plane = 0.06 + 3.0e-3;
    std::size_t caps = 0;
    for (const ParticleSpec& p : d.wall.particles) {
        const bool in_plane = std::abs(std::abs(p.position.z) - cap_plane) < 1e-12;
        EXPECT_EQ(p.material, in_plane ? 3 : 2);
        caps += in_plane;
    }
    // The cap discs and the mantle's two end rings.
    EXPECT_EQ(caps, d.wall.cap_particles + 2 * (d.wall.mantle_particles / d.wall.mantle_rings));
    // Same grains as without: the caps' material does not change the fill.
    for (std::size_t i = 0; i < 300; ++i) EXPECT_EQ(s.particles[i].position, plain.scenario.particles[i].position);
}

// A periodic axis keeps every grain: mixed start, each grain thrown along
// the axis at +-0.5 m/s, 0.03 s (about 1.5 cm of travel, so grains cross the
// period's ends): the same grains of each species, all inside the drum.
TEST(DrumArrangement, PeriodicAxisConservesTheGrains) {
    DrumGeometry g;
    g.periodic_axis = true;
    g.length = 0.06;
    DrumSetup setup = build_drum_scenario(g, "two-component", 200, 5, mixed);
    std::size_t per_tag[2] = {setup.grains_left, setup.grains_right};
    for (std::size_t i = 0; i < setup.scenario.particles.size(); ++i)
        if (setup.scenario.particles[i].motion == free_motion)
            setup.scenario.particles[i].velocity = {0.0, 0.0, i % 2 ? 0.5 : -0.5};
    Simulation sim(setup.scenario);
    sim.advance(std::llround(0.03 / sim.dt()));
    const ParticleStore& p = sim.particles();
    ASSERT_EQ(p.free_count(), 200u);
    std::size_t seen[2] = {0, 0}, crossed = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (p.is_kinematic(i)) continue;
        ++seen[p.tag[i]];
        // Moved by less than half the period, unless it crossed an end.
        const double start = setup.scenario.particles[static_cast<std::size_t>(p.id[i])].position.z;
        crossed += std::abs(p.position[i].z - start) > 0.5 * g.length;
        EXPECT_LT(std::hypot(p.position[i].x, p.position[i].y), setup.wall.inner_radius) << p.id[i];
        EXPECT_LT(std::abs(p.position[i].z), 0.5 * g.length + 0.01) << p.id[i];  // wrapped at rebuilds
    }
    EXPECT_EQ(seen[0], per_tag[0]);
    EXPECT_EQ(seen[1], per_tag[1]);
    EXPECT_GT(crossed, 0u);
}

// Impossible fills are refused before any work, naming the key.
TEST(DrumArrangement, BadFillsAreRefusedNamingTheKey) {
    const DrumGeometry g;
    auto key_of = [&](const DrumFill& f, const std::string& mode = "two-component", DrumGeometry geometry = {}) {
        const auto problem = drum_fill_problem(geometry, mode, f);
        return problem ? problem->key + ": " + problem->reason : std::string();
    };
    auto starts = [](const std::string& text, const std::string& key) { return text.rfind(key + ":", 0) == 0; };
    EXPECT_EQ(key_of(DrumFill{}), "");
    EXPECT_TRUE(starts(key_of(fill_of(Arrangement::bands, 1)), "bands"));
    EXPECT_TRUE(starts(key_of(fill_of(Arrangement::bands)), "bands"));
    EXPECT_TRUE(starts(key_of(fill_of(Arrangement::mixed, 3)), "bands"));
    EXPECT_TRUE(starts(key_of(fill_of(Arrangement::bands, 3, {0.3, 0.3, 0.3})),
                       "band_widths"));
    EXPECT_TRUE(starts(key_of(fill_of(Arrangement::bands, 3, {0.5, 0.5})),
                       "band_widths"));
    EXPECT_TRUE(starts(key_of(fill_of(Arrangement::bands, 2, {1.2, -0.2})),
                       "band_widths"));
    EXPECT_TRUE(starts(key_of(fill_of(Arrangement::bands, 100)), "bands"));  // 1.2 mm bands
    EXPECT_TRUE(starts(key_of(fill_of(Arrangement::boundaries)), "boundaries"));
    EXPECT_TRUE(starts(key_of(boundaries_fill({0.01, -0.01})), "boundaries"));
    EXPECT_TRUE(starts(key_of(boundaries_fill({0.0, 0.07})), "boundaries"));
    EXPECT_TRUE(starts(key_of(boundaries_fill({-0.06})), "boundaries"));
    EXPECT_TRUE(starts(key_of(boundaries_fill({0.0}, Arrangement::halves)), "boundaries"));
    EXPECT_TRUE(starts(key_of(fill_of(Arrangement::bands, 3), "self"), "arrangement"));
    EXPECT_TRUE(starts(key_of(boundaries_fill({0.0}), "self"), "arrangement"));
    DrumFill f;
    for (const double F : {0.0, 1.0}) {
        f.small_volume_fraction = F;
        EXPECT_TRUE(starts(key_of(f), "small_volume_fraction")) << F;
    }
    f.small_volume_fraction = 0.3;
    EXPECT_TRUE(starts(key_of(f, "self"), "small_volume_fraction"));
    f = {};
    f.cap_friction = -0.1;
    EXPECT_TRUE(starts(key_of(f), "cap_friction"));
    f.cap_friction = 0.5;
    DrumGeometry periodic = g;
    periodic.periodic_axis = true;
    EXPECT_TRUE(starts(key_of(f, "two-component", periodic), "cap_friction"));
    EXPECT_EQ(key_of(mixed, "self"), "");
    // build_drum_scenario refuses them too.
    EXPECT_THROW(build_drum_scenario(g, "two-component", 100, 1, fill_of(Arrangement::bands, 1)),
                 Error);
    // Too few grains for every band.
    EXPECT_THROW(build_drum_scenario(long_drum(0.3), "two-component", 4, 1,
                                     fill_of(Arrangement::bands, 5)),
                 Error);
}

// The drum file's keys: [fill] arrangement, bands, band_widths, boundaries,
// ends, small_volume_fraction, [drum] cap_friction, [neighbor] skin and
// [model] surface_energy; a bad value names the file, the key and the option.
TEST(DrumArrangement, DrumFileKeys) {
    auto read = [](const std::string& text) {
        return io::read_drum_settings(io::parse_toml(text, "drum.toml"), "drum.toml");
    };
    const io::DrumSettings s = read(
        "[drum]\nlength = 0.24\ncap_friction = 0.6\n[fill]\narrangement = \"bands\"\nbands = 3\n"
        "band_widths = [0.25, 0.5, 0.25]\nends = \"large\"\nsmall_volume_fraction = 0.4\n");
    EXPECT_EQ(s.fill.arrangement, Arrangement::bands);
    EXPECT_EQ(s.fill.bands, 3);
    EXPECT_EQ(s.fill.band_widths, (std::vector<double>{0.25, 0.5, 0.25}));
    EXPECT_EQ(s.fill.ends, Species::large);
    EXPECT_EQ(s.fill.small_volume_fraction, 0.4);
    EXPECT_EQ(s.fill.cap_friction, 0.6);
    const io::DrumSettings b = read("[fill]\narrangement = \"boundaries\"\nboundaries = [-0.01, 0.02]\n");
    EXPECT_EQ(b.fill.boundaries, (std::vector<double>{-0.01, 0.02}));
    const io::DrumSettings plain = read("");
    EXPECT_EQ(plain.fill.arrangement, Arrangement::halves);
    EXPECT_FALSE(plain.fill.small_volume_fraction);
    EXPECT_FALSE(plain.fill.cap_friction);
    auto message = [&](const std::string& text) {
        try {
            read(text);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(message("[fill]\narrangement = \"stripes\"\n").find("fill.arrangement"), std::string::npos);
    EXPECT_NE(message("[fill]\narrangement = \"bands\"\nbands = 1\n").find("fill.bands"), std::string::npos);
    const std::string sum = message("[fill]\narrangement = \"bands\"\nbands = 2\nband_widths = [0.5, 0.6]\n");
    EXPECT_NE(sum.find("drum.toml"), std::string::npos) << sum;
    EXPECT_NE(sum.find("band_widths"), std::string::npos) << sum;
    EXPECT_NE(sum.find("--band-widths"), std::string::npos) << sum;
    EXPECT_NE(message("[fill]\nboundaries = \"0.1\"\n").find("fill.boundaries"), std::string::npos);
    EXPECT_NE(message("[drum]\nperiodic_axis = true\ncap_friction = 0.3\n").find("cap_friction"), std::string::npos);
    // [neighbor] skin, m (0: automatic), below the drum's diameter.
    EXPECT_EQ(read("[neighbor]\nskin = 0.001\n").skin, 0.001);
    EXPECT_EQ(plain.skin, 0.0);
    EXPECT_NE(message("[neighbor]\nskin = -0.001\n").find("neighbor.skin"), std::string::npos);
    const std::string wide = message("[neighbor]\nskin = 0.09\n");
    EXPECT_NE(wide.find("below the drum's diameter"), std::string::npos) << wide;
    EXPECT_NE(message("[neighbor]\nsort_every = 2\n").find("sort_every"), std::string::npos);
    // [model] surface_energy, J/m^2 (by default each pair's own, the paper's 0.2; 0: no attraction).
    EXPECT_EQ(read("[model]\nsurface_energy = 0.0\n").surface_energy, 0.0);
    EXPECT_FALSE(plain.surface_energy);
    EXPECT_EQ(plain.uniform_surface_energy(), 0.2);
    EXPECT_NE(message("[model]\nsurface_energy = -0.2\n").find("model.surface_energy"), std::string::npos);
    // The example file.
    const io::DrumSettings example =
        io::load_drum_settings(std::string(TUMBLE_SOURCE_DIR) + "/examples/drum_bands.toml");
    const std::vector<double> edges = band_edges(example.geometry, example.fill);
    ASSERT_EQ(edges.size(), 4u);
    const double expected[] = {-0.16, -0.08, 0.08, 0.16};
    for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(edges[i], expected[i], 1e-15);
    EXPECT_EQ(example.fill.cap_friction, 0.5);
}

}  // namespace
}  // namespace tumble
