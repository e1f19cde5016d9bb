// SPDX-License-Identifier: MIT
// The drum's smooth walls (setup/drum.hpp, DrumWalls::smooth): a cylinder
// and two discs where the particle wall's inner surface is, carried by the
// drum's rotation, of the wall's and the caps' materials; no wall spheres;
// the same fill as the particle-walled drum, off the walls; the periodic
// drum's infinite cylinder; the drum file's and the command line's keyword.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "io/drum_config.hpp"
#include "io/toml_reader.hpp"
#include "tumble/core/error.hpp"
#include "tumble/setup/drum.hpp"

namespace tumble {
namespace {

DrumGeometry smooth(bool periodic = false) {
    DrumGeometry g;
    g.walls = DrumWalls::smooth;
    g.periodic_axis = periodic;
    return g;
}

TEST(DrumSmoothWalls, ACylinderAndTwoDiscsAtTheParticleWallsInnerSurface) {
    const DrumSetup particles = build_drum_scenario({}, "two-component", 300, 1);
    const DrumSetup d = build_drum_scenario(smooth(), "two-component", 300, 1);
    const Scenario& s = d.scenario;
    // No wall spheres: every particle is a grain.
    EXPECT_TRUE(d.wall.particles.empty());
    EXPECT_EQ(s.particles.size(), 300u);
    EXPECT_EQ(s.free_count(), 300u);
    // The inner surface is the particle wall's (exactly: both are the
    // geometry's diameter / 2 and length).
    EXPECT_EQ(d.wall.inner_radius, particles.wall.inner_radius);
    EXPECT_EQ(d.wall.inner_length, particles.wall.inner_length);
    ASSERT_EQ(s.walls.size(), 3u);
    const Wall& mantle = s.walls[0];
    EXPECT_EQ(mantle.name, "drum");
    EXPECT_EQ(mantle.shape, WallShape::cylinder);
    EXPECT_TRUE(mantle.inside);
    EXPECT_EQ(mantle.radius, 0.04);
    EXPECT_EQ(mantle.length, 0.12);
    EXPECT_EQ(mantle.point, (Vec3{0.0, 0.0, -0.06}));
    EXPECT_EQ(mantle.normal, (Vec3{0.0, 0.0, 1.0}));
    for (std::size_t k = 1; k < 3; ++k) {
        const Wall& cap = s.walls[k];
        EXPECT_EQ(cap.shape, WallShape::disc);
        EXPECT_EQ(cap.radius, 0.04);
        EXPECT_EQ(cap.point.z, k == 1 ? -0.06 : 0.06);
    }
    EXPECT_EQ(s.walls[1].name, "drum.start");
    EXPECT_EQ(s.walls[2].name, "drum.end");
    // Carried by the drum's rotation (motion 0), all of the wall's material
    // (the paper's: material-1, material-2, wall).
    ASSERT_EQ(s.materials.size(), 3u);
    for (const Wall& w : s.walls) {
        EXPECT_EQ(w.motion, 0);
        EXPECT_EQ(w.material, 2);
        EXPECT_TRUE(wall_problem(w).empty()) << w.name << ": " << wall_problem(w);
    }
    EXPECT_TRUE(scenario_problem(s).empty()) << scenario_problem(s);
}

// The fill keeps every grain off the smooth walls: the clearance that keeps
// it off the particle wall's inner surface keeps it off the walls there,
// and the wall spheres (outside that surface) never stopped a grain, so the
// grains are those of the particle-walled drum, position for position.
TEST(DrumSmoothWalls, TheFillIsTheParticleDrumsAndTouchesNoWall) {
    DrumFill bands;
    bands.arrangement = Arrangement::bands;
    bands.bands = 3;
    for (const DrumFill& fill : {DrumFill{}, bands}) {
        const DrumSetup particles = build_drum_scenario({}, "two-component", 600, 4, fill);
        const DrumSetup d = build_drum_scenario(smooth(), "two-component", 600, 4, fill);
        ASSERT_EQ(d.scenario.particles.size(), 600u);
        for (std::size_t i = 0; i < 600; ++i) {
            const ParticleSpec& p = d.scenario.particles[i];
            EXPECT_EQ(p.position, particles.scenario.particles[i].position) << i;
            for (const Wall& w : d.scenario.walls)
                EXPECT_GE(wall_touch(w, p.position).distance, p.radius * (1.0 + fill_wall_clearance) - 1e-15)
                    << "grain " << i << " against " << w.name;
        }
    }
}

TEST(DrumSmoothWalls, APeriodicAxisHasAnInfiniteCylinderAndNoCaps) {
    const DrumSetup d = build_drum_scenario(smooth(true), "two-component", 300, 1);
    ASSERT_EQ(d.scenario.walls.size(), 1u);
    const Wall& mantle = d.scenario.walls[0];
    EXPECT_EQ(mantle.shape, WallShape::cylinder);
    EXPECT_TRUE(std::isinf(mantle.length));
    EXPECT_EQ(mantle.radius, 0.04);
    EXPECT_TRUE(d.scenario.domain.periodic[2]);
    EXPECT_TRUE(d.wall.particles.empty());
}

// The caps' friction: the smooth caps take the material "cap" (the wall's,
// with that mu against the grains); the mantle keeps the wall's.
TEST(DrumSmoothWalls, CapFrictionGivesTheDiscsTheirOwnMaterial) {
    DrumFill fill;
    fill.cap_friction = 0.7;
    const DrumSetup d = build_drum_scenario(smooth(), "two-component", 300, 1, fill);
    const Scenario& s = d.scenario;
    ASSERT_EQ(s.materials.size(), 4u);
    EXPECT_EQ(s.materials[3].name, "cap");
    EXPECT_EQ(s.walls[0].material, 2);
    EXPECT_EQ(s.walls[1].material, 3);
    EXPECT_EQ(s.walls[2].material, 3);
    for (int grain : {0, 1}) EXPECT_EQ(s.pair_properties[grain][3].mu, 0.7);
}

// The domain bounds the drum with a margin of a large grain's diameter
// beyond smooth walls (a centre outside it has passed through a wall).
TEST(DrumSmoothWalls, TheDomainBoundsTheDrumWithAGrainsMargin) {
    const DrumSetup d = build_drum_scenario(smooth(), "two-component", 300, 1);
    const double margin = 2.0 * 3.6e-3;
    EXPECT_DOUBLE_EQ(d.scenario.domain.hi.x, 0.04 + margin);
    EXPECT_DOUBLE_EQ(d.scenario.domain.hi.z, 0.06 + margin);
    EXPECT_DOUBLE_EQ(d.scenario.domain.lo.y, -(0.04 + margin));
}

// One keyword table for the choice: the drum file's [drum] walls (and so
// the command line's --walls, which checks against the same table).
TEST(DrumSmoothWalls, TheDrumFileNamesTheWalls) {
    auto read = [](const std::string& text) {
        return io::read_drum_settings(io::parse_toml(text, "drum.toml"), "drum.toml");
    };
    EXPECT_EQ(read("").geometry.walls, DrumWalls::particles);
    EXPECT_EQ(read("[drum]\nwalls = \"smooth\"\n").geometry.walls, DrumWalls::smooth);
    EXPECT_EQ(read("[drum]\nwalls = \"particles\"\n").geometry.walls, DrumWalls::particles);
    ASSERT_NE(find_keyword(drum_wall_kinds, "smooth"), nullptr);
    try {
        read("[drum]\nwalls = \"smoth\"\n");
        ADD_FAILURE() << "a misspelt wall kind was read";
    } catch (const io::ConfigError& e) {
        EXPECT_EQ(e.key(), "drum.walls");
        const std::string reason = e.reason();
        EXPECT_NE(reason.find("\"smooth\""), std::string::npos) << reason;  // the nearest, and the known ones
        EXPECT_NE(reason.find("\"particles\""), std::string::npos) << reason;
    }
}

}  // namespace
}  // namespace tumble
