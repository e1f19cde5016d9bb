// SPDX-License-Identifier: MIT
// The tumble command as a user meets it: exit codes, messages, and that the
// same input and seed give byte-identical output files.
#include <gtest/gtest.h>

#include "test_support.hpp"
#include "io/drum_output.hpp"
#include "io/json.hpp"
#include "io/snapshots.hpp"
#include "io/sweep.hpp"
#include "tumble/core/isa.hpp"
#include "tumble/core/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>
#include <string>
#include <tuple>

#include <fmt/format.h>

namespace fs = std::filesystem;

namespace {

using tumble::test_support::read_file;
using Result = tumble::test_support::CommandResult;
using tumble::test_support::small_scenario;

Result run_tumble(const std::string& arguments) {
    return tumble::test_support::run_command(std::string(TUMBLE_BINARY) + " " + arguments);
}

// The last line of the output (the JSON object of --json).
std::string last_line(const std::string& output) {
    const std::string text = output.substr(0, output.find_last_not_of('\n') + 1);
    return text.substr(text.find_last_of('\n') + 1);
}

class Cli : public tumble::test_support::ScratchTest {};

}  // namespace

TEST(CliBasics, VersionAndHelp) {
    const Result version = run_tumble("--version");
    EXPECT_EQ(version.exit_code, 0);
    EXPECT_NE(version.output.find("tumble"), std::string::npos);
    const Result help = run_tumble("--help");
    EXPECT_EQ(help.exit_code, 0);
    EXPECT_NE(help.output.find("run"), std::string::npos);
    EXPECT_NE(help.output.find("bench"), std::string::npos);
}

// The contact model's choices of the drum: an unknown one is refused at once,
// naming the option and the choices (docs/MODEL.md, "Shear models").
TEST(CliBasics, DrumRefusesAnUnknownShearModelOrFrictionNormal) {
    const Result shear = run_tumble("drum --shear slip --out /nonexistent/never-written");
    EXPECT_NE(shear.exit_code, 0);
    EXPECT_NE(shear.output.find("--shear: slip not in {paper,coulomb,spring,off}"), std::string::npos) << shear.output;
    const Result normal = run_tumble("drum --friction-normal elastic --out /nonexistent/never-written");
    EXPECT_NE(normal.exit_code, 0);
    EXPECT_NE(normal.output.find("--friction-normal: elastic not in {net,jkr}"), std::string::npos) << normal.output;
    const Result stiffness = run_tumble("drum --tangential-stiffness hertz --out /nonexistent/never-written");
    EXPECT_NE(stiffness.exit_code, 0);
    EXPECT_NE(stiffness.output.find("--tangential-stiffness: hertz not in {paper,mindlin}"), std::string::npos)
        << stiffness.output;
}

// Command-line mistakes exit with tumble's usage code (2, as bad input; not
// CLI11's 104-109), naming the nearest command or option.
TEST(CliBasics, MistakesSuggestTheNearestCommandOrOption) {
    const Result command = run_tumble("rnu");
    EXPECT_EQ(command.exit_code, 2) << command.output;
    EXPECT_NE(command.output.find("unknown command 'rnu'; did you mean 'run'?"), std::string::npos) << command.output;
    EXPECT_NE(command.output.find("commands: run, bench, drum"), std::string::npos) << command.output;
    const Result option = run_tumble("drum --revolution 2 --out /nonexistent/never-written");
    EXPECT_EQ(option.exit_code, 2) << option.output;
    EXPECT_NE(option.output.find("unknown option '--revolution' of tumble drum; did you mean '--revolutions'?"),
              std::string::npos)
        << option.output;
    EXPECT_NE(option.output.find("see 'tumble drum --help'"), std::string::npos) << option.output;
    const Result value = run_tumble("drum --grains many --out /nonexistent/never-written");
    EXPECT_EQ(value.exit_code, 2) << value.output;
    EXPECT_NE(value.output.find("--grains"), std::string::npos) << value.output;
    EXPECT_EQ(run_tumble("").exit_code, 2);
    EXPECT_EQ(run_tumble("drum --help").exit_code, 0);
}

// The help shows flags without CLI11's default markers and cites only the
// repository's documents.
TEST(CliBasics, HelpShowsPlainFlagsAndCitesTheDocs) {
    const Result drum = run_tumble("drum --help");
    EXPECT_NE(drum.output.find("--no-plot "), std::string::npos) << drum.output;
    EXPECT_EQ(drum.output.find("{false}"), std::string::npos) << drum.output;
    for (const char* command : {"--help", "bench --help", "drum --help", "run --help", "render --help"})
        EXPECT_EQ(run_tumble(command).output.find("SPEC-NOTES"), std::string::npos) << command;
}

// Away from a terminal (here a pipe) a run says how far it is at a steady
// interval, as LAMMPS's thermo lines; --progress-every 0 silences it.
TEST_F(Cli, ProgressLinesWhenTheOutputIsNotATerminal) {
    const fs::path scenario = write("small.toml", small_scenario);
    const Result run = run_tumble("run " + scenario.string() + " --out " + (dir_ / "run").string() +
                                  " --progress-every 0.000001");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_NE(run.output.find("progress: run: steps "), std::string::npos) << run.output;
    EXPECT_NE(run.output.find(" of 2000 ("), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("steps/s"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("ETA "), std::string::npos) << run.output;
    // The closing line gives a short run's time to three digits (it said "0.0 s" below a twentieth of a second).
    std::smatch done;
    const std::string output = run.output;
    ASSERT_TRUE(std::regex_search(output, done, std::regex(R"(done in ([0-9.]+) s \()"))) << run.output;
    const std::string digits = std::regex_replace(done[1].str(), std::regex(R"(^[0.]+|\.)"), "");
    if (std::stod(done[1].str()) < 100.0) {
        EXPECT_EQ(digits.size(), 3u) << done[0];
    }

    const Result drum = run_tumble("drum --grains 150 --omega 8 --revolutions 0.25 --snapshots 0 --no-plot --out " +
                                   (dir_ / "drum").string() + " --progress-every 0.000001");
    ASSERT_EQ(drum.exit_code, 0) << drum.output;
    EXPECT_NE(drum.output.find("progress: settling: steps "), std::string::npos) << drum.output;
    EXPECT_NE(drum.output.find("rms grain speed"), std::string::npos) << drum.output;
    EXPECT_NE(drum.output.find("settled below 0.01"), std::string::npos) << drum.output;
    const std::size_t rotation = drum.output.find("progress: rotation: steps ");
    ASSERT_NE(rotation, std::string::npos) << drum.output;
    const std::string line = drum.output.substr(rotation, drum.output.find('\n', rotation) - rotation);
    for (const char* field : {"revolution ", " of 0.25", "steps/s", "rev/h", "ETA "})
        EXPECT_NE(line.find(field), std::string::npos) << field << " in: " << line;

    const Result silent = run_tumble("run " + scenario.string() + " --out " + (dir_ / "silent").string() +
                                     " --progress-every 0");
    ASSERT_EQ(silent.exit_code, 0) << silent.output;
    EXPECT_EQ(silent.output.find("progress:"), std::string::npos) << silent.output;
}

TEST_F(Cli, SameInputAndSeedGiveIdenticalFiles) {
    const fs::path scenario = write("small.toml", small_scenario);
    const Result a = run_tumble("run -q " + scenario.string() + " --out " + (dir_ / "a").string());
    const Result b = run_tumble("run -q " + scenario.string() + " --out " + (dir_ / "b").string());
    ASSERT_EQ(a.exit_code, 0) << a.output;
    ASSERT_EQ(b.exit_code, 0) << b.output;
    const std::string series = read_file(dir_ / "a" / "time_series.csv");
    // 2000 steps of 1e-5 s sampled every 100 steps: the header and 21 rows.
    EXPECT_EQ(std::count(series.begin(), series.end(), '\n'), 22);
    EXPECT_EQ(series, read_file(dir_ / "b" / "time_series.csv"));
    int snapshots = 0;
    for (const auto& entry : fs::directory_iterator(dir_ / "a" / "snapshots")) {
        ++snapshots;
        EXPECT_EQ(read_file(entry.path()), read_file(dir_ / "b" / "snapshots" / entry.path().filename()))
            << entry.path().filename();
    }
    EXPECT_EQ(snapshots, 12);  // t = 0, 0.01, 0.02 s, each as .csv, .vtu, .xyz and .vtp
    for (const char* index : {"particles.pvd", "contacts.pvd"})
        EXPECT_EQ(read_file(dir_ / "a" / index), read_file(dir_ / "b" / index)) << index;
}

// A run with smooth walls: each wall's load in time_series.csv (a turning
// plate drawn where it has turned in snapshots/NNNNNN_walls.vtp, indexed by
// walls.pvd), the floor's load most of the grains' weight once they rest.
TEST_F(Cli, WallLoadsAndDrawingsAreWritten) {
    const std::string scenario_text = tumble::test_support::walled_box_scenario(
        "0.4", "gravity = [0.0, 0.0, -9.81]\n",
        R"([[motion]]
name = "turn"
angular_velocity = 2.0
[[wall]]
name = "floor"
shape = "plane"
material = "m"
point = [0.0, 0.0, 0.002]
[[wall]]
name = "plate"
shape = "rectangle"
material = "m"
motion = "turn"
point = [0.0, 0.0, 0.06]
size = [0.01, 0.01]
[output]
time_series_interval = 0.1
snapshot_interval = 0.2
)");
    const fs::path scenario = write("walls.toml", scenario_text);
    const Result r = run_tumble("run -q " + scenario.string() + " --out " + (dir_ / "out").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const tumble::io::CsvTable series = tumble::io::read_csv_table(dir_ / "out" / "time_series.csv");
    for (const char* column : {"wall_floor_fx", "wall_floor_fz", "wall_floor_tz", "wall_plate_fz", "wall_plate_ty"})
        EXPECT_NO_THROW((void)series.column(column)) << column;
    const double weight = 30 * 1000.0 * 4.0 / 3.0 * 3.141592653589793 * 0.0036 * 0.0036 * 0.0036 * 9.81;
    // At rest the floor carries the weight but what friction and adhesion
    // hold on the box's side walls; it cannot carry more.
    const double floor = -series.numbers("wall_floor_fz").back();
    EXPECT_GT(floor, 0.5 * weight);
    EXPECT_LT(floor, 1.001 * weight);
    EXPECT_EQ(series.numbers("wall_plate_fz").back(), 0.0);  // nothing touches the plate above the box
    for (const char* file : {"walls.pvd", "snapshots/000000_walls.vtp", "snapshots/000002_walls.vtp"})
        EXPECT_TRUE(fs::exists(dir_ / "out" / file)) << file;
}

TEST_F(Cli, RefusesToOverwriteAnEarlierRun) {
    const fs::path scenario = write("small.toml", small_scenario);
    const std::string out = (dir_ / "out").string();
    ASSERT_EQ(run_tumble("run -q " + scenario.string() + " --out " + out).exit_code, 0);
    const std::string before = read_file(dir_ / "out" / "time_series.csv");
    const Result again = run_tumble("run -q " + scenario.string() + " --out " + out);
    EXPECT_NE(again.exit_code, 0);
    EXPECT_NE(again.output.find("--force"), std::string::npos) << again.output;
    EXPECT_EQ(read_file(dir_ / "out" / "time_series.csv"), before);
    EXPECT_EQ(run_tumble("run -q --force " + scenario.string() + " --out " + out).exit_code, 0);
}

TEST_F(Cli, BadInputNamesFileKeyAndReasonAndWritesNothing) {
    std::string bad = small_scenario;
    bad.replace(bad.find("nu = 0.25"), 9, "nu = 0.7");
    const fs::path scenario = write("bad.toml", bad);
    const Result r = run_tumble("run " + scenario.string() + " --out " + (dir_ / "out").string());
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.output.find("bad.toml"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("nu"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(Cli, MissingFileIsAClearError) {
    const Result r = run_tumble("run " + (dir_ / "nowhere.toml").string());
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.output.find("nowhere.toml"), std::string::npos) << r.output;
}

TEST_F(Cli, TooLargeTimeStepIsRefusedWithTheReason) {
    std::string bad = small_scenario;
    bad.replace(bad.find("dt = 1e-5"), 9, "dt = 1e-3");
    const fs::path scenario = write("coarse.toml", bad);
    const Result r = run_tumble("run " + scenario.string() + " --out " + (dir_ / "out").string());
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.output.find("safe maximum"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST(CliBench, JsonLastLineHasTheBenchmarkKeys) {
    // A tiny lattice and few steps: this checks the report, not the speed.
    const Result r = run_tumble("bench --size 8 --steps 20 --warmup 0 --json");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const tumble::io::Json j = tumble::io::parse_json(last_line(r.output));
    EXPECT_EQ(j.at("particles").get<int>(), 512) << r.output;
    EXPECT_EQ(j.at("steps").get<int>(), 20);
    for (const char* key : {"seconds", "updates_per_second"})
        EXPECT_TRUE(tumble::io::json_number(j, key).has_value()) << key << " missing in: " << r.output;
    // Each sphere of the 1.98 R lattice overlaps its six neighbours.
    EXPECT_EQ(j.at("contacts_per_particle").get<double>(), 6.0) << r.output;
}

TEST(CliBench, ThreadsAndMemoryAreReported) {
    const Result r = run_tumble("bench --size 8 --steps 5 --warmup 0 --threads 2 --json");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    // Without OpenMP the command runs on one thread and says so.
    const tumble::io::Json j = tumble::io::parse_json(last_line(r.output));
    EXPECT_EQ(j.at("threads").get<int>(), tumble::parallel_build() ? 2 : 1) << r.output;
    EXPECT_GT(j.at("bytes_per_particle").get<double>(), 0.0) << r.output;
    EXPECT_NE(run_tumble("bench --size 8 --steps 5 --threads -1").exit_code, 0);
}

// The instruction set of the hot loops is reported; TUMBLE_ISA chooses it,
// and a value that is not a level is refused before anything runs.
TEST(CliBench, InstructionSetIsReportedAndAnUnknownOneRefused) {
    const Result r = run_tumble("bench --size 8 --steps 5 --warmup 0 --json");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_FALSE(tumble::io::parse_json(last_line(r.output)).value("isa", "").empty()) << r.output;
    const Result baseline = tumble::test_support::run_command("TUMBLE_ISA=baseline " + std::string(TUMBLE_BINARY) +
                                                              " bench --size 8 --steps 5 --warmup 0");
    if constexpr (TUMBLE_ISA_CHOICE) {
        ASSERT_EQ(baseline.exit_code, 0) << baseline.output;
        EXPECT_NE(baseline.output.find("instruction set  baseline (x86-64;"), std::string::npos) << baseline.output;
    } else {  // a build for one processor has no choice to make
        EXPECT_NE(baseline.exit_code, 0) << baseline.output;
    }
    const Result unknown = tumble::test_support::run_command("TUMBLE_ISA=sse9 " + std::string(TUMBLE_BINARY) +
                                                             " bench --size 8 --steps 5 --warmup 0");
    EXPECT_NE(unknown.exit_code, 0);
    EXPECT_NE(unknown.output.find("TUMBLE_ISA=sse9"), std::string::npos) << unknown.output;
}

// A small long drum (2 cm of the paper's cross-section) and few steps: this
// checks the report and the stored bed, not the speed.
TEST_F(Cli, BenchLongDrumReportsEveryFieldAndKeepsTheSettledBed) {
    // 40 steps in all, 1 ms of rotation (time enough for the peer's law below to let contacts go).
    const std::string arguments = "bench --case long-drum --length 0.02 --fill 0.2 --steps 20 --warmup 20 --cache " +
                                  (dir_ / "cache").string();
    const Result table = run_tumble(arguments);
    ASSERT_EQ(table.exit_code, 0) << table.output;
    for (const char* field : {"settled bed made and stored in", "grain updates/s", "revolutions/hour",
                              "steps/revolution", "dt ", "set by", "bytes per particle", "threads", "machine"})
        EXPECT_NE(table.output.find(field), std::string::npos) << field << " missing in: " << table.output;
    const Result json = run_tumble(arguments + " --json --threads 2");
    ASSERT_EQ(json.exit_code, 0) << json.output;
    const tumble::io::Json j = tumble::io::parse_json(last_line(json.output));
    EXPECT_EQ(j.value("bed", ""), "read");  // the second run reads the bed the first made
    EXPECT_EQ(j.value("case", ""), "long-drum");
    for (const char* key : {"grains", "particles", "steps", "seconds", "grain_updates_per_second",
                            "revolutions_per_hour", "steps_per_revolution", "dt", "bytes_per_particle", "threads",
                            "kinetic_translational", "kinetic_rotational", "contacts", "candidate_pairs"})
        EXPECT_TRUE(tumble::io::json_number(j, key).has_value()) << key << " missing in: " << json.output;
    // The drum has no flat walls: every contact is a pair of the list, which
    // holds more (those within the skin).
    EXPECT_GE(j.at("candidate_pairs").get<double>(), j.at("contacts").get<double>());
    EXPECT_GT(j.at("contacts").get<double>(), 0.0);
    EXPECT_FALSE(j.value("thread_binding", "").empty()) << json.output;
    EXPECT_NE(j.value("dt_limited_by", "").find("viscous time"), std::string::npos) << json.output;
    // 5 rad/s at the automatic step: 2 pi / 5 / dt steps per revolution.
    EXPECT_NEAR(j.at("steps_per_revolution").get<double>(), 2.0 * 3.141592653589793 / 5.0 / j.at("dt").get<double>(),
                1e-6);
    EXPECT_EQ(j.at("steps").get<double>(), 20.0);
    EXPECT_EQ(j.at("threads").get<double>(), tumble::parallel_build() ? 2.0 : 1.0);

    // --law peer: the same bed at the same step, the LAMMPS deck's law (no
    // attraction: the settled bed's adhesive contacts let go, fewer touch).
    const Result peer = run_tumble(arguments + " --json --law peer");
    ASSERT_EQ(peer.exit_code, 0) << peer.output;
    const tumble::io::Json pj = tumble::io::parse_json(last_line(peer.output));
    EXPECT_EQ(pj.value("law", ""), "peer");
    EXPECT_EQ(j.value("law", ""), "drum");
    EXPECT_EQ(pj.at("dt").get<double>(), j.at("dt").get<double>());
    EXPECT_NE(pj.value("dt_limited_by", "").find("kept for --law peer"), std::string::npos) << peer.output;
    EXPECT_LT(pj.at("contacts").get<double>(), j.at("contacts").get<double>());

    // --export writes the stored bed, grains and wall, for a peer code and runs nothing.
    const Result exported = run_tumble(arguments + " --export " + (dir_ / "bed").string());
    ASSERT_EQ(exported.exit_code, 0) << exported.output;
    EXPECT_EQ(exported.output.find("grain updates/s"), std::string::npos) << exported.output;
    const tumble::io::SnapshotParticles bed = tumble::io::read_snapshot_csv(dir_ / "bed" / "snapshots" / "000000.csv");
    EXPECT_EQ(static_cast<double>(bed.position.size()), j.at("particles").get<double>());
}

// --turned: the bed turned before the warm-up (steady flow), kept beside
// the settled one. Its wall has turned by exactly the whole steps it ran,
// llround(turned x steps per revolution) x dt x omega (rotation is
// prescribed, so to round-off), and its grains move.
TEST_F(Cli, BenchLongDrumTurnedBedIsKeptAndHasTurned) {
    const std::string arguments = "bench --case long-drum --length 0.02 --fill 0.2 --steps 20 --warmup 5 --cache " +
                                  (dir_ / "cache").string();
    const Result first = run_tumble(arguments + " --turned 0.05 --json");
    ASSERT_EQ(first.exit_code, 0) << first.output;
    const tumble::io::Json j = tumble::io::parse_json(last_line(first.output));
    EXPECT_EQ(j.value("bed", ""), "made");
    EXPECT_EQ(j.at("turned").get<double>(), 0.05);
    const Result again = run_tumble(arguments + " --turned 0.05 --json");
    ASSERT_EQ(again.exit_code, 0) << again.output;
    EXPECT_EQ(tumble::io::parse_json(last_line(again.output)).value("bed", ""), "read");
    std::size_t beds = 0;
    for (const auto& entry : fs::directory_iterator(dir_ / "cache")) beds += entry.path().extension() == ".tck";
    EXPECT_EQ(beds, 2u);  // the settled bed and the turned one

    ASSERT_EQ(run_tumble(arguments + " --export " + (dir_ / "settled").string()).exit_code, 0);
    ASSERT_EQ(run_tumble(arguments + " --turned 0.05 --export " + (dir_ / "turned").string()).exit_code, 0);
    const auto settled = tumble::io::read_snapshot_csv(dir_ / "settled" / "snapshots" / "000000.csv");
    const auto turned = tumble::io::read_snapshot_csv(dir_ / "turned" / "snapshots" / "000000.csv");
    ASSERT_EQ(settled.position.size(), turned.position.size());
    const double dt = j.at("dt").get<double>(), omega = 5.0;
    const double angle = static_cast<double>(std::llround(0.05 * j.at("steps_per_revolution").get<double>())) * dt * omega;
    double grain_moved = 0.0;
    for (std::size_t i = 0; i < settled.position.size(); ++i) {
        const tumble::Vec3 a = settled.position[i], b = turned.position[i];
        if (settled.kinematic[i]) {
            EXPECT_EQ(a.z, b.z);
            if (std::hypot(a.x, a.y) < 1e-3) continue;  // a cap's sphere on the axis: no angle to see
            const double turned_by = std::remainder(std::atan2(b.y, b.x) - std::atan2(a.y, a.x), 2.0 * M_PI);
            EXPECT_NEAR(turned_by, angle, 1e-12) << "wall sphere " << i;
        } else {
            grain_moved = std::max(grain_moved, tumble::norm(b - a));
        }
    }
    // A grain at the wall is carried some 0.05 x 2 pi x 4 cm = 1.3 cm.
    EXPECT_GT(grain_moved, 1e-3);
}

// --walls smooth: the long drum walled by a smooth cylinder and two discs,
// from its own settled bed (its file name says so), no wall spheres.
TEST_F(Cli, BenchLongDrumWithSmoothWallsKeepsItsOwnBed) {
    const std::string arguments = "bench --case long-drum --length 0.02 --fill 0.2 --steps 20 --warmup 5 --json --cache " +
                                  (dir_ / "cache").string();
    const Result particles = run_tumble(arguments);
    ASSERT_EQ(particles.exit_code, 0) << particles.output;
    const Result smooth = run_tumble(arguments + " --walls smooth");
    ASSERT_EQ(smooth.exit_code, 0) << smooth.output;
    const tumble::io::Json p = tumble::io::parse_json(last_line(particles.output));
    const tumble::io::Json j = tumble::io::parse_json(last_line(smooth.output));
    EXPECT_EQ(j.value("walls", ""), "smooth");
    EXPECT_EQ(p.value("walls", ""), "particles");
    EXPECT_EQ(j.value("bed", ""), "made");  // not the particle-walled drum's bed
    EXPECT_EQ(j.at("particles").get<double>(), j.at("grains").get<double>());  // no wall spheres
    EXPECT_EQ(j.at("grains").get<double>(), p.at("grains").get<double>());
    std::vector<std::string> beds;
    for (const auto& entry : fs::directory_iterator(dir_ / "cache")) beds.push_back(entry.path().filename().string());
    std::sort(beds.begin(), beds.end());
    ASSERT_EQ(beds.size(), 2u);
    EXPECT_EQ(beds[0].rfind("long-drum-length", 0), 0u) << beds[0];  // the particle-walled bed's name of before
    EXPECT_EQ(beds[1].rfind("long-drum-smooth-length", 0), 0u) << beds[1];
    EXPECT_EQ(tumble::io::parse_json(last_line(run_tumble(arguments + " --walls smooth").output)).value("bed", ""),
              "read");
}

TEST(CliBench, OptionsOfTheOtherCaseAreRefused) {
    const std::pair<const char*, const char*> cases[] = {{"bench --case long-drum --size 8", "--size"},
                                                         {"bench --length 0.1", "--length"},
                                                         {"bench --case drum", "--case"},
                                                         {"bench --case long-drum --fill 0", "--fill"},
                                                         {"bench --export bed", "--export"},
                                                         {"bench --turned 1", "--turned"},
                                                         {"bench --law peer", "--law"},
                                                         {"bench --walls smooth", "--walls"},
                                                         {"bench --case long-drum --walls glass", "--walls"},
                                                         {"bench --case long-drum --law lammps", "--law"},
                                                         {"bench --case long-drum --turned -1", "--turned"}};
    for (const auto& [arguments, option] : cases) {
        const Result r = run_tumble(arguments);
        EXPECT_NE(r.exit_code, 0) << arguments;
        EXPECT_NE(r.output.find(option), std::string::npos) << arguments << ": " << r.output;
    }
}

TEST(CliContact, DrumTableHasEveryPairAndColumn) {
    const Result r = run_tumble("contact --drum");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const char* text : {"time step 2.614e-05 s (automatic), set by 0.7 x the viscous time m*/c", "largest safe step",
                             "material-1-material-1:", "material-1-material-2:", "material-2-material-2:",
                             "material-1-wall (kinematic):", "material-2-wall (kinematic):", "Hertz collision time",
                             "equilibrium overlap 44.8 um", "pull-off force 2.262 mN", "sticks at every impact speed",
                             "creep time tau 1.071 ms", "restitution", "converged", "1.4 "})
        EXPECT_NE(r.output.find(text), std::string::npos) << text << " missing in: " << r.output;
}

TEST_F(Cli, ContactJsonOfAScenarioFile) {
    const fs::path scenario = write("small.toml", small_scenario);
    const Result r = run_tumble("contact " + scenario.string() + " --speeds 0.1 1 --json");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const tumble::io::Json j = tumble::io::parse_json(last_line(r.output));
    EXPECT_EQ(j.at("dt").get<double>(), 1e-5);  // the scenario's own
    const tumble::io::Json& pairs = j.at("pairs");
    ASSERT_EQ(pairs.size(), 2u);  // material-1 with itself and with the flat floor
    EXPECT_EQ(pairs[1].at("pair").get<std::string>(), "material-1-flat wall");
    for (const tumble::io::Json& pair : pairs) {
        ASSERT_EQ(pair.at("impacts").size(), 2u);
        for (const char* key : {"R_star", "m_star", "hertz_collision_time", "viscous_time", "equilibrium_overlap",
                                "pull_off_force", "sticking_speed"})
            EXPECT_TRUE(tumble::io::json_number(pair, key).has_value()) << key;
        const tumble::io::Json& impact = pair.at("impacts")[0];
        EXPECT_TRUE(tumble::io::json_number(impact.at("at_step"), "restitution").has_value());
        EXPECT_TRUE(tumble::io::json_number(impact.at("converged"), "contact_time").has_value());
    }
}

TEST(CliContact, RefusesMissingOrBadInput) {
    for (const char* arguments : {"contact", "contact --speeds 0 --drum", "contact --drum --speeds nan",
                                  "contact /nonexistent.toml", "contact --mode mixed --drum", "contact --dt 1e-6"}) {
        const Result r = run_tumble(arguments);
        EXPECT_NE(r.exit_code, 0) << arguments;
        EXPECT_FALSE(r.output.empty()) << arguments;
    }
}

TEST(CliContact, AnImpactSpeedBeyondAnyFlowIsRefusedNamingSpeeds) {
    for (const char* speed : {"1e308", "1001"}) {
        const Result r = run_tumble(std::string("contact --drum --speeds ") + speed);
        EXPECT_EQ(r.exit_code, 2) << r.output;
        EXPECT_NE(r.output.find(std::string("--speeds: must be a number > 0 and at most 1000 m/s, got ") + speed),
                  std::string::npos)
            << r.output;
    }
    EXPECT_EQ(run_tumble("contact --drum --speeds 1000").exit_code, 0);
}

TEST_F(Cli, ContactRefusesTheMaterialsThatRunRefuses) {
    // A density of 1e-300 kg/m^3 gives a time step of 0 s; W = 1e300 J/m^2
    // pulls grains at rest into each other. Refused by both commands, with
    // the same message, before any collision is computed.
    const std::string box = tumble::test_support::walled_box_scenario("0.01");
    const std::string light = std::regex_replace(box, std::regex("rho = [0-9.e+]+"), "rho = 1e-300");
    const std::string sticky = std::regex_replace(box, std::regex("W = [0-9.e+]+"), "W = 1e300");
    ASSERT_NE(light, box);
    ASSERT_NE(sticky, box);
    const fs::path light_file = write("light.toml", light), sticky_file = write("sticky.toml", sticky);
    const std::pair<fs::path, std::string> cases[] = {
        {light_file, light_file.string() + ": the time step is 0 s (set by "},
        {sticky_file, sticky_file.string() + ": pair m-m (W = 1e+300 J/m^2): its attraction alone "
                                             "would pull two grains at rest into each other"}};
    for (const auto& [file, message] : cases) {
        for (const std::string& command :
             {"contact " + file.string(), "run -q " + file.string() + " --out " + (dir_ / "out").string()}) {
            const Result r = run_tumble(command);
            EXPECT_EQ(r.exit_code, 2) << command << ": " << r.output;
            EXPECT_NE(r.output.find(message), std::string::npos) << command << ": " << r.output;
            EXPECT_EQ(r.output.find("time step 0 s"), std::string::npos) << "no table: " << r.output;
        }
        EXPECT_FALSE(fs::exists(dir_ / "out" / "time_series.csv"));
    }
    // --allow-soft lets the sticky pair through, as tumble run's does.
    EXPECT_EQ(run_tumble("contact --allow-soft " + sticky_file.string()).exit_code, 0);
}

TEST_F(Cli, DrumRefusesImpossibleSettingsAndWritesNothing) {
    const std::string out = " --out " + (dir_ / "drum").string();
    const std::pair<std::string, std::string> cases[] = {
        {"drum --omega -1", "speed"},
        {"drum --omega 0", "speed"},
        {"drum --fill 1.5", "fill_fraction"},
        {"drum --fill 0", "--fill: must be a finite number > 0, got 0"},  // was taken as "not given": 1000 grains
        {"drum --checkpoint-every-revolutions inf", "--checkpoint-every-revolutions: must be a finite number >= 0"},
        {"drum --revolutions 0", "revolutions"},
        {"drum --mode mixed", "mode"},
        {"drum --diameter 0.01", "diameter"},
    };
    for (const auto& [arguments, key] : cases) {
        const Result r = run_tumble(arguments + out);
        EXPECT_NE(r.exit_code, 0) << arguments;
        EXPECT_NE(r.output.find(key), std::string::npos) << arguments << ": " << r.output;
        EXPECT_FALSE(fs::exists(dir_ / "drum")) << arguments;
    }
    const fs::path config = write("drum.toml", "[rotation]\nomega = 3.0\nspin = 2\n");
    const Result r = run_tumble("drum --config " + config.string() + out);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.output.find("drum.toml: rotation.spin: unknown key"), std::string::npos) << r.output;
}

// A drum on a mantle from an STL file: a missing or bad file, a mesh with
// smooth walls and a mesh on a periodic axis are refused naming the option
// and writing nothing; a good one runs briefly and is recorded.
TEST_F(Cli, DrumOnAMeshMantleRefusesBadFilesAndRecordsGoodOnes) {
    const std::string out = " --out " + (dir_ / "drum").string();
    const fs::path flat = write("flat.stl", "solid flat\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                            "vertex 2 0 0\nendloop\nendfacet\nendsolid flat\n");
    const std::pair<std::string, std::string> cases[] = {
        {"drum --mesh " + (dir_ / "none.stl").string(), "none.stl: no such file"},
        {"drum --mesh " + flat.string(), "triangle 1 (line 2): degenerate"},
        {"drum --walls smooth --mesh " + (fs::path(TUMBLE_SOURCE_DIR) / "examples/meshes/drum_lifters.stl").string(),
         "--walls: smooth walls, but the mantle is the mesh"},
        {"drum --walls mesh --periodic-axis", "periodic_axis: a mesh mantle has ends"},
        {"drum --mesh-scale 0", "--mesh-scale: must be a finite number > 0"},
    };
    for (const auto& [arguments, key] : cases) {
        const Result r = run_tumble(arguments + out);
        EXPECT_NE(r.exit_code, 0) << arguments;
        EXPECT_NE(r.output.find(key), std::string::npos) << arguments << ": " << r.output;
        EXPECT_FALSE(fs::exists(dir_ / "drum")) << arguments;
    }
    const fs::path run = dir_ / "lifters";
    const Result r = run_tumble("drum -q --no-plot --config " +
                                (fs::path(TUMBLE_SOURCE_DIR) / "examples/drum_lifters.toml").string() +
                                " --grains 200 --omega 8 --revolutions 0.1 --samples 40 --snapshots 0 --out " +
                                run.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const tumble::io::DrumRunInfo info = tumble::io::read_drum_run_info(run / "drum_run.toml");
    EXPECT_EQ(info.walls, "mesh");
    EXPECT_EQ(fs::path(info.mesh).filename(), "drum_lifters.stl");
    EXPECT_EQ(info.mesh_scale, 1e-3);
}

// The drum of its own materials (cohesionless glass-like beads of 3 and 2
// mm, a steel wall) with smooth walls, short: the run and its analysis go
// through, and what was run is recorded. It checks the files, not the
// physics (tests/physics/test_drum_walls.cpp).
TEST_F(Cli, DrumOfItsOwnMaterialsWithSmoothWallsRecordsBoth) {
    std::string tables;
    for (const auto& [name, radius, rho] : {std::tuple{"glass-3mm", 3.0e-3, 2500.0}, std::tuple{"glass-2mm", 2.0e-3, 2500.0},
                                            std::tuple{"steel", 3.0e-3, 7800.0}})
        tables += fmt::format("[[material]]\nname = \"{}\"\nE = 1.0e7\nG = 4.0e6\nnu = 0.22\nxi = 50.0\neta = 50.0\n"
                              "rho = {}\nradius = {}\n",
                              name, rho, radius);
    for (const auto& [a, b, mu] : {std::tuple{"glass-3mm", "glass-3mm", 0.3}, std::tuple{"glass-3mm", "glass-2mm", 0.3},
                                   std::tuple{"glass-2mm", "glass-2mm", 0.3}, std::tuple{"glass-3mm", "steel", 0.4},
                                   std::tuple{"glass-2mm", "steel", 0.4}, std::tuple{"steel", "steel", 0.4}})
        tables += fmt::format("[[pair]]\nmaterials = [\"{}\", \"{}\"]\nmu = {}\nW = 0.0\n", a, b, mu);
    const fs::path config = write("glass.toml", tables + "[materials]\nlarge = \"glass-3mm\"\nsmall = \"glass-2mm\"\n"
                                                         "wall = \"steel\"\n");
    const fs::path run = dir_ / "glass";
    const Result r = run_tumble("drum -q --no-plot --config " + config.string() +
                                " --walls smooth --grains 200 --omega 8 --revolutions 0.2 --samples 40 --snapshots 10 "
                                "--out " + run.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const tumble::io::DrumRunInfo info = tumble::io::read_drum_run_info(run / "drum_run.toml");
    EXPECT_EQ(info.walls, "smooth");
    EXPECT_EQ(info.wall_particles, 0u);
    EXPECT_FALSE(info.paper_materials);
    EXPECT_EQ(info.large_material, "glass-3mm");
    EXPECT_EQ(info.small_material, "glass-2mm");
    EXPECT_EQ(info.wall_material, "steel");
    EXPECT_EQ(info.cap_material, "steel");
    ASSERT_EQ(info.materials.size(), 3u);
    EXPECT_EQ(info.materials[2].rho, 7800.0);
    EXPECT_EQ(info.surface_energy, 0.0);  // every pair's W
    ASSERT_EQ(info.components.size(), 2u);
    EXPECT_EQ(info.components[0].name, "glass-3mm");
    EXPECT_EQ(info.components[1].name, "glass-2mm");
    const tumble::io::Json j = tumble::io::parse_json(read_file(run / "summary.json"));
    EXPECT_EQ(j.value("walls", ""), "smooth");
    EXPECT_EQ(j.at("materials").value("large", ""), "glass-3mm");
    EXPECT_EQ(j.at("materials").value("wall", ""), "steel");
    EXPECT_FALSE(j.at("materials").value("paper", true));
    const std::string text = read_file(run / "summary.txt");
    EXPECT_NE(text.find("smooth walls (a cylinder and two discs)"), std::string::npos) << text;
    EXPECT_NE(text.find("materials: large grains glass-3mm (R = 0.003 m), small grains glass-2mm (R = 0.002 m), "
                        "wall steel, caps steel"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("W = 0 J/m^2 (no attraction)"), std::string::npos) << text;
    EXPECT_NE(read_file(run / "drum_series.csv").find("mean_z_glass_3mm"), std::string::npos);
    // The analysis again, from the files: the grains' masses from the recorded materials.
    fs::remove(run / "summary.json");
    const Result again = run_tumble("analyze " + run.string());
    ASSERT_EQ(again.exit_code, 0) << again.output;
    EXPECT_NE(again.output.find("glass-2mm"), std::string::npos) << again.output;

    // What the run's line says; a wall kind or a material that is not there is refused.
    const Result bad_walls = run_tumble("drum --walls glass --out " + (dir_ / "no").string());
    EXPECT_NE(bad_walls.exit_code, 0);
    EXPECT_NE(bad_walls.output.find("--walls"), std::string::npos) << bad_walls.output;
    const fs::path wrong = write("wrong.toml", tables + "[materials]\nlarge = \"glass-3mm\"\nsmall = \"glass-2m\"\n"
                                                        "wall = \"steel\"\n");
    const Result bad_material = run_tumble("drum --config " + wrong.string() + " --out " + (dir_ / "no").string());
    EXPECT_EQ(bad_material.exit_code, 2);
    EXPECT_NE(bad_material.output.find("wrong.toml: materials.small: unknown material \"glass-2m\" (did you mean "
                                       "\"glass-2mm\"?)"),
              std::string::npos)
        << bad_material.output;
    // The two-component mode asked on the command line of a file made for the self mode.
    const fs::path self = write("self.toml", tables + "[fill]\nmode = \"self\"\n[materials]\nlarge = \"glass-3mm\"\n"
                                                      "wall = \"steel\"\n");
    const Result no_small = run_tumble("drum --config " + self.string() + " --mode two-component --out " +
                                       (dir_ / "no").string());
    EXPECT_EQ(no_small.exit_code, 2);
    EXPECT_NE(no_small.output.find("command line: materials.small: missing"), std::string::npos) << no_small.output;
    EXPECT_FALSE(fs::exists(dir_ / "no"));
}

TEST_F(Cli, DrumRunWritesSeriesAndSummaryAndCanBeAnalysedAgain) {
    // A small, short drum: 300 grains, 0.3 revolutions at 8 rad/s sampled
    // 40 times per revolution, with the spring shear model, the JKR friction
    // normal, a neighbour skin of 1 mm and half the paper's surface energy.
    // It checks the files, not the physics.
    const fs::path run = dir_ / "drum";
    const Result r = run_tumble("drum -q --grains 300 --omega 8 --revolutions 0.3 --samples 40 --snapshots 10 "
                                "--shear spring --friction-normal jkr --tangential-stiffness mindlin --skin 0.001 "
                                "--surface-energy 0.1 --out " + run.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const char* file : {"drum_run.toml", "drum_series.csv", "profiles.csv", "profile_comparison.csv",
                             "depth_mobility.csv", "summary.json", "summary.txt", "time_series.csv"})
        EXPECT_TRUE(fs::exists(run / file)) << file;
    const std::string series = read_file(run / "drum_series.csv");
    // The header, N = 0, 12 samples at 1/40 revolution (and the final state
    // if the step count does not divide evenly).
    const auto rows = std::count(series.begin(), series.end(), '\n');
    EXPECT_GE(rows, 14);
    EXPECT_LE(rows, 15);
    const std::string summary = read_file(run / "summary.json");
    for (const char* key : {"\"D\"", "\"D_stderr\"", "\"D_one_term\"", "\"omega\"", "\"revolutions\"", "\"grains\"",
                            "\"wall_particles\"", "\"fill_fraction\"", "\"kinetic_energy_ratio_total\"",
                            "\"kinetic_energy_ratio_per_grain_equal_velocity\"", "\"depth_mobility\"",
                            "\"surface_share\""})
        EXPECT_NE(summary.find(key), std::string::npos) << key;
    EXPECT_EQ(summary.find("NaN"), std::string::npos) << "JSON has no NaN";
    // The contact model chosen is recorded with the results.
    const tumble::io::Json j = tumble::io::parse_json(summary);
    EXPECT_EQ(j.value("shear_model", ""), "spring") << summary.substr(0, 400);
    EXPECT_EQ(j.value("friction_normal", ""), "jkr");
    EXPECT_EQ(j.value("tangential_stiffness", ""), "mindlin");
    EXPECT_EQ(tumble::io::read_drum_run_info(run / "drum_run.toml").tangential_stiffness, "mindlin");
    EXPECT_NE(read_file(run / "drum_run.toml").find("shear_model = 'spring'"), std::string::npos);
    EXPECT_EQ(tumble::io::read_drum_run_info(run / "drum_run.toml").skin, 0.001);
    EXPECT_EQ(tumble::io::read_drum_run_info(run / "drum_run.toml").surface_energy, 0.1);
    EXPECT_EQ(j.value("surface_energy", 0.0), 0.1);
    // A D that is not determined is null, everywhere in the summary (its
    // best estimate, if any, beside it), never a number beside
    // "determined": false. This run is too short for the grains' MSD.
    std::size_t undetermined = 0;
    const std::function<void(const tumble::io::Json&)> check = [&](const tumble::io::Json& o) {
        if (o.is_object() && o.contains("determined") && o.contains("D") && !o.at("determined").get<bool>()) {
            ++undetermined;
            EXPECT_TRUE(o.at("D").is_null()) << o.dump();
            EXPECT_TRUE(o.contains("D_best_estimate")) << o.dump();
        }
        if (o.is_object() || o.is_array())
            for (const auto& item : o) check(item);
    };
    check(j);
    EXPECT_GE(undetermined, 2u) << "the grains' MSD of both components is not determined";
    EXPECT_FALSE(j.at("components").at(0).at("msd").at("determined").get<bool>());
    const std::string text = read_file(run / "summary.txt");
    EXPECT_NE(text.find("surface energy W = 0.1 J/m^2"), std::string::npos);
    // The summary leads with one D per component (the grains' axial MSD, or
    // why there is none), before the set-up; every estimator then has its
    // line for each of the two components under a heading, a value or why
    // there is none.
    const std::size_t headline = text.find("  D, how fast each component's grains spread along the axis");
    const std::size_t setup = text.find("  shear model");
    const std::size_t details = text.find("\nother estimators and measurements:\n");
    ASSERT_NE(headline, std::string::npos) << text;
    ASSERT_NE(details, std::string::npos) << text;
    EXPECT_LT(headline, setup) << text;
    EXPECT_LT(setup, details) << text;
    for (const char* component : {"\n    material-1: D ", "\n    material-2: D "}) {
        const std::size_t at = text.find(component);
        EXPECT_TRUE(at > headline && at < setup) << component << "\n" << text;
    }
    for (const char* estimator : {"grains' axial MSD", "Hogg, amplitude free", "old estimator"}) {
        std::size_t lines = 0;
        for (auto at = text.find(estimator); at != std::string::npos; at = text.find(estimator, at + 1))
            lines += at > details;
        EXPECT_EQ(lines, 2u) << estimator << "\n" << text;
    }

    fs::remove(run / "summary.json");
    const Result again = run_tumble("analyze " + run.string());
    ASSERT_EQ(again.exit_code, 0) << again.output;
    EXPECT_NE(again.output.find("material-2"), std::string::npos) << again.output;
    EXPECT_TRUE(fs::exists(run / "summary.json"));
    EXPECT_NE(run_tumble("analyze " + (dir_ / "nothing").string()).exit_code, 0);
    // A first revolution that is no number was taken, and every fit then
    // had no sample without saying why.
    const Result nan = run_tumble("analyze " + run.string() + " --first-revolution nan");
    EXPECT_NE(nan.exit_code, 0);
    EXPECT_NE(nan.output.find("--first-revolution: must be a finite number >= 0, got nan"), std::string::npos)
        << nan.output;
}

// tumble analyze and tumble plot take a drum run; given a scenario's run
// (tumble run: run.json, no drum_run.toml) they say so and what reads its
// files, instead of naming a missing drum_run.toml.
TEST_F(Cli, AnalyzeAndPlotOfAScenarioRunSayWhatTheyTake) {
    const fs::path scenario = write("small.toml", small_scenario);
    const fs::path run = dir_ / "scenario-run";
    ASSERT_EQ(run_tumble("run -q " + scenario.string() + " --out " + run.string()).exit_code, 0);
    for (const char* command : {"analyze ", "plot ", "analyze --so-far ", "plot --compare "}) {
        const Result r = run_tumble(command + run.string());
        EXPECT_EQ(r.exit_code, 2) << command << r.output;
        EXPECT_EQ(r.output.find("missing file"), std::string::npos) << command << r.output;
        EXPECT_NE(r.output.find(run.string() + " is a run of a scenario (" + TUMBLE_BINARY + " run: it has run.json)"),
                  std::string::npos)
            << command << r.output;
        EXPECT_NE(r.output.find("takes the directory of a " + std::string(TUMBLE_BINARY) + " drum run"),
                  std::string::npos)
            << command << r.output;
        EXPECT_NE(r.output.find(std::string(TUMBLE_BINARY) + " render " + run.string()), std::string::npos)
            << command << r.output;
    }
    const Result none = run_tumble("plot " + (dir_ / "nowhere").string());
    EXPECT_EQ(none.exit_code, 2) << none.output;
    EXPECT_NE(none.output.find("nowhere: no such directory"), std::string::npos) << none.output;
}

// The commands that messages suggest name the program as it was invoked:
// ./tumble from the build directory, build/tumble from the source tree.
TEST_F(Cli, HintsNameTheProgramAsInvoked) {
    const fs::path binary(TUMBLE_BINARY);
    const fs::path out = dir_ / "stopped";
    const Result r = tumble::test_support::run_command(
        "cd " + binary.parent_path().string() + " && ./" + binary.filename().string() +
        " drum -q --mode self --grains 4 --length 0.02 --diameter 0.02 --revolutions 0.1 --no-plot --out " +
        out.string() + " --stop-at-step 50");
    ASSERT_EQ(r.exit_code, 4) << r.output;
    EXPECT_NE(r.output.find("Continue with: ./" + binary.filename().string() + " resume " + out.string()),
              std::string::npos)
        << r.output;
    const Result analyze = tumble::test_support::run_command("cd " + binary.parent_path().string() + " && ./" +
                                                             binary.filename().string() + " analyze " + out.string());
    EXPECT_EQ(analyze.exit_code, 2) << analyze.output;
    EXPECT_NE(analyze.output.find("finish it with ./" + binary.filename().string() + " resume " + out.string()),
              std::string::npos)
        << analyze.output;
}

// README's example of --max-memory is true on any machine: the run it shows
// is refused before any work, with the estimate and the limit, whatever the
// machine's memory (the limit is given, not the default).
TEST_F(Cli, ReadmeMaxMemoryExampleIsRefused) {
    // (./README.md: scripts/check_doc_refs.py would read the quoted regex after the name as a section.)
    const std::string readme = read_file(fs::path(TUMBLE_SOURCE_DIR) / "./README.md");
    std::smatch line;
    ASSERT_TRUE(std::regex_search(readme, line, std::regex("build/tumble (drum [^\\n#]*--max-memory [^\\n#]*?)\\s*#")))
        << "README.md has no example of --max-memory";
    const fs::path out = dir_ / "refused";
    const Result r = run_tumble(line[1].str() + " --out " + out.string());
    EXPECT_EQ(r.exit_code, 2) << line[1] << "\n" << r.output;
    EXPECT_NE(r.output.find("--max-memory"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out)) << "nothing is written";
}
