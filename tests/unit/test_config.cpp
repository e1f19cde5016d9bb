// SPDX-License-Identifier: MIT
// The scenario reader (src/io/config.hpp, particle_csv.hpp): every class of
// bad input is refused with the file, the key path and the reason; good
// input gives exactly the values written.
#include <gtest/gtest.h>

#include "test_support.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "io/config.hpp"
#include "io/particle_csv.hpp"

namespace fs = std::filesystem;
using tumble::io::ConfigError;
using tumble::io::parse_run_config;
using tumble::io::RunConfig;

namespace {

// Two material-1 spheres 1 mm apart: the smallest valid scenario.
const std::string base = R"(
[simulation]
duration = 0.01
gravity = [0.0, 0.0, -9.81]

[domain]
lo = [-0.02, -0.02, -0.02]
hi = [0.02, 0.02, 0.02]

[[material]]
name = "material-1"
E = 1.0e6
G = 0.3e6
nu = 0.25
xi = 500.0
eta = 500.0
rho = 1000.0
radius = 0.0036

[[pair]]
materials = ["material-1", "material-1"]
mu = 0.1
W = 0.2

[[particles]]
kind = "list"
material = "material-1"
particles = [
    { position = [-0.0041, 0.0, 0.0], velocity = [0.5, 0.0, 0.0] },
    { position = [0.0041, 0.0, 0.0], velocity = [-0.5, 0.0, 0.0] },
]
)";

const std::string material_2 = R"(
[[material]]
name = "material-2"
E = 1.0e6
G = 0.3e6
nu = 0.25
xi = 500.0
eta = 500.0
rho = 1000.0
radius = 0.0024
)";

RunConfig parse(const std::string& text, const fs::path& base_dir = ".") {
    return parse_run_config(text, "test.toml", base_dir);
}

// `text` with the first occurrence of `from` replaced by `to` (which must exist).
std::string replace(std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << "test bug: \"" << from << "\" not in the scenario";
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

// Runs `read`, which must throw ConfigError for `file` at `key` with a
// reason containing `reason`; the message must read "FILE: KEY: REASON".
void expect_error(const std::function<void()>& read, const std::string& file, const std::string& key,
                  const std::string& reason) {
    try {
        read();
        ADD_FAILURE() << "no error; expected " << file << ": " << key << ": ..." << reason << "...";
    } catch (const ConfigError& e) {
        const std::string what = e.what();
        EXPECT_EQ(e.file().string(), file) << what;
        EXPECT_EQ(e.key(), key) << what;
        EXPECT_NE(e.reason().find(reason), std::string::npos) << "reason \"" << reason << "\" not in: " << what;
        const std::string prefix = key.empty() ? file + ": " : file + ": " + key + ": ";
        EXPECT_EQ(what.rfind(prefix, 0), 0u) << what;
    }
}

void expect_error(const std::string& text, const std::string& key, const std::string& reason) {
    expect_error([&] { parse(text); }, "test.toml", key, reason);
}

// A scratch directory per test for CSV files.
class ConfigFiles : public tumble::test_support::ScratchTest {};

const fs::path examples = fs::path(TUMBLE_SOURCE_DIR) / "examples";

}  // namespace

// ---------------------------------------------------------------- errors

TEST(ConfigErrors, UnknownKeysAreRefusedEverywhereWithASuggestion) {
    expect_error(base + "\n[simulaton]\nduration = 1.0\n", "simulaton", "did you mean \"simulation\"");
    expect_error(replace(base, "duration = 0.01", "duration = 0.01\ndurration = 2"), "simulation.durration",
                 "unknown key (did you mean \"duration\"?)");
    expect_error(replace(base, "radius = 0.0036", "radius = 0.0036\nradus = 1.0"), "material[0].radus",
                 "did you mean \"radius\"");
    expect_error(replace(base, "mu = 0.1", "mu = 0.1\nmu_roll = 0.1"), "pair[0].mu_roll", "unknown key");
    expect_error(replace(base, "{ position = [0.0041", "{ postion = [0.0041"), "particles[0].particles[1].postion",
                 "did you mean \"position\"");
    // A key valid for another kind of block is unknown here.
    expect_error(replace(base, "kind = \"list\"", "kind = \"list\"\ncount = 3"), "particles[0].count",
                 "unknown key");
    // The reason lists the known keys and the line.
    expect_error(replace(base, "duration = 0.01", "duration = 0.01\nspeed = 2"), "simulation.speed",
                 "known keys here: \"duration\", \"seed\", \"gravity\", \"max_initial_overlap\" (line 4)");
}

TEST(ConfigErrors, MissingRequiredKeys) {
    expect_error(replace(base, "duration = 0.01", ""), "simulation.duration", "missing required key");
    expect_error(replace(base, "rho = 1000.0", ""), "material[0].rho", "missing required key");
    expect_error(replace(base, "hi = [0.02, 0.02, 0.02]", ""), "domain.hi", "missing required key");
    expect_error(replace(base, "[domain]", "[domainx]"), "domainx", "unknown key");
    expect_error(replace(base, "W = 0.2", ""), "pair[0].W", "missing required key");
    expect_error(replace(base, "kind = \"list\"", ""), "particles[0].kind", "missing required key");
    expect_error(replace(base, "{ position = [0.0041, 0.0, 0.0], ", "{ "), "particles[0].particles[1].position",
                 "missing required key");
    expect_error(replace(base, "material = \"material-1\"\nparticles", "particles"),
                 "particles[0].particles[0].material", "missing");
    // Lattice and random fill need a material at block level.
    expect_error(base + "[[particles]]\nkind = \"lattice\"\norigin = [0.0, 0.0, 0.01]\ncounts = [1, 1, 1]\n"
                        "spacing = 0.01\n",
                 "particles[1].material", "missing required key");
}

TEST(ConfigErrors, WrongTypes) {
    expect_error(replace(base, "duration = 0.01", "duration = \"long\""), "simulation.duration",
                 "expected a number, got a string");
    expect_error(replace(base, "E = 1.0e6", "E = true"), "material[0].E", "expected a number, got a boolean");
    expect_error(replace(base, "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, -9.81]"), "simulation.gravity",
                 "expected an array of 3 numbers [x, y, z], got 2 elements");
    expect_error(replace(base, "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, \"down\", -9.81]"),
                 "simulation.gravity[1]", "expected a number, got a string");
    expect_error(replace(base, "duration = 0.01", "duration = 0.01\nseed = 1.5"), "simulation.seed",
                 "expected an integer, got a floating-point number");
    expect_error(replace(base, "[[material]]", "[material]"), "material",
                 "expected an array of tables");
    expect_error(replace(base, "lo = [-0.02, -0.02, -0.02]", "lo = [-0.02, -0.02, -0.02]\nperiodic = [true, 0, false]"),
                 "domain.periodic[1]", "expected true or false, got an integer");
    expect_error(replace(base, "name = \"material-1\"", "name = 1"), "material[0].name", "expected a string");
    expect_error(base + "[time_step]\ndt = \"fast\"\n", "time_step.dt", "expected \"auto\" or a time step in s");
    expect_error(base + "[time_step]\ndt = [1e-6]\n", "time_step.dt", "expected \"auto\" or a number");
}

TEST(ConfigErrors, IntegersAreAcceptedWhereFloatsAreExpected) {
    const RunConfig c = parse(replace(replace(base, "E = 1.0e6", "E = 1000000"), "rho = 1000.0", "rho = 1000"));
    EXPECT_EQ(c.scenario.materials[0].E, 1.0e6);
    EXPECT_EQ(c.scenario.materials[0].rho, 1000.0);
}

TEST(ConfigErrors, ImpossibleNumbers) {
    expect_error(replace(base, "nu = 0.25", "nu = 0.7"), "material[0].nu", "must lie in (-1, 0.5), got 0.7");
    expect_error(replace(base, "nu = 0.25", "nu = 0.5"), "material[0].nu", "must lie in (-1, 0.5)");
    expect_error(replace(base, "nu = 0.25", "nu = -1"), "material[0].nu", "must lie in (-1, 0.5)");
    expect_error(replace(base, "nu = 0.25", "nu = nan"), "material[0].nu", "must be finite");
    expect_error(replace(base, "E = 1.0e6", "E = inf"), "material[0].E", "must be finite");
    expect_error(replace(base, "radius = 0.0036", "radius = 0.0"), "material[0].radius", "must be > 0, got 0");
    expect_error(replace(base, "radius = 0.0036", "radius = -0.001"), "material[0].radius", "must be > 0");
    expect_error(replace(base, "{ position = [0.0041, 0.0, 0.0],", "{ position = [0.0041, 0.0, 0.0], radius = 0,"),
                 "particles[0].particles[1].radius", "must be > 0");
    expect_error(replace(base, "duration = 0.01", "duration = 0"), "simulation.duration", "must be > 0");
    expect_error(replace(base, "mu = 0.1", "mu = -0.1"), "pair[0].mu", "must be >= 0");
    expect_error(replace(base, "xi = 500.0", "xi = 0.0"), "material[0]", "viscosities xi and eta");
    expect_error(replace(base, "hi = [0.02, 0.02, 0.02]", "hi = [0.02, -0.03, 0.02]"), "domain.hi[1]",
                 "must exceed lo along y");
    expect_error(base + "[model]\nslip_velocity_regularisation = 0\n", "model.slip_velocity_regularisation",
                 "must be > 0");
    expect_error(base + "[time_step]\ndt = 0\n", "time_step.dt", "must be > 0");
    expect_error(base + "[neighbor]\nsort_every = -1\n", "neighbor.sort_every", "must lie in [0,");
    expect_error(base + "[output]\nsnapshot_interval = -1.0\n", "output.snapshot_interval", "must be >= 0");
}

TEST(ConfigErrors, TooLargeTimeStepNamesTheKey) {
    expect_error(base + "[time_step]\ndt = 1e-3\n", "time_step.dt", "maximum");
    // ... unless explicitly allowed.
    EXPECT_EQ(parse(base + "[time_step]\ndt = 1e-3\nallow_unsafe = true\n").scenario.time_step.dt, 1e-3);
}

TEST(ConfigErrors, PairTableMustBeComplete) {
    // Two materials need 1-1, 1-2 and 2-2; only 1-1 is given.
    expect_error(base + material_2, "pair",
                 "missing [[pair]] with materials = [\"material-1\", \"material-2\"]");
    const std::string pair_12 = "[[pair]]\nmaterials = [\"material-1\", \"material-2\"]\nmu = 0.2\nW = 0.2\n";
    const std::string pair_22 = "[[pair]]\nmaterials = [\"material-2\", \"material-2\"]\nmu = 0.5\nW = 0.2\n";
    expect_error(base + material_2 + pair_12, "pair",
                 "missing [[pair]] with materials = [\"material-2\", \"material-2\"]");
    // Complete: parses, symmetric.
    const RunConfig c = parse(base + material_2 + pair_12 + pair_22);
    EXPECT_EQ(c.scenario.pair_properties[0][1].mu, 0.2);
    EXPECT_EQ(c.scenario.pair_properties[1][0].mu, 0.2);
    EXPECT_EQ(c.scenario.pair_properties[1][1].mu, 0.5);
    // The same pair twice, in either order.
    const std::string pair_21 = "[[pair]]\nmaterials = [\"material-2\", \"material-1\"]\nmu = 0.3\nW = 0.2\n";
    expect_error(base + material_2 + pair_12 + pair_22 + pair_21, "pair[3].materials",
                 "duplicate pair \"material-2\" - \"material-1\" (already given by pair[1])");
    expect_error(base + material_2 + pair_12 + pair_22 +
                     "[[pair]]\nmaterials = [\"material-1\", \"material-3\"]\nmu = 0.3\nW = 0.2\n",
                 "pair[3].materials[1]", "unknown material \"material-3\"");
}

TEST(ConfigErrors, UnknownNames) {
    expect_error(replace(base, "material = \"material-1\"\nparticles", "material = \"materal-1\"\nparticles"),
                 "particles[0].material",
                 "unknown material \"materal-1\" (did you mean \"material-1\"?); known materials: \"material-1\"");
    expect_error(replace(base, "{ position = [0.0041, 0.0, 0.0],", "{ position = [0.0041, 0.0, 0.0], motion = \"spin\","),
                 "particles[0].particles[1].motion", "unknown motion \"spin\"; known motions: none");
    expect_error(replace(base, "kind = \"list\"", "kind = \"lists\""), "particles[0].kind",
                 "unknown kind \"lists\" (did you mean \"list\"?)");
    expect_error(base + "[model]\nshear = \"spring-dashpot\"\n", "model.shear",
                 "unknown choice \"spring-dashpot\"; known: \"paper\", \"coulomb\", \"spring\", \"off\"");
    expect_error(base + material_2 + material_2, "material[2].name",
                 "duplicate material name \"material-2\" (also material[1])");
    expect_error(base + "[[motion]]\nname = \"m\"\n[[motion]]\nname = \"m\"\n", "motion[1].name",
                 "duplicate motion name \"m\"");
    expect_error(base + "[[motion]]\nname = \"m\"\naxis_direction = [0, 0, 0]\n", "motion[0].axis_direction",
                 "must not be the zero vector");
}

TEST(ConfigErrors, OverlappingExplicitParticlesAreNamed) {
    // Centres 6.0 mm apart: an overlap of 1.2 mm = 0.33 R.
    expect_error(replace(base, "position = [0.0041, 0.0, 0.0]", "position = [0.0019, 0.0, 0.0]"),
                 "particles[0].particles[1]",
                 "the particle at (0.0019, 0, 0) overlaps particles[0].particles[0] at (-0.0041, 0, 0) "
                 "by 0.333 of the smaller radius, more than simulation.max_initial_overlap = 0.05");
    // Allowed when the limit is raised.
    EXPECT_EQ(parse(replace(replace(base, "position = [0.0041, 0.0, 0.0]", "position = [0.0019, 0.0, 0.0]"),
                            "duration = 0.01", "duration = 0.01\nmax_initial_overlap = 0.4"))
                  .scenario.particles.size(),
              2u);
    // Across blocks: a lattice sphere overlapping a list particle.
    expect_error(base + "[[particles]]\nkind = \"lattice\"\nmaterial = \"material-1\"\norigin = [0.0, 0.0, 0.0]\n"
                        "counts = [1, 1, 1]\nspacing = 0.01\n",
                 "particles[1]", "sphere 0 at (0, 0, 0) overlaps particles[0].particles[");
}

TEST(ConfigErrors, AnInitialOverlapBeyondTheBlowUpLimitCannotBeAllowed) {
    // The blow-up check stops a run at overlaps above half the radius; a
    // start above it relaxes in a few steps, before the first check (step
    // 100), and ran to exit 0 unless a checkpoint fell on those steps.
    expect_error(replace(base, "duration = 0.01", "duration = 0.01\nmax_initial_overlap = 0.9"),
                 "simulation.max_initial_overlap",
                 "must be at most 0.5, the overlap at which the blow-up check stops a run, got 0.9 (line 4)");
    EXPECT_EQ(parse(replace(base, "duration = 0.01", "duration = 0.01\nmax_initial_overlap = 0.5")).scenario.particles.size(),
              2u);
}

TEST(ConfigErrors, ASphereStartingInAFlatWallIsNamed) {
    // The wall at x = -0.0045 m, 0.4 mm from the first sphere's centre: an
    // overlap of 3.2 mm, 0.889 of its radius (it ran to exit 0, flung out).
    const std::string walled = replace(replace(base, "lo = [-0.02, -0.02, -0.02]", "lo = [-0.0045, -0.02, -0.02]"),
                                       "hi = [0.02, 0.02, 0.02]",
                                       "hi = [0.02, 0.02, 0.02]\nwalls = [true, false, false]\n"
                                       "wall_material = \"material-1\"");
    expect_error(walled, "particles[0].particles[0]",
                 "the particle at (-0.0041, 0, 0) overlaps the flat wall at domain.lo[0] = -0.0045 by 0.889 of its "
                 "radius, more than simulation.max_initial_overlap = 0.05");
    // A sphere touching the wall (its centre one radius from it) is fine.
    EXPECT_EQ(parse(replace(walled, "lo = [-0.0045,", "lo = [-0.0077,")).scenario.particles.size(), 2u);
}

// The second sphere of `base` follows motion "turn" (0.0041 m from the z
// axis through the origin, its surface 0.0077 m), given `keys`.
std::string turning(const std::string& keys) {
    return replace(base, "{ position = [0.0041, 0.0, 0.0],", "{ position = [0.0041, 0.0, 0.0], motion = \"turn\",") +
           "[[motion]]\nname = \"turn\"\n" + keys + "\n";
}

TEST(ConfigErrors, AMotionFasterThanTheBlowUpCheckAllowsIsRefused) {
    // The blow-up check stops a run at free spheres faster than 100 x the
    // reference speed (1 m/s: 100 m/s); a wall that fast flings what it hits.
    expect_error(turning("angular_velocity = 1e6"), "motion[0].angular_velocity",
                 "its spheres and walls would move at up to 7.7e+03 m/s (|velocity| 0 m/s + |angular_velocity| 1e+06 rad/s x "
                 "0.0077 m, the farthest surface from the axis), faster than the 100 m/s at which the blow-up "
                 "check stops a run (100 x time_step.reference_speed)");
    expect_error(turning("angular_velocity = 1e308"), "motion[0].angular_velocity", "move at up to 7.7e+305 m/s");
    // An axis a kilometre away: 1 rad/s moves the sphere at 1 km/s.
    expect_error(turning("axis_point = [1000.0, 0.0, 0.0]\nangular_velocity = 1.0"), "motion[0].angular_velocity",
                 "move at up to 1e+03 m/s");
    expect_error(turning("axis_point = [1e308, 0.0, 0.0]\nangular_velocity = 1.0"), "motion[0].angular_velocity",
                 "move at up to 1e+308 m/s");
    expect_error(turning("velocity = [1e308, 0.0, 0.0]"), "motion[0].velocity", "move at up to 1e+308 m/s");
    expect_error(turning("velocity = [150.0, 0.0, 0.0]"), "motion[0].velocity", "move at up to 150 m/s");
    // Within the limit, or the limit raised with the reference speed.
    EXPECT_NO_THROW(parse(turning("angular_velocity = 1e4")));  // 77 m/s
    EXPECT_NO_THROW(parse(turning("velocity = [150.0, 0.0, 0.0]") + "[time_step]\nreference_speed = 2.0\n"));
    // An axis whose length overflows would be normalised to zero: no rotation.
    expect_error(turning("axis_direction = [1e308, 1e308, 0.0]\nangular_velocity = 1.0"), "motion[0].axis_direction",
                 "its length overflows");
}

TEST(ConfigErrors, APeriodicAxisShorterThanThreeInteractionRangesIsNamed) {
    // The neighbour search needs three cells of 2 R + skin across a periodic
    // axis: 3 x (2 x 0.0036 + 0.00072) = 0.02376 m with the automatic skin.
    const std::string periodic = replace(base, "hi = [0.02, 0.02, 0.02]", "hi = [0.02, 0.02, 0.02]\nperiodic = [true, false, false]");
    EXPECT_NO_THROW(parse(periodic));  // 0.04 m
    expect_error(replace(replace(periodic, "lo = [-0.02,", "lo = [-0.011,"), "hi = [0.02,", "hi = [0.011,"), "domain.hi[0]",
                 "the periodic axis x is 0.022 m long (domain.hi - domain.lo), shorter than three interaction ranges, "
                 "3 x (2 x the largest radius 0.0036 m + the skin 0.00072 m, automatic) = 0.02376 m, which the "
                 "neighbour search needs across a periodic axis; make the axis longer");
    // A skin of 0.01 m would need 0.0516 m: the skin's fault (the run
    // refused it without the file or the key).
    expect_error(periodic + "[neighbor]\nskin = 0.01\n", "neighbor.skin",
                 "3 x (2 x the largest radius 0.0036 m + the skin 0.01 m) = 0.0516 m, which the neighbour search needs "
                 "across a periodic axis; make the skin smaller or the axis longer");
}

TEST(ConfigErrors, ABoxWhoseLengthOverflowsIsNamed) {
    expect_error(replace(replace(base, "lo = [-0.02,", "lo = [-1e308,"), "hi = [0.02,", "hi = [1e308,"), "domain.hi[0]",
                 "the box's length along x, hi - lo = 1e+308 - (-1e+308), overflows (line 8)");
}

// The reader counts the spheres every block will make, and hands the count
// to the check it is given, before it makes any: a lattice of 10^7 is
// refused in well under a second instead of after gigabytes.
TEST(ConfigErrors, TheParticleCheckSeesTheCountBeforeAnySphereIsMade) {
    // A list of 2, a lattice of 9,990,000 and a list of 2 in a box of 1 x 1 x 10 m.
    const std::string text =
        replace(base, "hi = [0.02, 0.02, 0.02]", "hi = [1.0, 1.0, 10.0]") +
        "[[particles]]\nkind = \"lattice\"\nmaterial = \"material-1\"\norigin = [0.05, 0.05, 0.05]\n"
        "counts = [100, 100, 999]\nspacing = 0.008\nradius = 0.003\n" +
        replace(replace(base.substr(base.find("[[particles]]")), "-0.0041", "0.9341"), "0.0041", "0.9421");
    tumble::io::ParticleCount seen;
    std::size_t made = 1;
    const auto started = std::chrono::steady_clock::now();
    expect_error(
        [&] {
            parse_run_config(text, "test.toml", ".", [&](const RunConfig& settings, const tumble::io::ParticleCount& c) {
                seen = c;
                made = settings.scenario.particles.size();
                throw ConfigError("test.toml", "", "refused by the check");
            });
        },
        "test.toml", "", "refused by the check");
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), 1.0);
    EXPECT_EQ(made, 0u);
    EXPECT_EQ(seen.spheres, 9'990'004u);
    EXPECT_EQ(seen.smallest_radius, 0.003);
    EXPECT_EQ(seen.largest_radius, 0.0036);
    EXPECT_EQ(seen.keys, "particles[1].counts 9990000, particles[0].particles 2, particles[2].particles 2");
    // One block: its key alone.
    parse_run_config(base, "test.toml", ".", [&](const RunConfig&, const tumble::io::ParticleCount& c) { seen = c; });
    EXPECT_EQ(seen.spheres, 2u);
    EXPECT_EQ(seen.keys, "particles[0].particles");
}

TEST(ConfigErrors, ParticleSetMustNotBeEmpty) {
    const std::string no_particles = base.substr(0, base.find("[[particles]]"));
    expect_error(no_particles, "particles", "at least one [[particles]] or [[insert]] block is required");
    expect_error(no_particles + "[[particles]]\nkind = \"list\"\nmaterial = \"material-1\"\nparticles = []\n",
                 "particles[0].particles", "the list is empty");
}

TEST(ConfigErrors, ParticlesOutsideTheDomain) {
    expect_error(replace(replace(base, "lo = [-0.02, -0.02, -0.02]", "lo = [-0.04, -0.04, -0.04]\nperiodic = [true, true, true]"),
                         "{ position = [0.0041, 0.0, 0.0]", "{ position = [0.0041, 0.05, 0.0]"),
                 "particles[0].particles[1]", "the particle at (0.0041, 0.05, 0) lies outside the domain along the periodic axis y: [-0.04, 0.02)");
    // On open axes the box bounds where particles start.
    expect_error(replace(base, "{ position = [0.0041, 0.0, 0.0]", "{ position = [0.0041, 0.0, 0.5]"),
                 "particles[0].particles[1]",
                 "the particle at (0.0041, 0, 0.5) lies outside the domain along the open axis z: "
                 "[-0.02, 0.02]");
}

TEST(ConfigErrors, SyntaxErrorGivesLineAndColumn) {
    try {
        parse(replace(base, "duration = 0.01", "duration = = 0.01"));
        ADD_FAILURE() << "no error";
    } catch (const ConfigError& e) {
        EXPECT_EQ(e.file().string(), "test.toml");
        EXPECT_EQ(e.key().rfind("line 3, column ", 0), 0u) << e.what();
        EXPECT_NE(e.reason().find("TOML syntax error"), std::string::npos) << e.what();
    }
    // A key given twice is a TOML error, too.
    expect_error([] { parse(replace(base, "duration = 0.01", "duration = 0.01\nduration = 0.02")); }, "test.toml",
                 "line 4, column 12", "TOML syntax error: Error while parsing key-value pair: cannot redefine");
}

TEST(ConfigErrors, MissingFileNamesIt) {
    expect_error([] { tumble::io::load_run_config("/nonexistent/scenario.toml"); }, "/nonexistent/scenario.toml",
                 "", "no such file");
}

TEST_F(ConfigFiles, BadCsvValueNamesFileLineAndColumn) {
    const fs::path csv = write("p.csv", "x,y,z,vx,material\n0,0,0,0,material-1\n# a comment\n0.01,0,0,abc,material-1\n");
    const std::string text = replace(base, "kind = \"list\"", "kind = \"csv\"\nfile = \"p.csv\"\n[[particles]]\nkind = \"list\"");
    expect_error([&] { parse(text, dir_); }, csv.string(), "line 4, column vx", "expected a number, got \"abc\"");

    write("p.csv", "x,y,z,material\n0,0,0,material-1\n\n0.01,0,0,materal-2\n");
    expect_error([&] { parse(text, dir_); }, csv.string(), "line 4, column material",
                 "unknown material \"materal-2\" (did you mean \"material-1\"?)");
    write("p.csv", "x,y,z,material\n0,0,0,material-1\n0.01,0,0\n");
    expect_error([&] { parse(text, dir_); }, csv.string(), "line 3", "expected 4 fields as in the header, found 3");
    write("p.csv", "x,y,z,materials\n0,0,0,material-1\n");
    expect_error([&] { parse(text, dir_); }, csv.string(), "line 1",
                 "unknown column \"materials\" in the header (did you mean \"material\"?)");
    write("p.csv", "x,y,material\n0,0,material-1\n");
    expect_error([&] { parse(text, dir_); }, csv.string(), "line 1", "no column \"z\"");
    write("p.csv", "x,y,z,material,radius\n0,0,0,material-1,-1\n");
    expect_error([&] { parse(text, dir_); }, csv.string(), "line 2, column radius", "must be > 0");
    write("p.csv", "x,y,z,material,tag\n0,0,0,material-1,1.5\n");
    expect_error([&] { parse(text, dir_); }, csv.string(), "line 2, column tag", "expected an integer");
    write("p.csv", "x,y,z,material\n");
    expect_error([&] { parse(text, dir_); }, csv.string(), "", "no particles");
    write("p.csv", "x,y,z,material\n0.01,0,0,material-1\n0.012,0,0,material-1\n");
    expect_error([&] { parse(text, dir_); }, "test.toml", "particles[0]",
                 "the particle of " + csv.string() + " line 3 at (0.012, 0, 0) overlaps particles[0] (" + csv.string() +
                     " line 2) at (0.01, 0, 0) by 1.44 of the smaller radius");
    // A file that is not there is named by the TOML key.
    expect_error([&] { parse(replace(text, "p.csv", "q.csv"), dir_); }, "test.toml", "particles[0].file",
                 "no such file: " + (dir_ / "q.csv").string());
}

// ---------------------------------------------------------------- values

TEST(ConfigValues, DefaultsOfAMinimalScenario) {
    const RunConfig c = parse(base);
    EXPECT_EQ(c.source, fs::path("test.toml"));
    EXPECT_EQ(c.duration, 0.01);
    EXPECT_EQ(c.seed, 1u);
    EXPECT_EQ(c.scenario.gravity, (tumble::Vec3{0.0, 0.0, -9.81}));
    EXPECT_EQ(c.scenario.time_step.dt, 0.0);  // auto
    EXPECT_EQ(c.scenario.time_step.reference_speed, 1.0);
    EXPECT_FALSE(c.scenario.time_step.allow_unsafe);
    EXPECT_EQ(c.scenario.neighbor.skin, 0.0);
    EXPECT_EQ(c.scenario.neighbor.sort_every, 1);
    EXPECT_TRUE(c.scenario.model.elastic && c.scenario.model.viscous && c.scenario.model.attraction &&
                c.scenario.model.twisting);
    EXPECT_EQ(c.scenario.model.shear, tumble::ShearModel::Paper);
    EXPECT_EQ(c.scenario.model.slip_velocity_regularisation, 1e-4);
    EXPECT_EQ(c.scenario.domain.periodic, (std::array<bool, 3>{false, false, false}));
    EXPECT_EQ(c.scenario.domain.walls, (std::array<bool, 3>{false, false, false}));
    EXPECT_EQ(c.output.directory, fs::path("tumble-out"));
    EXPECT_DOUBLE_EQ(c.output.time_series_interval, 0.01 / 100);
    EXPECT_EQ(c.output.snapshot_interval, 0.0);
    EXPECT_TRUE(c.scenario.motions.empty());
}

TEST(ConfigValues, DtAutoOrANumber) {
    EXPECT_EQ(parse(base + "[time_step]\ndt = \"auto\"\n").scenario.time_step.dt, 0.0);
    const RunConfig c = parse(base + "[time_step]\ndt = 2e-6\nreference_speed = 2\n");
    EXPECT_EQ(c.scenario.time_step.dt, 2e-6);
    EXPECT_EQ(c.scenario.time_step.reference_speed, 2.0);
}

TEST(ConfigValues, SectionsAreRead) {
    const RunConfig c = parse(replace(base, "lo = [-0.02, -0.02, -0.02]",
                                      "lo = [-0.02, -0.02, -0.02]\nperiodic = [true, false, false]\n"
                                      "walls = [false, false, true]\nwall_material = \"material-1\"") +
                              "[model]\nelastic = true\nviscous = false\nattraction = false\ntwisting = false\n"
                              "shear = \"spring\"\nfriction_normal = \"jkr\"\ntangential_stiffness = \"mindlin\"\n"
                              "slip_velocity_regularisation = 1e-3\n"
                              "[neighbor]\nskin = 0.0005\nsort_every = 0\n"
                              "[output]\ndirectory = \"out\"\ntime_series_interval = 0.001\nsnapshot_interval = 0\n"
                              "[[motion]]\nname = \"drum\"\naxis_point = [0, 0.01, 0]\naxis_direction = [1, 0, 0]\n"
                              "angular_velocity = 5\nvelocity = [0, 0, 0.1]\n");
    const tumble::Scenario& s = c.scenario;
    EXPECT_EQ(s.domain.periodic, (std::array<bool, 3>{true, false, false}));
    EXPECT_EQ(s.domain.walls, (std::array<bool, 3>{false, false, true}));
    EXPECT_EQ(s.domain.wall_material, 0);
    EXPECT_FALSE(s.model.viscous || s.model.attraction || s.model.twisting);
    EXPECT_EQ(s.model.shear, tumble::ShearModel::Spring);
    EXPECT_EQ(s.model.friction_normal, tumble::FrictionNormal::Jkr);
    EXPECT_EQ(s.model.tangential_stiffness, tumble::TangentialStiffness::Mindlin);
    EXPECT_EQ(s.model.slip_velocity_regularisation, 1e-3);
    EXPECT_EQ(s.neighbor.skin, 0.0005);
    EXPECT_EQ(s.neighbor.sort_every, 0);
    EXPECT_EQ(c.output.directory, fs::path("out"));
    EXPECT_EQ(c.output.time_series_interval, 0.001);
    ASSERT_EQ(s.motions.size(), 1u);
    EXPECT_EQ(s.motions[0].axis_point, (tumble::Vec3{0, 0.01, 0}));
    EXPECT_EQ(s.motions[0].axis_direction, (tumble::Vec3{1, 0, 0}));
    EXPECT_EQ(s.motions[0].angular_velocity, 5.0);
    EXPECT_EQ(s.motions[0].velocity, (tumble::Vec3{0, 0, 0.1}));
}

TEST(ConfigValues, ListParticlesGiveTheWrittenValuesAndBlockDefaults) {
    const std::string text = base + material_2 +
                             "[[pair]]\nmaterials = [\"material-1\", \"material-2\"]\nmu = 0.2\nW = 0.2\n"
                             "[[pair]]\nmaterials = [\"material-2\", \"material-2\"]\nmu = 0.5\nW = 0.2\n"
                             "[[motion]]\nname = \"fixed\"\n"
                             "[[particles]]\nkind = \"list\"\nmaterial = \"material-2\"\ntag = 7\nmotion = \"fixed\"\n"
                             "angular_velocity = [0, 0, 3]\nparticles = [\n"
                             "  { position = [0.0, 0.01, 0.0] },\n"
                             "  { position = [0.0, -0.01, 0.0], velocity = [1, 2, 3], angular_velocity = [4, 5, 6],"
                             " radius = 0.002, material = \"material-1\", tag = -3 },\n]\n";
    const RunConfig c = parse(text);
    const auto& p = c.scenario.particles;
    ASSERT_EQ(p.size(), 4u);
    // The first block (base): block material, given velocities, free.
    EXPECT_EQ(p[0].position, (tumble::Vec3{-0.0041, 0, 0}));
    EXPECT_EQ(p[0].velocity, (tumble::Vec3{0.5, 0, 0}));
    EXPECT_EQ(p[0].radius, 0.0036);
    EXPECT_EQ(p[0].material, 0);
    EXPECT_EQ(p[0].motion, tumble::free_motion);
    EXPECT_EQ(p[0].tag, 0);
    // Block defaults.
    EXPECT_EQ(p[2].position, (tumble::Vec3{0.0, 0.01, 0.0}));
    EXPECT_EQ(p[2].velocity, (tumble::Vec3{}));
    EXPECT_EQ(p[2].angular_velocity, (tumble::Vec3{0, 0, 3}));
    EXPECT_EQ(p[2].radius, 0.0024);
    EXPECT_EQ(p[2].material, 1);
    EXPECT_EQ(p[2].motion, 0);
    EXPECT_EQ(p[2].tag, 7);
    // Per-particle values win.
    EXPECT_EQ(p[3].velocity, (tumble::Vec3{1, 2, 3}));
    EXPECT_EQ(p[3].angular_velocity, (tumble::Vec3{4, 5, 6}));
    EXPECT_EQ(p[3].radius, 0.002);
    EXPECT_EQ(p[3].material, 0);
    EXPECT_EQ(p[3].motion, 0);
    EXPECT_EQ(p[3].tag, -3);
}

TEST_F(ConfigFiles, CsvParticlesGiveTheWrittenValues) {
    write("p.csv",
          "# comment\n"
          "tag , motion, material, x, y, z, vx, vy, vz, wx, wy, wz, radius\r\n"
          "3, spin, material-1, 0.01, 0.02, 0.0, 1, 2, 3, 4, 5, 6, 0.003\r\n"
          "\n"
          ",, material-1, -0.015, 0.0, 0.0,,,,,,,\n");
    const std::string text = replace(base, "kind = \"list\"", "kind = \"csv\"\nfile = \"p.csv\"\n[[particles]]\nkind = \"list\"") +
                             "[[motion]]\nname = \"spin\"\nangular_velocity = 1.0\n";
    const RunConfig c = parse(text, dir_);
    const auto& p = c.scenario.particles;
    ASSERT_EQ(p.size(), 4u);
    EXPECT_EQ(p[0].position, (tumble::Vec3{0.01, 0.02, 0.0}));
    EXPECT_EQ(p[0].velocity, (tumble::Vec3{1, 2, 3}));
    EXPECT_EQ(p[0].angular_velocity, (tumble::Vec3{4, 5, 6}));
    EXPECT_EQ(p[0].radius, 0.003);
    EXPECT_EQ(p[0].material, 0);
    EXPECT_EQ(p[0].motion, 0);
    EXPECT_EQ(p[0].tag, 3);
    // Empty cells: the defaults.
    EXPECT_EQ(p[1].position, (tumble::Vec3{-0.015, 0.0, 0.0}));
    EXPECT_EQ(p[1].velocity, (tumble::Vec3{}));
    EXPECT_EQ(p[1].radius, 0.0036);
    EXPECT_EQ(p[1].motion, tumble::free_motion);
    EXPECT_EQ(p[1].tag, 0);

    // The reader on its own, with block defaults and line numbers.
    write("q.csv", "x,y,z\n0,0,0\n\n1,2,3\n");
    tumble::io::CsvDefaults d;
    d.material = 0;
    d.tag = 9;
    d.velocity = {0, 0, -1};
    std::vector<std::size_t> lines;
    const auto q = tumble::io::read_particle_csv(dir_ / "q.csv", c.scenario.materials, {"spin"}, d, &lines);
    ASSERT_EQ(q.size(), 2u);
    EXPECT_EQ(lines, (std::vector<std::size_t>{2, 4}));
    EXPECT_EQ(q[1].position, (tumble::Vec3{1, 2, 3}));
    EXPECT_EQ(q[1].velocity, (tumble::Vec3{0, 0, -1}));
    EXPECT_EQ(q[1].tag, 9);
    EXPECT_EQ(q[1].radius, 0.0036);
    // Without a default material the column is required.
    expect_error([&] { tumble::io::read_particle_csv(dir_ / "q.csv", c.scenario.materials, {}); },
                 (dir_ / "q.csv").string(), "line 1", "no column \"material\"");
}

TEST(ConfigValues, GeneratedBlocksAreDeterministicAndSeeded) {
    const std::string fill = "[[particles]]\nkind = \"random_fill\"\nmaterial = \"material-1\"\n"
                             "lo = [-0.02, -0.02, 0.005]\nhi = [0.02, 0.02, 0.02]\ncount = 10\nspeed = 0.3\n";
    const RunConfig a = parse(base + fill + fill);
    const RunConfig b = parse(base + fill + fill);
    const RunConfig other_seed = parse(replace(base + fill + fill, "duration = 0.01", "duration = 0.01\nseed = 2"));
    ASSERT_EQ(a.scenario.particles.size(), 22u);
    for (std::size_t i = 0; i < 22; ++i) {
        EXPECT_EQ(a.scenario.particles[i].position, b.scenario.particles[i].position);
        EXPECT_EQ(a.scenario.particles[i].velocity, b.scenario.particles[i].velocity);
    }
    EXPECT_NE(a.scenario.particles[2].position, other_seed.scenario.particles[2].position);
    // Two identical blocks draw different numbers.
    EXPECT_NE(a.scenario.particles[2].position, a.scenario.particles[12].position);
    EXPECT_NE(a.scenario.particles[2].velocity, a.scenario.particles[12].velocity);
    for (std::size_t i = 2; i < 22; ++i) EXPECT_NEAR(norm(a.scenario.particles[i].velocity), 0.3, 1e-12);

    // Polydisperse fill and a lattice.
    const RunConfig c = parse(base +
                              "[[particles]]\nkind = \"random_fill\"\nmaterial = \"material-1\"\n"
                              "lo = [-0.02, -0.02, 0.005]\nhi = [0.02, 0.02, 0.02]\ncount = 10\n"
                              "radius_min = 0.001\nradius_max = 0.002\ntag = 4\n"
                              "[[particles]]\nkind = \"lattice\"\nmaterial = \"material-1\"\n"
                              "origin = [-0.01, -0.01, -0.015]\ncounts = [3, 2, 1]\nspacing = 0.008\n"
                              "velocity = [0, 0, 1]\n");
    ASSERT_EQ(c.scenario.particles.size(), 18u);
    for (std::size_t i = 2; i < 12; ++i) {
        EXPECT_GE(c.scenario.particles[i].radius, 0.001);
        EXPECT_LE(c.scenario.particles[i].radius, 0.002);
        EXPECT_EQ(c.scenario.particles[i].tag, 4);
    }
    EXPECT_EQ(c.scenario.particles[12].position, (tumble::Vec3{-0.01, -0.01, -0.015}));
    EXPECT_EQ(c.scenario.particles[17].position, (tumble::Vec3{-0.01 + 2 * 0.008, -0.01 + 0.008, -0.015}));
    EXPECT_EQ(c.scenario.particles[17].velocity, (tumble::Vec3{0, 0, 1}));
    EXPECT_EQ(c.scenario.particles[17].radius, 0.0036);

    expect_error(base + "[[particles]]\nkind = \"lattice\"\nmaterial = \"material-1\"\norigin = [0, 0, 0.01]\n"
                        "counts = [1000, 1000, 1000]\nspacing = 0.008\n",
                 "particles[1].counts", "more than 10000000 spheres in the scenario");
    expect_error(base + "[[particles]]\nkind = \"lattice\"\nmaterial = \"material-1\"\norigin = [0, 0, 0.01]\n"
                        "counts = [1, 0, 1]\nspacing = 0.008\n",
                 "particles[1].counts[1]", "must lie in [1, ");
    expect_error(base + fill + "velocity = [0, 0, 1]\n", "particles[1].speed", "not both");
    expect_error(base + replace(fill, "hi = [0.02, 0.02, 0.02]", "hi = [0.02, 0.02, 0.01]"), "particles[1]",
                 "random fill: the region is thinner than one sphere along z");
    expect_error(replace(base + fill, "count = 10", "count = 1000000"), "particles[1].count",
                 "1000000 spheres of radius >= 0.0036 m would fill 8.1e+03 of the region's volume");
}

// ---------------------------------------------------------------- examples

TEST(ConfigExamples, DemoParses) {
    const RunConfig c = tumble::io::load_run_config(examples / "demo.toml");
    const tumble::Scenario& s = c.scenario;
    ASSERT_EQ(s.materials.size(), 3u);
    EXPECT_EQ(s.materials[0].name, "material-1");
    EXPECT_EQ(s.materials[1].name, "material-2");
    EXPECT_EQ(s.materials[2].name, "wall");
    EXPECT_EQ(s.materials[0].radius, 3.6e-3);
    EXPECT_EQ(s.materials[1].radius, 2.4e-3);
    EXPECT_EQ(s.materials[2].radius, 3.0e-3);
    EXPECT_EQ(s.materials[0].xi, 500.0);
    EXPECT_EQ(s.pair_properties[0][0].mu, 0.1);
    EXPECT_EQ(s.pair_properties[0][1].mu, 0.2);
    EXPECT_EQ(s.pair_properties[1][1].mu, 0.5);
    EXPECT_EQ(s.pair_properties[2][1].mu, 0.2);
    ASSERT_EQ(s.motions.size(), 1u);
    std::size_t per_material[3] = {0, 0, 0}, kinematic = 0;
    for (const auto& p : s.particles) {
        ++per_material[p.material];
        kinematic += p.motion != tumble::free_motion;
    }
    EXPECT_EQ(per_material[0], 100u);
    EXPECT_EQ(per_material[1], 338u);
    EXPECT_EQ(per_material[2], 144u + 2 * 48 + 2 * 40);
    EXPECT_EQ(kinematic, per_material[2]);
    EXPECT_EQ(c.duration, 0.5);
    EXPECT_EQ(c.seed, 7u);
    EXPECT_EQ(c.output.time_series_interval, 0.005);
    EXPECT_EQ(c.output.snapshot_interval, 0.05);
    EXPECT_EQ(c.source, examples / "demo.toml");
}

TEST(ConfigExamples, TwoSpheresAndCsvDemoParse) {
    const RunConfig two = tumble::io::load_run_config(examples / "two_spheres.toml");
    ASSERT_EQ(two.scenario.particles.size(), 2u);
    EXPECT_EQ(two.scenario.particles[0].velocity, (tumble::Vec3{0.5, 0, 0}));
    EXPECT_EQ(two.scenario.particles[1].velocity, (tumble::Vec3{-0.5, 0, 0}));

    // The CSV path in csv_demo.toml is relative to the TOML file's folder,
    // wherever the reader is called from.
    const RunConfig csv = tumble::io::load_run_config(examples / "csv_demo.toml");
    ASSERT_EQ(csv.scenario.particles.size(), 28u);
    std::size_t fixed = 0;
    for (const auto& p : csv.scenario.particles) fixed += p.motion == 0;
    EXPECT_EQ(fixed, 25u);
    EXPECT_EQ(csv.scenario.particles[27].radius, 0.003);
    EXPECT_EQ(csv.scenario.particles[26].velocity, (tumble::Vec3{0, 0, -0.2}));
}

// ---------------------------------------------------------------- walls

namespace {
const std::string two_materials = base + material_2 + R"(
[[pair]]
materials = ["material-1", "material-2"]
mu = 0.2
W = 0.2

[[pair]]
materials = ["material-2", "material-2"]
mu = 0.5
W = 0.2

[[motion]]
name = "turn"
angular_velocity = 5.0
)";

const std::string drum_wall = R"(
[[wall]]
name = "drum"
shape = "cylinder"
material = "material-1"
motion = "turn"
point = [0.0, 0.0, -0.01]
axis = [0.0, 0.0, 2.0]
radius = 0.015
length = 0.02
caps = true
cap_material = "material-2"
)";
}  // namespace

// A capped cylinder is its mantle and a disc at each end, named after it,
// of the cap material; the axis is made a unit vector.
TEST(ConfigWalls, ACappedCylinderIsItsMantleAndTwoDiscs) {
    const RunConfig c = parse(two_materials + drum_wall);
    const auto& walls = c.scenario.walls;
    ASSERT_EQ(walls.size(), 3u);
    EXPECT_EQ(walls[0].name, "drum");
    EXPECT_EQ(walls[0].shape, tumble::WallShape::cylinder);
    EXPECT_EQ(walls[0].normal, (tumble::Vec3{0.0, 0.0, 1.0}));
    EXPECT_EQ(walls[0].radius, 0.015);
    EXPECT_EQ(walls[0].length, 0.02);
    EXPECT_TRUE(walls[0].inside);
    EXPECT_EQ(walls[0].material, 0);
    EXPECT_EQ(walls[0].motion, 0);
    EXPECT_EQ(walls[1].name, "drum.start");
    EXPECT_EQ(walls[1].shape, tumble::WallShape::disc);
    EXPECT_EQ(walls[1].point, (tumble::Vec3{0.0, 0.0, -0.01}));
    EXPECT_EQ(walls[1].material, 1);
    EXPECT_EQ(walls[2].name, "drum.end");
    EXPECT_NEAR(walls[2].point.z, 0.01, 1e-18);
    EXPECT_EQ(walls[2].motion, 0);
}

// Each shape takes its own keys only, and each value is checked where it
// is read, with the key named.
TEST(ConfigWalls, BadWallsAreRefusedNamingTheKey) {
    const std::string w = two_materials;
    expect_error(w + drum_wall + "end_radius = 0.01\n", "wall[0].end_radius", "unknown key");
    expect_error(replace(w + drum_wall, "shape = \"cylinder\"", "shape = \"cylindre\""), "wall[0].shape",
                 "unknown choice \"cylindre\" (did you mean \"cylinder\"?)");
    expect_error(replace(w + drum_wall, "axis = [0.0, 0.0, 2.0]", "axis = [0.0, 0.0, 0.0]"), "wall[0].axis",
                 "must not be the zero vector");
    expect_error(replace(w + drum_wall, "radius = 0.015\n", ""), "wall[0].radius", "missing required key");
    expect_error(replace(w + drum_wall, "radius = 0.015", "radius = -0.015"), "wall[0].radius", "must be > 0");
    expect_error(replace(w + drum_wall, "material = \"material-1\"\nmotion", "material = \"steel\"\nmotion"), "wall[0].material",
                 "unknown material \"steel\"");
    expect_error(replace(w + drum_wall, "motion = \"turn\"", "motion = \"spin\""), "wall[0].motion",
                 "unknown motion \"spin\"");
    expect_error(replace(w + drum_wall, "caps = true", "caps = false"), "wall[0].cap_material",
                 "given, but caps is not true");
    expect_error(replace(w + drum_wall, "length = 0.02\n", ""), "wall[0].caps", "an infinite cylinder has no ends");
    expect_error(w + drum_wall + drum_wall, "wall[1].name", "duplicate wall name \"drum\"");
    // A motion that carries only a wall is checked for speed as one that carries spheres.
    expect_error(replace(w + drum_wall, "angular_velocity = 5.0", "angular_velocity = 1e6"), "motion[0].angular_velocity",
                 "its spheres and walls would move at up to 1.5e+04 m/s");
    expect_error(w + "[[wall]]\nname = \"tip\"\nshape = \"cone\"\nmaterial = \"material-1\"\nradius = 0.0\n"
                     "end_radius = 0.0\nlength = 0.01\n",
                 "wall[0]", "its radii must be finite, >= 0 and not both 0");
    expect_error(w + "[[wall]]\nname = \"plate\"\nshape = \"rectangle\"\nmaterial = \"material-1\"\nsize = [0.01, 0.02]\n"
                     "edge = [0.0, 0.0, 1.0]\n",
                 "wall[0].edge", "must not be parallel to the normal");
}

// A random fill and a lattice over a box around a cone fill the cone only:
// every grain clear of the wall, on its inside. A grain listed beyond the
// wall is refused naming the wall.
TEST(ConfigWalls, FillsStayClearOfTheWallsAndAGrainBeyondOneIsRefused) {
    const std::string hopper = replace(replace(base, "lo = [-0.02, -0.02, -0.02]", "lo = [-0.05, -0.05, -0.05]"),
                                       "hi = [0.02, 0.02, 0.02]", "hi = [0.05, 0.05, 0.05]") + R"(
[[wall]]
name = "hopper"
shape = "cone"
material = "material-1"
point = [0.0, 0.0, -0.02]
radius = 0.01
end_radius = 0.04
length = 0.06

[[particles]]
kind = "lattice"
material = "material-1"
origin = [-0.045, -0.045, 0.02]
counts = [13, 13, 1]
spacing = 0.0075

[[particles]]
kind = "random_fill"
material = "material-1"
lo = [-0.05, -0.05, -0.02]
hi = [0.05, 0.05, 0.04]
count = 60
)";
    const RunConfig c = parse(hopper);
    const tumble::Wall& cone = c.scenario.walls.at(0);
    const std::size_t lattice_sites = 13 * 13;
    ASSERT_GT(c.scenario.particles.size(), 2u + 60u);
    const std::size_t from_lattice = c.scenario.particles.size() - 62;
    // The cone is 0.03 m in radius at the lattice's height (z = 0.02): of the
    // 13 x 13 sites 7.5 mm apart about 40 lie clear inside it.
    EXPECT_GT(from_lattice, 20u);
    EXPECT_LT(from_lattice, lattice_sites / 2);
    for (std::size_t i = 2; i < c.scenario.particles.size(); ++i) {
        const tumble::ParticleSpec& p = c.scenario.particles[i];
        EXPECT_GE(tumble::wall_touch(cone, p.position).distance, p.radius) << "particle " << i;
    }
    expect_error(replace(hopper, "{ position = [0.0041, 0.0, 0.0],", "{ position = [0.03, 0.0, 0.0],"),
                 "particles[0].particles[1]", "overlaps wall \"hopper\"");
}

// ---------------------------------------------------------------- mesh walls

namespace {
// Two triangles of a 20 mm square in the plane z = 0 (mm), in ASCII STL;
// `third` the last corner of the second triangle.
std::string square_stl(const std::string& third = "0 20 0") {
    return "solid plate\n"
           "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 20 0 0\nvertex 20 20 0\nendloop\nendfacet\n"
           "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 20 20 0\nvertex " + third +
           "\nendloop\nendfacet\nendsolid plate\n";
}

const std::string mesh_wall = R"(
[[wall]]
name = "plate"
shape = "mesh"
material = "material-2"
motion = "turn"
file = "parts/plate.stl"
scale = 1e-3
rotation = { axis = [0.0, 0.0, 2.0], angle = 90.0 }
offset = [0.0, 0.0, -0.01]
point = [0.0, 0.0, -0.01]
)";
}  // namespace

// The STL file is found beside the scenario (as a CSV file is), scaled
// from mm, turned by 90 degrees about z, moved; the wall names its mesh.
TEST_F(ConfigFiles, AMeshWallReadsItsStlBesideTheScenario) {
    write("parts/plate.stl", square_stl());
    const RunConfig c = parse(two_materials + mesh_wall, dir_);
    ASSERT_EQ(c.scenario.walls.size(), 1u);
    const tumble::Wall& w = c.scenario.walls[0];
    EXPECT_EQ(w.shape, tumble::WallShape::mesh);
    EXPECT_EQ(w.mesh, 0);
    EXPECT_EQ(w.material, 1);
    EXPECT_EQ(w.motion, 0);
    EXPECT_EQ(w.point, (tumble::Vec3{0.0, 0.0, -0.01}));
    ASSERT_EQ(c.scenario.meshes.size(), 1u);
    const tumble::TriangleMesh& m = c.scenario.meshes[0];
    ASSERT_EQ(m.vertices.size(), 4u);  // welded: the diagonal's corners shared
    ASSERT_EQ(m.triangles.size(), 2u);
    // (20 mm, 0, 0) -> 0.02 m along x, turned a quarter about z: 0.02 along y
    // (cos 90 degrees is 6e-17, not 0: a few 1e-18 m).
    EXPECT_NEAR(m.vertices[1].x, 0.0, 1e-17);
    EXPECT_NEAR(m.vertices[1].y, 0.02, 1e-17);
    EXPECT_EQ(m.vertices[1].z, -0.01);
}

// Fills keep clear of a mesh wall as of an analytic one, and a grain that
// starts in a mesh is refused naming the wall: a plate of two triangles
// 40 mm square across the box at z = -0.01 m, 60 grains at random in the
// box's lower half (the plate cuts it: without the mesh in the fill some
// of them would lie across it).
TEST_F(ConfigFiles, FillsStayClearOfAMeshAndAGrainInOneIsRefused) {
    write("plate.stl", "solid plate\n"
                       "facet normal 0 0 1\nouter loop\nvertex -20 -20 0\nvertex 20 -20 0\nvertex 20 20 0\n"
                       "endloop\nendfacet\n"
                       "facet normal 0 0 1\nouter loop\nvertex -20 -20 0\nvertex 20 20 0\nvertex -20 20 0\n"
                       "endloop\nendfacet\nendsolid plate\n");
    const std::string text = two_materials + R"(
[[wall]]
name = "plate"
shape = "mesh"
material = "material-2"
file = "plate.stl"
scale = 1e-3
offset = [0.0, 0.0, -0.01]

[[particles]]
kind = "random_fill"
material = "material-1"
lo = [-0.02, -0.02, -0.02]
hi = [0.02, 0.02, -0.001]
count = 30
)";
    const RunConfig c = parse(text, dir_);
    ASSERT_EQ(c.scenario.particles.size(), 32u);
    std::size_t below = 0;
    for (std::size_t i = 2; i < c.scenario.particles.size(); ++i) {
        const tumble::ParticleSpec& p = c.scenario.particles[i];
        EXPECT_GE(std::abs(p.position.z + 0.01), p.radius) << "particle " << i;
        below += p.position.z < -0.01;
    }
    EXPECT_GT(below, 0u);  // on both sides of the plate
    EXPECT_LT(below, 30u);
    expect_error([&] { parse(replace(text, "offset = [0.0, 0.0, -0.01]", "offset = [0.0, 0.0, 0.001]"), dir_); },
                 "test.toml", "particles[0].particles[0]", "overlaps wall \"plate\"");
}

// A closed mesh with `inside`: a fill over the whole box keeps to the
// inside of a cube of 30 mm (ASCII STL, faces turned out), and with
// `inside = false` to the outside, where the two listed grains at the
// centre are then refused as beyond the wall; an open mesh has no inside.
TEST_F(ConfigFiles, AFillKeepsToTheInsideOfAClosedMesh) {
    // The cube [-15, 15]^3 mm: each side as four corners counter-clockwise seen from outside.
    const double h = 15.0;
    const std::vector<std::array<std::array<double, 3>, 4>> sides{
        {{{h, -h, -h}, {h, h, -h}, {h, h, h}, {h, -h, h}}},     {{{-h, -h, -h}, {-h, -h, h}, {-h, h, h}, {-h, h, -h}}},
        {{{-h, h, -h}, {-h, h, h}, {h, h, h}, {h, h, -h}}},     {{{-h, -h, -h}, {h, -h, -h}, {h, -h, h}, {-h, -h, h}}},
        {{{-h, -h, h}, {h, -h, h}, {h, h, h}, {-h, h, h}}},     {{{-h, -h, -h}, {-h, h, -h}, {h, h, -h}, {h, -h, -h}}}};
    std::string stl = "solid cube\n";
    for (const auto& q : sides)
        for (const std::array<int, 3> t : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}}) {
            stl += "facet normal 0 0 0\nouter loop\n";
            for (int k : t)
                stl += "vertex " + std::to_string(q[k][0]) + " " + std::to_string(q[k][1]) + " " + std::to_string(q[k][2]) + "\n";
            stl += "endloop\nendfacet\n";
        }
    write("cube.stl", stl + "endsolid cube\n");
    const std::string text = two_materials + R"(
[[wall]]
name = "cube"
shape = "mesh"
material = "material-2"
file = "cube.stl"
scale = 1e-3
inside = true

[[particles]]
kind = "random_fill"
material = "material-1"
radius = 0.002
lo = [-0.02, -0.02, -0.02]
hi = [0.02, 0.02, 0.02]
count = 30
)";
    const RunConfig c = parse(text, dir_);
    ASSERT_EQ(c.scenario.particles.size(), 32u);
    EXPECT_TRUE(c.scenario.walls.at(0).sided);
    for (std::size_t i = 2; i < c.scenario.particles.size(); ++i)
        for (int a = 0; a < 3; ++a)
            EXPECT_LE(std::abs(c.scenario.particles[i].position[a]), 0.015 - 0.002) << "particle " << i;
    expect_error([&] { parse(replace(text, "inside = true", "inside = false"), dir_); }, "test.toml",
                 "particles[0].particles[0]", "its centre lies beyond the wall");
    write("plate.stl", "solid plate\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                       "endloop\nendfacet\nendsolid plate\n");
    expect_error([&] { parse(replace(text, "cube.stl", "plate.stl"), dir_); }, "test.toml", "wall[0].inside",
                 "a mesh has an inside only if it is closed: the edge between vertices 1 and 2 has 1 face");
}

// [[insert]]: counted with the particles (a scenario may start empty), the
// stream of each its own, and its settings refused at the key.
TEST_F(ConfigFiles, InsertionsAreReadAndTheirBadSettingsRefusedAtTheKey) {
    const std::string insert = R"(
[[insert]]
material = "material-1"
radius = 0.002
lo = [-0.019, -0.019, 0.0]
hi = [0.019, 0.019, 0.02]
count = 50
batch = 10
every = 0.01
start = 0.002
velocity = [0.0, 0.0, -1.0]
tag = 3
)";
    const RunConfig c = parse(two_materials + insert + insert, dir_);
    ASSERT_EQ(c.scenario.insertions.size(), 2u);
    const tumble::Insertion& q = c.scenario.insertions[0];
    EXPECT_EQ(q.count, 50);
    EXPECT_EQ(q.batch, 10);
    EXPECT_EQ(q.every, 0.01);
    EXPECT_EQ(q.start, 0.002);
    EXPECT_EQ(q.radius_min, 0.002);
    EXPECT_EQ(q.radius_max, 0.002);
    EXPECT_EQ(q.velocity, (tumble::Vec3{0.0, 0.0, -1.0}));
    EXPECT_EQ(q.tag, 3);
    EXPECT_NE(q.seed, c.scenario.insertions[1].seed);
    EXPECT_EQ(c.scenario.particles.size(), 2u);  // none made yet
    const std::string t = two_materials + insert;
    expect_error([&] { parse(replace(t, "batch = 10", "batch = 60"), dir_); }, "test.toml", "insert[0].batch",
                 "must lie in [1, 50], got 60");
    expect_error([&] { parse(replace(t, "every = 0.01", ""), dir_); }, "test.toml", "insert[0].every",
                 "missing required key");
    expect_error([&] { parse(replace(t, "every = 0.01", "every = 0.0"), dir_); }, "test.toml", "insert[0].every",
                 "must be > 0");
    expect_error([&] {
        parse(replace(replace(t, "[domain]\n", "[domain]\nwalls = [false, false, true]\nwall_material = \"material-2\"\n"), "hi = [0.019, 0.019, 0.02]",
                      "hi = [0.019, 0.019, 0.03]"),
              dir_);
    }, "test.toml", "insert[0]", "the region reaches beyond domain.lo or domain.hi along z");
    expect_error([&] { parse(replace(t, "lo = [-0.019, -0.019, 0.0]", "lo = [-0.019, -0.019, 0.017]"), dir_); }, "test.toml",
                 "insert[0]", "the region is thinner than one sphere");
    expect_error([&] { parse(replace(t, "batch = 10", "batch = 10\nspeed = 1.0"), dir_); }, "test.toml",
                 "insert[0].speed", "unknown key");
    expect_error([&] { parse(replace(replace(t, "count = 50", "count = 900"), "batch = 10", "batch = 900"), dir_); },
                 "test.toml", "insert[0].batch", "would fill");
}

// A missing file, a bad triangle (named with its file and its place in
// it), keys of other shapes and a rotation without its angle are refused
// at the key.
TEST_F(ConfigFiles, BadMeshWallsAreRefusedNamingTheKeyAndTheTriangle) {
    const std::string text = two_materials + mesh_wall;
    expect_error([&] { parse(text, dir_); }, "test.toml", "wall[0].file", "no such file");
    const fs::path stl = write("parts/plate.stl", square_stl("40 40 0"));  // on the diagonal's line: no area
    expect_error([&] { parse(text, dir_); }, "test.toml", "wall[0].file", stl.string() + ": triangle 2 (line 9): degenerate");
    write("parts/plate.stl", square_stl());
    expect_error([&] { parse(text + "radius = 0.01\n", dir_); }, "test.toml", "wall[0].radius", "unknown key");
    expect_error([&] { parse(text + "normal = [0.0, 0.0, 1.0]\n", dir_); }, "test.toml", "wall[0].normal", "unknown key");
    expect_error([&] { parse(replace(text, "shape = \"mesh\"", "shape = \"plane\""), dir_); }, "test.toml", "wall[0].file",
                 "unknown key");
    expect_error([&] { parse(replace(text, ", angle = 90.0", ""), dir_); }, "test.toml", "wall[0].rotation.angle",
                 "missing required key");
    expect_error([&] { parse(replace(text, "scale = 1e-3", "scale = 0.0"), dir_); }, "test.toml", "wall[0].scale",
                 "must be > 0");
}
