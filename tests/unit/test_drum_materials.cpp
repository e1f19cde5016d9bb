// SPDX-License-Identifier: MIT
// The drum with materials of its own (docs/DRUM.md, "Materials"): the drum
// file's [[material]] and [[pair]] tables, read by the scenario reader's
// code, and [materials] saying which is the large grains', the small
// grains', the wall's and the caps'; the grains' radii from their
// materials; every bad input refused naming the file, the key and the
// reason.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "io/drum_config.hpp"
#include "io/toml_reader.hpp"
#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"
#include "tumble/setup/drum.hpp"

namespace tumble {
namespace {

std::string material(const std::string& name, double radius, double rho = 2500.0) {
    return "[[material]]\nname = \"" + name +
           "\"\nE = 1.0e7\nG = 4.0e6\nnu = 0.22\nxi = 50.0\neta = 50.0\nrho = " + std::to_string(rho) +
           "\nradius = " + std::to_string(radius) + "\n";
}

std::string pair(const std::string& a, const std::string& b, double mu = 0.3, double W = 0.0) {
    return "[[pair]]\nmaterials = [\"" + a + "\", \"" + b + "\"]\nmu = " + std::to_string(mu) +
           "\nW = " + std::to_string(W) + "\n";
}

// Glass-like beads of 3 and 2 mm and a steel wall, every pair given.
std::string glass_tables(double steel_W = 0.0) {
    return material("glass-3mm", 3.0e-3) + material("glass-2mm", 2.0e-3) + material("steel", 3.0e-3, 7800.0) +
           pair("glass-3mm", "glass-3mm") + pair("glass-3mm", "glass-2mm") + pair("glass-2mm", "glass-2mm") +
           pair("glass-3mm", "steel", 0.4, steel_W) + pair("glass-2mm", "steel", 0.4, steel_W) +
           pair("steel", "steel", 0.4, steel_W);
}

const std::string glass_roles = "[materials]\nlarge = \"glass-3mm\"\nsmall = \"glass-2mm\"\nwall = \"steel\"\n";

io::DrumSettings read(const std::string& text) {
    return io::read_drum_settings(io::parse_toml(text, "drum.toml"), "drum.toml");
}

// The ConfigError of reading `text`: "drum.toml: KEY: REASON".
std::string refusal(const std::string& text) {
    try {
        read(text);
    } catch (const io::ConfigError& e) {
        EXPECT_EQ(e.file().string(), "drum.toml");
        return e.key() + ": " + e.reason();
    }
    return "(read)";
}

TEST(DrumMaterials, TheFilesTablesSayWhichMaterialIsWhich) {
    const io::DrumSettings s = read(glass_tables() + glass_roles);
    const DrumMaterials& m = s.materials;
    EXPECT_FALSE(m.paper);
    ASSERT_EQ(m.materials.size(), 3u);
    EXPECT_EQ(m.materials[m.large].name, "glass-3mm");
    EXPECT_EQ(m.materials[m.small].name, "glass-2mm");
    EXPECT_EQ(m.materials[m.wall].name, "steel");
    EXPECT_EQ(m.cap, -1);  // the wall's
    EXPECT_EQ(m.pair_properties[m.large][m.wall].mu, 0.4);
    EXPECT_EQ(m.pair_properties[m.small][m.large].mu, 0.3);
    EXPECT_EQ(s.uniform_surface_energy(), 0.0);  // every pair's W
    // The paper's without the tables.
    EXPECT_TRUE(read("").materials.paper);
    EXPECT_EQ(read("").materials.materials[0].name, "material-1");
}

// The drum of those materials: large (tag 0) and small (tag 1) grains of
// their materials' radii, the scenario's materials the used ones in the
// order large, small, wall, and the pair table theirs.
TEST(DrumMaterials, TheDrumIsBuiltOfThem) {
    io::DrumSettings s = read(glass_tables() + "[materials]\nlarge = \"glass-3mm\"\nsmall = \"glass-2mm\"\n"
                                               "wall = \"steel\"\ncap = \"glass-3mm\"\n");
    for (const DrumWalls walls : {DrumWalls::particles, DrumWalls::smooth}) {
        s.geometry.walls = walls;
        const DrumSetup d = build_drum_scenario(s.geometry, s.mode, 400, 2, s.fill, s.materials);
        const Scenario& sc = d.scenario;
        ASSERT_EQ(sc.materials.size(), 3u);
        EXPECT_EQ(sc.materials[0].name, "glass-3mm");
        EXPECT_EQ(sc.materials[1].name, "glass-2mm");
        EXPECT_EQ(sc.materials[2].name, "steel");
        EXPECT_EQ(sc.pair_properties[0][2].mu, 0.4);
        EXPECT_EQ(sc.pair_properties[1][1].mu, 0.3);
        std::size_t grains[2] = {0, 0};
        for (const ParticleSpec& p : sc.particles) {
            if (p.motion != free_motion) continue;
            ++grains[p.tag];
            EXPECT_EQ(p.material, p.tag);  // large: glass-3mm, small: glass-2mm
            EXPECT_EQ(p.radius, p.tag == 0 ? 3.0e-3 : 2.0e-3);
        }
        EXPECT_EQ(grains[0] + grains[1], 400u);
        // Equal masses of one density: 27 n_large = 8 n_small, to within a grain.
        EXPECT_NEAR(27.0 * grains[0], 8.0 * grains[1], 27.0);
        // The caps of glass-3mm (material 0), the mantle of steel.
        if (walls == DrumWalls::smooth) {
            ASSERT_EQ(sc.walls.size(), 3u);
            EXPECT_EQ(sc.walls[0].material, 2);
            EXPECT_EQ(sc.walls[1].material, 0);
            EXPECT_EQ(sc.walls[2].material, 0);
        } else {
            std::size_t cap = 0, mantle = 0;
            for (const ParticleSpec& p : d.wall.particles) ++(p.material == 0 ? cap : mantle);
            EXPECT_EQ(cap, d.wall.cap_particles + 2 * (d.wall.mantle_particles / d.wall.mantle_rings));
            EXPECT_EQ(cap + mantle, d.wall.particles.size());
        }
        EXPECT_TRUE(scenario_problem(sc).empty()) << scenario_problem(sc);
    }
}

// In the self mode the small grains' material is not needed, and the
// grains are all of the large grains' material.
TEST(DrumMaterials, TheSelfModeNeedsNoSmallGrains) {
    const io::DrumSettings s =
        read(glass_tables() + "[fill]\nmode = \"self\"\n[materials]\nlarge = \"glass-2mm\"\nwall = \"steel\"\n");
    EXPECT_EQ(s.materials.small, -1);
    const DrumSetup d = build_drum_scenario(s.geometry, s.mode, 200, 1, s.fill, s.materials);
    ASSERT_EQ(d.scenario.materials.size(), 2u);  // glass-2mm, steel
    for (const ParticleSpec& p : d.scenario.particles)
        if (p.motion == free_motion) {
            EXPECT_EQ(p.radius, 2.0e-3);
        }
}

// --fill aims at a fill fraction with the grains' own radii: in the self
// mode, 0.6 x fill x pi R^2 L of grain volume.
TEST(DrumMaterials, TheFillFractionCountsTheirGrains) {
    io::DrumSettings s =
        read(glass_tables() + "[fill]\nmode = \"self\"\nfill_fraction = 0.2\n[materials]\nlarge = \"glass-2mm\"\n"
                              "wall = \"steel\"\n");
    const double solid = 0.6 * 0.2 * pi * 0.04 * 0.04 * 0.12, grain = 4.0 / 3.0 * pi * std::pow(2.0e-3, 3);
    EXPECT_EQ(s.grain_count(), static_cast<std::size_t>(std::llround(solid / grain)));
}

// The W of the drum: --surface-energy sets every pair's; without it the
// pairs keep theirs, and where they differ there is no one W.
TEST(DrumMaterials, TheSurfaceEnergyIsThePairsUnlessGiven) {
    io::DrumSettings s = read(glass_tables(0.05) + glass_roles);
    EXPECT_FALSE(s.uniform_surface_energy());
    s.surface_energy = 0.1;
    EXPECT_EQ(s.uniform_surface_energy(), 0.1);
}

TEST(DrumMaterials, BadTablesAreRefusedNamingTheKeyAndTheReason) {
    const std::string tables = glass_tables();
    auto starts = [](const std::string& text, const std::string& prefix) { return text.rfind(prefix, 0) == 0; };
    struct Case {
        std::string text, expected;  // the refusal begins with `expected`
    };
    const Case cases[] = {
        // Tables without the roles, roles without tables.
        {tables, "materials: missing: with [[material]] tables, say which material is which"},
        {glass_roles, "materials: given, but no [[material]] table defines a material"},
        // A role that names no material, with the nearest name and the list.
        {tables + "[materials]\nlarge = \"glass-3m\"\nsmall = \"glass-2mm\"\nwall = \"steel\"\n",
         "materials.large: unknown material \"glass-3m\" (did you mean \"glass-3mm\"?)"},
        {tables + "[materials]\nlarge = \"glass-3mm\"\nsmall = \"glass-2mm\"\nwall = \"iron\"\n",
         "materials.wall: unknown material \"iron\""},
        {tables + glass_roles + "cap = \"rubber\"\n", "materials.cap: unknown material \"rubber\""},
        // A role missing.
        {tables + "[materials]\nsmall = \"glass-2mm\"\nwall = \"steel\"\n", "materials.large: missing required key"},
        {tables + "[materials]\nlarge = \"glass-3mm\"\nsmall = \"glass-2mm\"\n", "materials.wall: missing required key"},
        {tables + "[materials]\nlarge = \"glass-3mm\"\nwall = \"steel\"\n",
         "materials.small: missing: the two-component mode needs the small grains' material"},
        // The two components of one material.
        {tables + "[materials]\nlarge = \"glass-3mm\"\nsmall = \"glass-3mm\"\nwall = \"steel\"\n",
         "materials.small: the same material as the large grains"},
        // An unknown role, a name that is not a string.
        {tables + glass_roles + "medium = \"glass-3mm\"\n", "materials.medium: unknown key"},
        {tables + "[materials]\nlarge = 3\nsmall = \"glass-2mm\"\nwall = \"steel\"\n",
         "materials.large: expected a string, got an integer"},
        // The scenario's rules for the tables themselves.
        {material("glass-3mm", 3.0e-3) + material("glass-2mm", 2.0e-3) + material("steel", 3.0e-3) +
             pair("glass-3mm", "glass-3mm") + pair("glass-3mm", "glass-2mm") + pair("glass-2mm", "glass-2mm") +
             pair("glass-3mm", "steel") + pair("steel", "steel") + glass_roles,
         "pair: missing [[pair]] with materials = [\"glass-2mm\", \"steel\"]"},
        {tables + pair("glass-3mm", "brass") + glass_roles, "pair[6].materials[1]: unknown material \"brass\""},
        {tables + material("glass-3mm", 1.0e-3) + glass_roles, "material[3].name: duplicate material name"},
        {tables + "[[material]]\nname = \"x\"\n" + glass_roles, "material[3].E: missing required key"},
        {pair("a", "a") + "[drum]\nwalls = \"smooth\"\n", "pair[0].materials[0]: unknown material \"a\"; no [[material]] is defined"},
        // Caps on a drum that has none; the caps' own material under a taken name.
        {tables + glass_roles + "cap = \"steel\"\n[drum]\nperiodic_axis = true\n",
         "materials.cap: a drum with a periodic axis has no end caps"},
        {material("glass-3mm", 3.0e-3) + material("glass-2mm", 2.0e-3) + material("cap", 3.0e-3) +
             pair("glass-3mm", "glass-3mm") + pair("glass-3mm", "glass-2mm") + pair("glass-2mm", "glass-2mm") +
             pair("glass-3mm", "cap") + pair("glass-2mm", "cap") + pair("cap", "cap") +
             "[materials]\nlarge = \"glass-3mm\"\nsmall = \"glass-2mm\"\nwall = \"cap\"\n[drum]\ncap_friction = 0.5\n",
         "cap_friction: the caps' own material would be named \"cap\""},
    };
    for (const Case& c : cases) {
        const std::string why = refusal(c.text);
        EXPECT_TRUE(starts(why, c.expected)) << "expected: " << c.expected << "\ngot: " << why;
    }
    // A band narrower than one of these grains is refused with their radius
    // (a large band at the left: 2 x 3 mm x 1.02), not the paper's (7.3 mm).
    const std::string bands = "[fill]\narrangement = \"boundaries\"\nends = \"large\"\nboundaries = ";
    const std::string narrow = refusal(tables + glass_roles + bands + "[-0.0545]\n");
    EXPECT_TRUE(starts(narrow, "boundaries: band 1")) << narrow;
    EXPECT_NE(narrow.find("narrower than a large grain (0.00612 m)"), std::string::npos) << narrow;
    EXPECT_EQ(refusal(tables + glass_roles + bands + "[-0.0535]\n"), "(read)");
}

// The engine refuses what the reader would, naming the role.
TEST(DrumMaterials, TheEngineRefusesMissingRoles) {
    DrumMaterials m = paper_drum_materials();
    EXPECT_FALSE(drum_materials_problem(m, "two-component"));
    m.small = -1;
    ASSERT_TRUE(drum_materials_problem(m, "two-component"));
    EXPECT_EQ(drum_materials_problem(m, "two-component")->key, "small");
    EXPECT_FALSE(drum_materials_problem(m, "self"));
    EXPECT_THROW(build_drum_scenario({}, "two-component", 100, 1, {}, m), Error);
    m = paper_drum_materials();
    m.wall = 7;
    EXPECT_EQ(drum_materials_problem(m, "self")->key, "wall");
}

}  // namespace
}  // namespace tumble
