// SPDX-License-Identifier: MIT
// Checkpoints (docs/CHECKPOINTS.md): capture -> run -> restore -> run must
// match the uninterrupted run bit for bit, contact history included; the
// file format round-trips and refuses damaged files.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>

#include "io/binary.hpp"
#include "io/checkpoint.hpp"
#include "io/config.hpp"
#include "test_support.hpp"
#include "tumble/setup/drum.hpp"
#include "tumble/sim/simulation.hpp"

namespace {

using namespace tumble;
namespace fs = std::filesystem;

// A small drum (173 wall spheres, 20 grains) and a walled box with adhesive
// grains: together every part of the state (kinematic particles, pair and
// flat-wall contact history, sorting, a changed motion).
Scenario small_drum() {
    DrumGeometry g;
    g.length = g.diameter = 0.03;
    g.wall_radius = 3e-3;
    return build_drum_scenario(g, "self", 20, 3).scenario;
}

Scenario walled_box() {
    return io::parse_run_config(tumble::test_support::walled_box_scenario("0.1", "gravity = [0.0, 0.0, -9.81]\n"),
                                "box.toml", ".")
        .scenario;
}

// Bitwise equality of two states, field by field, naming the first that differs.
void expect_same_state(const SimulationState& a, const SimulationState& b) {
    auto bytes = [](const auto& v) {
        return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(v[0]));
    };
    const ParticleStore &p = a.particles, &q = b.particles;
    EXPECT_EQ(bytes(p.id), bytes(q.id)) << "particle order";
    EXPECT_EQ(bytes(p.position), bytes(q.position));
    EXPECT_EQ(bytes(p.velocity), bytes(q.velocity));
    EXPECT_EQ(bytes(p.angular_velocity), bytes(q.angular_velocity));
    EXPECT_EQ(bytes(p.force), bytes(q.force));
    EXPECT_EQ(bytes(p.torque), bytes(q.torque));
    EXPECT_EQ(bytes(p.image_shift), bytes(q.image_shift));
    EXPECT_EQ(bytes(p.reference_position), bytes(q.reference_position));
    EXPECT_EQ(bytes(a.neighbors.pairs.first), bytes(b.neighbors.pairs.first)) << "pair order";
    EXPECT_EQ(bytes(a.neighbors.pairs.second), bytes(b.neighbors.pairs.second));
    EXPECT_EQ(bytes(a.neighbors.pairs.histories()), bytes(b.neighbors.pairs.histories())) << "contact history";
    EXPECT_EQ(bytes(a.wall_history), bytes(b.wall_history)) << "wall contact history";
    EXPECT_EQ(bytes(a.wall_feature), bytes(b.wall_feature)) << "the mesh features the wall histories follow";
    EXPECT_EQ(a.neighbors.builds, b.neighbors.builds);
    EXPECT_EQ(a.step, b.step);
    EXPECT_EQ(a.time, b.time);
}

std::size_t live_contacts(const SimulationState& s) {
    std::size_t n = 0;
    for (const ContactHistory& h : s.neighbors.pairs.histories()) n += !h.is_zero();
    for (const ContactHistory& h : s.wall_history) n += !h.is_zero();
    return n;
}

// Runs `before` steps, captures, runs `after` more; restores the capture into
// a fresh Simulation (through the file format) and runs `after` there too.
void expect_restored_run_matches(const Scenario& scenario, std::int64_t before, std::int64_t after,
                                 bool turn_after_capture) {
    Simulation original(scenario);
    original.advance(before);
    const io::Checkpoint saved{{}, original.scenario(), original.capture()};
    const std::string bytes = io::encode_checkpoint(saved);
    ASSERT_GT(live_contacts(saved.state), 0u) << "the test needs live contact history";
    if (turn_after_capture) original.set_motion(0, RigidMotion{{}, {0.0, 0.0, 1.0}, 10.0, {}});
    const std::int64_t builds_at_capture = original.neighbors().builds();
    original.advance(after);
    ASSERT_GT(original.neighbors().builds(), builds_at_capture) << "the continuation should rebuild the list";

    io::Checkpoint loaded = io::decode_checkpoint(bytes, "test");
    EXPECT_EQ(io::encode_checkpoint(loaded), bytes) << "decode and encode give the same bytes";
    Simulation restored(loaded.scenario);
    restored.restore(loaded.state);
    if (turn_after_capture) restored.set_motion(0, RigidMotion{{}, {0.0, 0.0, 1.0}, 10.0, {}});
    restored.advance(after);
    expect_same_state(original.capture(), restored.capture());
}

TEST(Checkpoint, RestoredDrumContinuesBitForBit) {
    // 1999 steps: the capture falls between two neighbour-list builds.
    expect_restored_run_matches(small_drum(), 1999, 3000, true);
}

TEST(Checkpoint, RestoredDrumWhileTurningContinuesBitForBit) {
    Scenario s = small_drum();
    Simulation settled(s);
    settled.advance(2000);
    settled.set_motion(0, RigidMotion{{}, {0.0, 0.0, 1.0}, 10.0, {}});
    settled.advance(777);
    // Start the comparison from a turning drum: the motion's start time and
    // the reference positions must come back too.
    io::Checkpoint c = io::decode_checkpoint(io::encode_checkpoint({{}, settled.scenario(), settled.capture()}), "t");
    Simulation a(c.scenario);
    a.restore(c.state);
    settled.advance(2500);
    a.advance(2500);
    expect_same_state(settled.capture(), a.capture());
}

TEST(Checkpoint, RestoredWalledBoxContinuesBitForBit) {
    // With Mindlin's stiffness: the restored run continues bitwise only if
    // the choice comes back from the file (format 6).
    Scenario s = walled_box();
    s.model.tangential_stiffness = TangentialStiffness::Mindlin;
    expect_restored_run_matches(s, 3001, 2000, false);
}

// The small drum's grains in a smooth drum instead of its wall spheres: a
// turning capped cylinder of the wall material. The walls come back from the
// file (format 7) with their contact histories.
TEST(Checkpoint, RestoredSmoothDrumContinuesBitForBit) {
    Scenario s = small_drum();
    std::erase_if(s.particles, [](const ParticleSpec& p) { return p.motion != free_motion; });
    s.motions[0].angular_velocity = 5.0;
    const Wall mantle{.name = "mantle", .shape = WallShape::cylinder, .point = {0.0, 0.0, -0.015},
                      .radius = 0.015, .length = 0.03, .material = 2, .motion = 0};
    Wall cap{.name = "cap", .shape = WallShape::disc, .point = mantle.point, .radius = 0.015, .material = 2, .motion = 0};
    s.walls = {mantle, cap};
    cap.point.z = 0.015;
    s.walls.push_back(cap);
    expect_restored_run_matches(s, 1999, 3000, false);
}

// The smooth drum's mantle made of triangles: 36 facets round, 3 along,
// from z = -0.015 to 0.015 (a grain in a crease between two facets has two
// contacts, each with its history slot and its feature); the mesh and the
// features come back from the file (format 8).
TEST(Checkpoint, RestoredMeshDrumContinuesBitForBit) {
    Scenario s = small_drum();
    std::erase_if(s.particles, [](const ParticleSpec& p) { return p.motion != free_motion; });
    s.motions[0].angular_velocity = 5.0;
    TriangleMesh mantle;
    const int around = 36, along = 3;
    const double Rc = 0.015;
    for (int j = 0; j <= along; ++j)
        for (int i = 0; i < around; ++i) {
            const double phi = 2.0 * 3.14159265358979323846 * i / around;
            mantle.vertices.push_back({Rc * std::cos(phi), Rc * std::sin(phi), -0.015 + 0.03 * j / along});
        }
    const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * around + i % around); };
    for (int j = 0; j < along; ++j)
        for (int i = 0; i < around; ++i) {
            mantle.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            mantle.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    s.meshes = {mantle};
    const Wall drum{.name = "mantle", .shape = WallShape::mesh, .point = {}, .material = 2, .motion = 0, .mesh = 0};
    Wall cap{.name = "cap", .shape = WallShape::disc, .point = {0.0, 0.0, -0.015}, .radius = 0.015, .material = 2, .motion = 0};
    s.walls = {drum, cap};
    cap.point.z = 0.015;
    s.walls.push_back(cap);
    expect_restored_run_matches(s, 1999, 3000, false);
    Simulation sim(s);
    sim.advance(1999);
    std::size_t followed = 0;  // the test needs slots that follow mesh features
    for (std::uint32_t f : sim.capture().wall_feature) followed += f != 0;
    EXPECT_GT(followed, 5u);
}

TEST(Checkpoint, RestoreRefusesAStateOfAnotherScenario) {
    Simulation drum(small_drum());
    Simulation box(walled_box());
    try {
        box.restore(drum.capture());
        FAIL() << "restored a drum state into a box";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("particles"), std::string::npos) << e.what();
    }
}

TEST(Checkpoint, RecordKeepsItsValuesAndNamesMissingKeys) {
    Simulation sim(walled_box());
    io::Checkpoint c{{}, sim.scenario(), sim.capture()};
    c.record.set("command", std::string("run"));
    c.record.set("n", std::int64_t{-7});
    c.record.set("x", 0.1);
    c.record.set("times", std::vector<double>{0.5, 1e-300});
    const io::Checkpoint back = io::decode_checkpoint(io::encode_checkpoint(c), "file.tck");
    EXPECT_EQ(back.record.text("command"), "run");
    EXPECT_EQ(back.record.integer("n"), -7);
    EXPECT_EQ(back.record.number("x"), 0.1);
    EXPECT_EQ(back.record.numbers("times"), (std::vector<double>{0.5, 1e-300}));
    try {
        back.record.number("y");
        FAIL();
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "file.tck: record key \"y\" is missing");
    }
    EXPECT_THROW(back.record.number("n"), Error) << "an integer is not a number";
}

class CheckpointFiles : public test_support::ScratchTest {
protected:
    // Two checkpoints at steps 10 and 20; returns their paths.
    std::vector<fs::path> write_two() {
        Simulation sim(walled_box());
        io::Checkpoint c{{}, sim.scenario(), {}};
        for (int k = 0; k < 2; ++k) {
            sim.advance(10);
            c.state = sim.capture();
            io::write_checkpoint(dir_, c);
        }
        return io::checkpoint_files(dir_);
    }
    std::string reject_reason_after(const std::function<void(std::string&)>& damage) {
        const std::vector<fs::path> files = write_two();
        std::string bytes = test_support::read_file(files.back());
        damage(bytes);
        std::ofstream(files.back(), std::ios::binary | std::ios::trunc) << bytes;
        const io::LoadedCheckpoint loaded = io::load_newest_checkpoint(dir_);
        EXPECT_EQ(loaded.file, files.front()) << "the previous checkpoint is used";
        EXPECT_EQ(loaded.checkpoint.state.step, 10);
        EXPECT_EQ(loaded.rejected.size(), 1u);
        return loaded.rejected.empty() ? "" : loaded.rejected.front();
    }
};

TEST_F(CheckpointFiles, KeepsTheNewestTwo) {
    write_two();
    Simulation sim(walled_box());
    io::write_checkpoint(dir_, {{}, sim.scenario(), sim.capture()});
    const std::vector<fs::path> files = io::checkpoint_files(dir_);
    ASSERT_EQ(files.size(), 2u);
    EXPECT_EQ(files[0].filename(), "000002.tck");
    EXPECT_EQ(files[1].filename(), "000003.tck");
    EXPECT_FALSE(fs::exists(dir_ / "checkpoints" / "000003.tck.tmp"));
}

TEST_F(CheckpointFiles, AFlippedByteIsCaughtByTheChecksum) {
    const std::string why = reject_reason_after([](std::string& b) { b[b.size() / 2] ^= 0x10; });
    EXPECT_NE(why.find("000002.tck: checksum mismatch"), std::string::npos) << why;
}

TEST_F(CheckpointFiles, ATruncatedFileIsRejected) {
    const std::string why = reject_reason_after([](std::string& b) { b.resize(b.size() - 1000); });
    EXPECT_NE(why.find("000002.tck"), std::string::npos) << why;
    EXPECT_NE(why.find("truncated"), std::string::npos) << why;
}

TEST_F(CheckpointFiles, ForeignAndFutureFilesAreRejected) {
    EXPECT_NE(reject_reason_after([](std::string& b) { b = "hello"; }).find("not a tumble checkpoint"),
              std::string::npos);
    fs::remove_all(dir_ / "checkpoints");
    EXPECT_NE(reject_reason_after([](std::string& b) { b[8] = 99; }).find("format version 99"), std::string::npos);
}

TEST_F(CheckpointFiles, AWriteCutShortLeavesThePreviousOneLoadable) {
    // What kill -9 in the middle of write_checkpoint leaves: a partial
    // temporary file beside the intact ones.
    const std::vector<fs::path> files = write_two();
    const std::string bytes = test_support::read_file(files.back());
    std::ofstream(dir_ / "checkpoints" / "000003.tck.tmp", std::ios::binary) << bytes.substr(0, bytes.size() / 3);
    const io::LoadedCheckpoint loaded = io::load_newest_checkpoint(dir_);
    EXPECT_EQ(loaded.file, files.back());
    EXPECT_TRUE(loaded.rejected.empty());
}

TEST_F(CheckpointFiles, NoCheckpointIsAClearError) {
    try {
        io::load_newest_checkpoint(dir_);
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("cannot resume: no checkpoints"), std::string::npos) << e.what();
    }
}

TEST_F(CheckpointFiles, AnUnwritableDirectoryIsReportedWithThePath) {
    if (::geteuid() == 0) GTEST_SKIP() << "root writes anywhere";
    fs::create_directories(dir_ / "checkpoints");
    fs::permissions(dir_ / "checkpoints", fs::perms::owner_read | fs::perms::owner_exec);
    Simulation sim(walled_box());
    try {
        io::write_checkpoint(dir_, {{}, sim.scenario(), sim.capture()});
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("000001.tck.tmp"), std::string::npos) << e.what();
    }
    fs::permissions(dir_ / "checkpoints", fs::perms::owner_all);
}

// ---- CRC-32 (zlib) -------------------------------------------------------

// CRC-32 by its definition (IEEE 802.3, reflected polynomial 0xEDB88320,
// initial value and final XOR 0xFFFFFFFF), one bit at a time.
std::uint32_t crc32_by_definition(std::string_view bytes) {
    std::uint32_t c = 0xFFFFFFFFu;
    for (unsigned char byte : bytes) {
        c ^= byte;
        for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    }
    return c ^ 0xFFFFFFFFu;
}

TEST(Crc32, IsTheStandardCrc) {
    EXPECT_EQ(io::crc32("123456789"), 0xCBF43926u);  // the standard check value of CRC-32
    EXPECT_EQ(io::crc32(""), 0u);
    std::mt19937 random(7);
    std::string bytes(100000, '\0');
    for (char& b : bytes) b = static_cast<char>(random());
    EXPECT_EQ(io::crc32(bytes), crc32_by_definition(bytes));
}

// A checkpoint written by tumble before its CRC-32 came from zlib (built at
// commit 49d1b62; `tumble run --stop-at-step 50` of 30 spheres of material
// "m" dropped into a walled 4 cm box, as test_support::walled_box_scenario,
// with seed 3) still loads: its stored checksum is the one zlib computes.
TEST(Crc32, ACheckpointWrittenBeforeZlibStillLoads) {
    const std::string bytes =
        test_support::read_file(fs::path(TUMBLE_SOURCE_DIR) / "tests/data/checkpoints/before_zlib.tck");
    ASSERT_GT(bytes.size(), 4u);
    std::uint32_t stored = 0;
    std::memcpy(&stored, bytes.data() + bytes.size() - 4, 4);  // the trailer: little-endian CRC of all before it
    EXPECT_EQ(io::crc32(std::string_view(bytes).substr(0, bytes.size() - 4)), stored);
    const io::Checkpoint c = io::decode_checkpoint(bytes, "before_zlib.tck");
    EXPECT_EQ(c.state.step, 50);
    EXPECT_EQ(c.scenario.particles.size(), 30u);
}

// Format 4 was written two ways on 2026-11-30 (io/checkpoint.hpp): without
// the slab cuts (commits 1a68a4f to 2f2c542, 16:11 to 16:51 UTC; the band
// study's checkpoints) and with them (bc6e54a to 9358371, until 19:20). Both
// files below are `tumble run --stop-at-step 50` of the walled box of
// test_support::walled_box_scenario with seed 3, one process (built at
// 2f2c542 and at 9358371 with the band analysis on top); both load, at
// step 50 with 30 spheres, all their own, and no cuts of a one-process run.
TEST(CheckpointFormat, BothKindsOfFormat4Load) {
    for (const char* name : {"format4_without_cuts.tck", "format4_with_cuts.tck"}) {
        const std::string bytes =
            test_support::read_file(fs::path(TUMBLE_SOURCE_DIR) / "tests/data/checkpoints" / name);
        std::uint32_t version = 0;
        std::memcpy(&version, bytes.data() + 8, 4);  // after the 8 bytes of TUMBLECK
        EXPECT_EQ(version, 4u) << name;
        const io::Checkpoint c = io::decode_checkpoint(bytes, name);
        EXPECT_EQ(c.state.step, 50) << name;
        EXPECT_EQ(c.scenario.particles.size(), 30u) << name;
        EXPECT_EQ(c.state.owned, 30u) << name;
        EXPECT_EQ(c.state.ranks, 1) << name;
        EXPECT_TRUE(c.state.slabs.cuts.empty()) << name;
    }
    // And what tumble writes now is format 9 (a mesh's side, the insertions).
    EXPECT_EQ(io::checkpoint_format_version, 9u);
}

}  // namespace
