// SPDX-License-Identifier: MIT
// tumble sweep (docs/SWEEP.md): the sweep file, the points and their
// directories, resume states, the MPI split, the child-process runner, the
// JSON reader and the aggregation into sweep.csv / sweep_summary.csv. The
// last test runs the real command end to end.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include "test_support.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>

#include "io/config.hpp"
#include "io/drum_output.hpp"
#include "io/json.hpp"
#include "io/sweep.hpp"
#include "tumble/analysis/hogg.hpp"
#include "tumble/core/mpi.hpp"
#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"

namespace fs = std::filesystem;
using namespace tumble;
using namespace tumble::io;

namespace {

std::string slurp(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<std::vector<std::string>> read_csv(const fs::path& file) {
    std::vector<std::vector<std::string>> rows;
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
        std::vector<std::string> row;
        std::string cellv;
        std::stringstream ss(line);
        while (std::getline(ss, cellv, ',')) row.push_back(cellv);
        if (!line.empty() && line.back() == ',') row.emplace_back();
        rows.push_back(row);
    }
    return rows;
}

// Row as column name -> value.
std::map<std::string, std::string> row_map(const std::vector<std::vector<std::string>>& rows, std::size_t r) {
    std::map<std::string, std::string> out;
    EXPECT_EQ(rows[0].size(), rows[r].size()) << "row " << r;
    for (std::size_t c = 0; c < rows[0].size() && c < rows[r].size(); ++c) out[rows[0][c]] = rows[r][c];
    return out;
}

class Sweep : public tumble::test_support::ScratchTest {
protected:
    // Loads a sweep file expected to be refused; returns "KEY: REASON".
    std::string refusal(const std::string& text) {
        const fs::path f = write("bad.toml", text);
        try {
            load_sweep_settings(f);
        } catch (const ConfigError& e) {
            EXPECT_EQ(e.file(), f);
            return e.key() + ": " + e.reason();
        }
        ADD_FAILURE() << "accepted:\n" << text;
        return {};
    }
};

// ------------------------------------------------------------ sweep file

TEST_F(Sweep, FileWithEveryKey) {
    const SweepSettings s = load_sweep_settings(write("s.toml", R"(
[sweep]
rpm = [30, 60]
modes = ["two-component"]
seeds = [4, 5, 6]
revolutions = 2.5
grains_two_component = 300
grains_self = 100
samples_per_revolution = 10
snapshots_per_revolution = 1
periodic_axis = true
walls = "smooth"
[output]
directory = "there"
)"));
    EXPECT_EQ(s.speed_unit, SpeedUnit::rpm);
    EXPECT_EQ(s.speeds, (std::vector<double>{30, 60}));
    EXPECT_EQ(s.modes, (std::vector<std::string>{"two-component"}));
    EXPECT_EQ(s.seeds, (std::vector<std::uint64_t>{4, 5, 6}));
    EXPECT_EQ(s.revolutions, 2.5);
    EXPECT_EQ(s.grains_two_component, 300u);
    EXPECT_EQ(s.grains_self, 100u);
    EXPECT_EQ(s.samples_per_revolution, 10);
    EXPECT_EQ(s.snapshots_per_revolution, 1);
    EXPECT_TRUE(s.periodic_axis);
    EXPECT_EQ(s.output, fs::path("there"));
    EXPECT_EQ(s.walls, "smooth");
    // Each point's drum runs without end caps, walled smooth.
    const std::vector<std::string> args = drum_arguments(expand_sweep(s, "d")[0]);
    ASSERT_GE(args.size(), 3u);
    EXPECT_EQ(args[args.size() - 3], "--periodic-axis");
    EXPECT_EQ(args[args.size() - 2], "--walls");
    EXPECT_EQ(args.back(), "smooth");
    // A wall kind that tumble drum does not know is refused, naming the key.
    try {
        load_sweep_settings(write("bad.toml", "[sweep]\nomega = [5]\nwalls = \"glass\"\n"));
        ADD_FAILURE() << "a bad sweep.walls was read";
    } catch (const ConfigError& e) {
        EXPECT_EQ(e.key(), "sweep.walls");
    }
}

TEST_F(Sweep, DefaultsAndExamples) {
    const SweepSettings s = load_sweep_settings(write("s.toml", "[sweep]\nomega = [5]\n"));
    EXPECT_EQ(s.modes, (std::vector<std::string>{"self", "two-component"}));
    EXPECT_EQ(s.seeds, (std::vector<std::uint64_t>{1}));
    EXPECT_EQ(s.grains_self, 458u);
    EXPECT_EQ(s.grains_two_component, 1000u);
    EXPECT_EQ(s.snapshots_per_revolution, 8);  // the grains' axial MSD needs them
    const SweepSettings paper = load_sweep_settings(fs::path(TUMBLE_SOURCE_DIR) / "examples/sweep_paper.toml");
    EXPECT_EQ(expand_sweep(paper, "d").size(), 24u);
    const SweepSettings tiny = load_sweep_settings(fs::path(TUMBLE_SOURCE_DIR) / "examples/sweep_tiny.toml");
    EXPECT_EQ(expand_sweep(tiny, "d").size(), 4u);
}

TEST_F(Sweep, FileErrorsNameKeyAndReason) {
    EXPECT_NE(refusal("[output]\ndirectory = \"x\"\n").find("sweep: missing required key"), std::string::npos);
    EXPECT_NE(refusal("[sweep]\nseeds = [1]\n").find("sweep: missing the speeds"), std::string::npos);
    EXPECT_NE(refusal("[sweep]\nomega = [1]\nrpm = [2]\n").find("sweep: give the speeds once"), std::string::npos);
    EXPECT_NE(refusal("[sweep]\nomega = []\n").find("sweep.omega: must not be empty"), std::string::npos);
    EXPECT_NE(refusal("[sweep]\nomega = 5.0\n").find("sweep.omega: expected an array of numbers"), std::string::npos);
    EXPECT_NE(refusal("[sweep]\nomega = [5, -1]\n").find("sweep.omega[1]: must be > 0"), std::string::npos);
    EXPECT_NE(refusal("[sweep]\nomega = [5, \"x\"]\n").find("sweep.omega[1]: expected a number"), std::string::npos);
    EXPECT_NE(refusal("[sweep]\nomega = [5, 5.0]\n").find("sweep.omega[1]: the value 5 is given twice"),
              std::string::npos);
    EXPECT_NE(refusal("[sweep]\nomega = [5]\nmodes = [\"both\"]\n").find("sweep.modes[0]: must be \"self\""),
              std::string::npos);
    EXPECT_NE(refusal("[sweep]\nomega = [5]\nmodes = [\"self\", \"self\"]\n").find("sweep.modes[1]: the mode"),
              std::string::npos);
    EXPECT_NE(refusal("[sweep]\nomega = [5]\nseeds = [1, 1]\n").find("sweep.seeds[1]: the seed 1 is given twice"),
              std::string::npos);
    EXPECT_NE(refusal("[sweep]\nomega = [5]\nseeds = [-1]\n").find("sweep.seeds[0]: must lie in"), std::string::npos);
    EXPECT_NE(refusal("[sweep]\nomega = [5]\nrevolutions = 0\n").find("sweep.revolutions: must be > 0"),
              std::string::npos);
    EXPECT_NE(refusal("[sweep]\nomega = [5]\ngrains_self = 1\n").find("sweep.grains_self: must lie in [2,"),
              std::string::npos);
    EXPECT_NE(refusal("[sweep]\nomega = [5]\nseed = [1]\n").find("sweep.seed: unknown key (did you mean \"seeds\"?)"),
              std::string::npos);
    EXPECT_NE(refusal("[sweep]\nomega = [5]\n[drum]\n").find("drum: unknown key"), std::string::npos);
    EXPECT_NE(refusal("[sweep]\nomega = [5]\ndiameter = 0.1\n").find("sweep.diameter: only used"),
              std::string::npos);
    EXPECT_NE(refusal("[sweep]\nomega = [5]\n[output]\ndirectory = 3\n").find("output.directory: expected a string"),
              std::string::npos);
    EXPECT_NE(refusal("[sweep]\nomega = [5\n").find("line"), std::string::npos);  // syntax error: ConfigError too
}

// ------------------------------------------------------------ points

TEST(SweepPoints, NamesAndOrder) {
    EXPECT_EQ(sweep_point_name("two-component", 5.0, 1), "two-component_omega5.000_seed1");
    EXPECT_EQ(sweep_point_name("self", 2.0 * pi, 12), "self_omega6.283_seed12");
    SweepSettings s;
    s.speeds = {5.0, 2.0, 8.0};
    s.modes = {"two-component", "self"};
    s.seeds = {3, 1};
    s.grains_self = 100;
    s.grains_two_component = 200;
    const auto points = expand_sweep(s, "out");
    ASSERT_EQ(points.size(), 12u);
    std::vector<std::string> names;
    for (const auto& p : points) names.push_back(p.name);
    EXPECT_EQ(names[0], "two-component_omega5.000_seed3");
    EXPECT_EQ(names[1], "two-component_omega5.000_seed1");
    EXPECT_EQ(names[2], "two-component_omega2.000_seed3");
    EXPECT_EQ(names[6], "self_omega5.000_seed3");
    EXPECT_EQ(names[11], "self_omega8.000_seed1");
    for (std::size_t i = 0; i < points.size(); ++i) {
        EXPECT_EQ(points[i].index, i);
        EXPECT_EQ(points[i].directory, fs::path("out") / "points" / points[i].name);
        EXPECT_EQ(points[i].grains, points[i].mode == "self" ? 100u : 200u);
        EXPECT_NEAR(points[i].froude, points[i].omega * points[i].omega * 0.04 / 9.81, 1e-15);
    }
    const auto args = drum_arguments(points[1]);
    const std::vector<std::string> expected{"drum",  "-q",         "--mode",    "two-component", "--omega", "5",
                                            "--seed", "1",         "--revolutions", "5",         "--grains", "200",
                                            "--samples", "20",     "--snapshots", "8",           "--shear",
                                            "paper", "--friction-normal", "net", "--tangential-stiffness", "paper",
                                            "--out",
                                            (fs::path("out") / "points" / "two-component_omega5.000_seed1").string(),
                                            "--force", "--threads", "1"};
    EXPECT_EQ(args, expected);
}

TEST(SweepPoints, SpeedUnitsAndCollisions) {
    SweepSettings s;
    s.modes = {"self"};
    s.speeds = {60.0};
    s.speed_unit = SpeedUnit::rpm;
    EXPECT_NEAR(expand_sweep(s, "d")[0].omega, 2.0 * pi, 1e-12);
    s.speed_unit = SpeedUnit::froude;
    s.speeds = {1.0};
    EXPECT_NEAR(expand_sweep(s, "d")[0].omega, std::sqrt(9.81 / 0.04), 1e-12);
    EXPECT_NEAR(expand_sweep(s, "d")[0].froude, 1.0, 1e-12);
    // omega given exactly to the child, even where the name rounds.
    s.speed_unit = SpeedUnit::rad_per_s;
    s.speeds = {1.23456789};
    EXPECT_EQ(drum_arguments(expand_sweep(s, "d")[0])[5], "1.23456789");
    s.speeds = {5.0001, 5.0002};
    EXPECT_THROW(expand_sweep(s, "d"), Error);
}

// ------------------------------------------------------------ resume

TEST_F(Sweep, PointStates) {
    EXPECT_EQ(point_state(dir_ / "a"), PointState::pending);
    fs::create_directories(dir_ / "b");
    write("b/drum_series.csv", "x\n");
    EXPECT_EQ(point_state(dir_ / "b"), PointState::unfinished);
    write_failure_marker(dir_ / "c", 3);
    EXPECT_EQ(point_state(dir_ / "c"), PointState::failed);
    write("d/summary.json", "{}");
    EXPECT_EQ(point_state(dir_ / "d"), PointState::finished);
    write("c/summary.json", "{}");  // a later success wins over an old marker
    EXPECT_EQ(point_state(dir_ / "c"), PointState::finished);
}

// ------------------------------------------------------------ MPI

// Whether a launcher started the process, from its variables; a child of
// a rank does not inherit them.
TEST(SweepMpi, LauncherFromEnvironment) {
    auto env = [](std::map<std::string, std::string> m) {
        return [m](const char* name) -> const char* {
            auto it = m.find(name);
            return it == m.end() ? nullptr : it->second.c_str();
        };
    };
    EXPECT_FALSE(mpi::launched_by_mpi(env({})));
    EXPECT_FALSE(mpi::launched_by_mpi(env({{"SLURM_JOB_ID", "7"}})));  // a batch job, not a launcher
    EXPECT_TRUE(mpi::launched_by_mpi(env({{"OMPI_COMM_WORLD_SIZE", "4"}})));
    EXPECT_TRUE(mpi::launched_by_mpi(env({{"PMIX_RANK", "0"}})));
    EXPECT_TRUE(mpi::launched_by_mpi(env({{"PMI_RANK", "1"}, {"PMI_SIZE", "3"}})));
    for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_NAMESPACE", "PMI_FD", "MPI_LOCALNRANKS"})
        EXPECT_TRUE(mpi::is_launcher_variable(name)) << name;
    for (const char* name : {"PATH", "OMP_NUM_THREADS", "SLURM_JOB_ID", "TUMBLE_ISA"})
        EXPECT_FALSE(mpi::is_launcher_variable(name)) << name;
    // Without a launcher the world is one rank.
    EXPECT_EQ(mpi::rank(), 0);
    EXPECT_EQ(mpi::size(), 1);
    EXPECT_EQ(mpi::line_prefix(), "");
}

TEST_F(Sweep, ChildrenDoNotInheritTheLaunchersVariables) {
    ::setenv("OMPI_COMM_WORLD_SIZE", "2", 1);
    ::setenv("TUMBLE_TEST_KEPT", "yes", 1);
    const fs::path log = dir_ / "env.txt";
    int status = 0;
    ::waitpid(spawn_process({"/usr/bin/env"}, log), &status, 0);
    ::unsetenv("OMPI_COMM_WORLD_SIZE");
    ::unsetenv("TUMBLE_TEST_KEPT");
    const std::string seen = slurp(log);
    EXPECT_EQ(seen.find("OMPI_COMM_WORLD_SIZE"), std::string::npos) << seen;
    EXPECT_NE(seen.find("TUMBLE_TEST_KEPT=yes"), std::string::npos) << seen;
}

// ------------------------------------------------------------ child processes

TEST_F(Sweep, RunnerReportsExitCodesAndCapturesOutput) {
    std::vector<PointJob> jobs{
        {0, {"/bin/sh", "-c", "echo out; echo err >&2; exit 0"}, dir_ / "p0" / "log.txt"},
        {1, {"/bin/sh", "-c", "echo broken >&2; exit 3"}, dir_ / "p1" / "log.txt"},
        {2, {"/bin/sh", "-c", "kill -9 $$"}, dir_ / "p2" / "log.txt"},
        {3, {"/nonexistent/tumble", "drum"}, dir_ / "p3" / "log.txt"},
    };
    std::vector<std::size_t> started;
    std::map<std::size_t, int> codes;
    const auto outcomes = run_jobs(
        jobs, 2, [&](const PointJob& j) { started.push_back(j.point); },
        [&](const PointJob& j, const PointOutcome& o) {
            EXPECT_EQ(j.point, o.point);
            codes[o.point] = o.exit_code;
        });
    EXPECT_EQ(started, (std::vector<std::size_t>{0, 1, 2, 3}));
    EXPECT_EQ(outcomes.size(), 4u);
    EXPECT_EQ(codes[0], 0);
    EXPECT_EQ(codes[1], 3);
    EXPECT_EQ(codes[2], 128 + 9);
    EXPECT_EQ(codes[3], 127);
    const std::string log0 = slurp(dir_ / "p0" / "log.txt");
    EXPECT_NE(log0.find("# tumble sweep: /bin/sh -c"), std::string::npos);
    EXPECT_NE(log0.find("out\n"), std::string::npos);
    EXPECT_NE(log0.find("err\n"), std::string::npos);
    EXPECT_NE(slurp(dir_ / "p1" / "log.txt").find("broken"), std::string::npos);
    EXPECT_NE(slurp(dir_ / "p3" / "log.txt").find("cannot start"), std::string::npos);
}

TEST_F(Sweep, RunnerKeepsTheLimitOfParallelJobs) {
    // Each job appends "+" when it starts and "-" when it ends to a shared
    // file; the running count never exceeds the limit.
    const fs::path trace = dir_ / "trace";
    std::vector<PointJob> jobs;
    for (std::size_t i = 0; i < 6; ++i)
        jobs.push_back({i, {"/bin/sh", "-c", "echo + >> \"$0\"; sleep 0.2; echo - >> \"$0\"", trace.string()},
                        dir_ / std::string("p").append(std::to_string(i)) / "log.txt"});
    const auto t0 = std::chrono::steady_clock::now();
    run_jobs(jobs, 3, nullptr, nullptr);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    int running = 0, most = 0;
    std::ifstream in(trace);
    std::string line;
    int lines = 0;
    while (std::getline(in, line)) {
        running += line == "+" ? 1 : -1;
        most = std::max(most, running);
        ++lines;
    }
    EXPECT_EQ(lines, 12);
    EXPECT_LE(most, 3);
    EXPECT_GE(most, 2);      // they did run side by side
    EXPECT_GE(seconds, 0.39);  // two waves of 0.2 s
}

// ------------------------------------------------------------ JSON

TEST(SweepJson, ParsesWhatSummaryJsonHolds) {
    const Json j = parse_json(R"( {"a": 1, "b": -2.5e-3, "c": [true, false, null, 0, 1E+2, -0.0],
        "d": {"e": "x\"y\\z\/\n\t\u00e9\ud83d\ude00"}, "empty": {}, "none": [] } )");
    ASSERT_TRUE(j.is_object());
    EXPECT_EQ(json_number(j, "a"), 1.0);
    EXPECT_EQ(json_number(j, "b"), -2.5e-3);
    const Json& c = j.at("c");
    ASSERT_EQ(c.size(), 6u);
    EXPECT_TRUE(c[0].get<bool>());
    EXPECT_FALSE(c[1].get<bool>());
    EXPECT_TRUE(c[2].is_null());
    EXPECT_EQ(c[4].get<double>(), 100.0);
    // Every escape, and a surrogate pair, decoded to UTF-8.
    EXPECT_EQ(j.at("d").at("e").get<std::string>(), "x\"y\\z/\n\t\xc3\xa9\xf0\x9f\x98\x80");
    EXPECT_TRUE(j.at("empty").is_object());
    EXPECT_TRUE(j.at("none").empty());
    EXPECT_EQ(json_number(j, "missing"), std::nullopt);
    EXPECT_THROW(json_number(j, "d"), Error);  // an object, not a number
    EXPECT_EQ(json_number(parse_json("{\"x\": null}"), "x"), std::nullopt);  // null: undefined
}

TEST(SweepJson, RefusesMalformedText) {
    for (const char* bad : {"", "{", "{\"a\" 1}", "{\"a\": 1,}", "[1,]", "[1 2]", "01", "1.", ".5", "1e", "-",
                            "NaN", "Infinity", "nul", "tru", "\"abc", "\"a\nb\"", "\"\\x\"", "\"\\u12\"",
                            "\"\\ud800\"", "\"\\udc00\"", "{a: 1}", "{} {}", "1e999", "'a'"}) {
        EXPECT_THROW(parse_json(bad, "t.json"), Error) << bad;
    }
    try {
        parse_json("{\n  \"a\": 1,\n  \"b\": ?\n}", "s.json");
        FAIL();
    } catch (const Error& e) {
        // The name of the text and where in it: line 3, column 8 is the '?'.
        EXPECT_NE(std::string(e.what()).find("s.json: parse error at line 3, column 8"), std::string::npos) << e.what();
    }
}

// ------------------------------------------------------------ aggregation

std::string summary_json(const std::string& mode, double d1, double d2, bool det2, double ke, double speed) {
    const auto names = components_of_mode(mode);
    std::string text = "{\n  \"mode\": \"" + mode + "\",\n  \"components\": [\n";
    text += "    {\"name\": \"" + names[0] + "\", \"D\": " + std::to_string(d1) +
            ", \"D_stderr\": 1e-6, \"D_one_term\": 2e-5, \"determined\": true, \"note\": \"\", \"msd\": {\"D\": " +
            std::to_string(d1) + ", \"D_lo\": " + std::to_string(0.9 * d1) + ", \"D_hi\": " + std::to_string(1.1 * d1) +
            ", \"determined\": true}, \"hogg_free\": {\"D\": 1e-5, \"D_lo\": null, \"D_hi\": null, \"determined\": false}},\n";
    text += "    {\"name\": \"" + names[1] + "\", \"D\": " + std::to_string(d2) +
            ", \"D_stderr\": null, \"D_one_term\": 3e-5, \"determined\": " + (det2 ? "true" : "false") +
            ", \"note\": \"too short\"}\n  ],\n";
    if (mode == "two-component")
        text += "  \"kinetic_energy_ratio_total\": " + std::to_string(ke) +
                ",\n  \"kinetic_energy_ratio_total_equal_velocity\": 1,\n  \"kinetic_energy_ratio_per_grain\": 0.45,\n"
                "  \"kinetic_energy_ratio_per_grain_equal_velocity\": 0.296,\n";
    text += "  \"depth_mobility\": [{\"name\": \"" + names[0] + "\", \"surface_share\": 0.9, \"surface_occupancy\": 0.5}],\n";
    text += "  \"angle_of_repose\": 38.5,\n";
    text += "  \"grain_updates_per_second\": " + std::to_string(speed) + "\n}\n";
    return text;
}

TEST_F(Sweep, AggregatesPointsIntoTables) {
    SweepSettings s;
    s.speeds = {3.0, 5.0};
    s.modes = {"two-component", "self"};
    s.seeds = {1, 2, 3};
    const auto points = expand_sweep(s, dir_);
    ASSERT_EQ(points.size(), 12u);
    // two-component omega 3: three seeds finished; seed 3's material-2 not determined.
    write("points/two-component_omega3.000_seed1/summary.json", summary_json("two-component", 1e-5, 2e-5, true, 1.0, 1e6));
    write("points/two-component_omega3.000_seed2/summary.json", summary_json("two-component", 3e-5, 4e-5, true, 2.0, 2e6));
    write("points/two-component_omega3.000_seed3/summary.json", summary_json("two-component", 5e-5, 9e-5, false, 3.0, 3e6));
    // two-component omega 5: seed 1 finished, seed 2 failed, seed 3 unfinished.
    write("points/two-component_omega5.000_seed1/summary.json", summary_json("two-component", 7e-5, 8e-5, true, 1.5, 1e6));
    write_failure_marker(dir_ / "points/two-component_omega5.000_seed2", 2);
    fs::create_directories(dir_ / "points/two-component_omega5.000_seed3");
    // self omega 3: one finished, one with a broken summary.json; omega 5: none.
    write("points/self_omega3.000_seed1/summary.json", summary_json("self", 4e-5, 6e-5, true, 0, 5e5));
    write("points/self_omega3.000_seed2/summary.json", "{\"components\": [");

    std::vector<PointResult> results;
    for (const auto& p : points) results.push_back(read_point_result(p));
    EXPECT_EQ(results[4].state, PointState::failed);
    EXPECT_NE(results[4].note.find("exit code 2"), std::string::npos);
    EXPECT_NE(results[4].note.find("log.txt"), std::string::npos);
    EXPECT_NE(results[7].note.find("unreadable summary.json"), std::string::npos);
    const std::size_t missing = write_sweep_tables(dir_, results);
    EXPECT_EQ(missing, 12u - 5u);

    const auto rows = read_csv(dir_ / "sweep.csv");
    ASSERT_EQ(rows.size(), 13u);
    const std::string header =
        "mode,shear_model,friction_normal,tangential_stiffness,ends,walls,omega,froude,seed,revolutions,grains,"
        "D_material_1,D_stderr_material_1,D_one_term_material_1,determined_material_1,surface_share_material_1,"
        "D_msd_material_1,D_msd_lo_material_1,D_msd_hi_material_1,D_hogg_free_material_1,D_hogg_free_lo_material_1,D_hogg_free_hi_material_1,"
        "D_material_2,D_stderr_material_2,D_one_term_material_2,determined_material_2,surface_share_material_2,"
        "D_msd_material_2,D_msd_lo_material_2,D_msd_hi_material_2,D_hogg_free_material_2,D_hogg_free_lo_material_2,D_hogg_free_hi_material_2,"
        "D_left,D_stderr_left,D_one_term_left,determined_left,surface_share_left,"
        "D_msd_left,D_msd_lo_left,D_msd_hi_left,D_hogg_free_left,D_hogg_free_lo_left,D_hogg_free_hi_left,"
        "D_right,D_stderr_right,D_one_term_right,determined_right,surface_share_right,"
        "D_msd_right,D_msd_lo_right,D_msd_hi_right,D_hogg_free_right,D_hogg_free_lo_right,D_hogg_free_hi_right,"
        "ke_ratio_total,ke_ratio_total_ref,ke_ratio_per_grain,ke_ratio_per_grain_ref,angle_of_repose,"
        "grain_updates_per_second,status";
    EXPECT_EQ(slurp(dir_ / "sweep.csv").substr(0, header.size() + 1), header + "\n");
    auto r1 = row_map(rows, 1);
    EXPECT_EQ(r1["mode"], "two-component");
    EXPECT_EQ(r1["omega"], "3");
    EXPECT_EQ(r1["seed"], "1");
    EXPECT_EQ(r1["grains"], "1000");
    EXPECT_EQ(r1["D_material_1"], "1e-05");
    EXPECT_EQ(r1["D_stderr_material_2"], "");  // null
    EXPECT_EQ(r1["D_one_term_material_2"], "3e-05");
    EXPECT_EQ(r1["determined_material_2"], "true");
    EXPECT_EQ(r1["D_left"], "");
    EXPECT_EQ(r1["ke_ratio_total"], "1");
    EXPECT_EQ(r1["ke_ratio_per_grain_ref"], "0.296");
    EXPECT_EQ(r1["surface_share_material_1"], "0.9");
    EXPECT_EQ(r1["surface_share_material_2"], "");  // absent from depth_mobility
    EXPECT_EQ(r1["D_msd_material_1"], "1e-05");
    EXPECT_EQ(r1["D_msd_lo_material_1"], "9e-06");
    EXPECT_EQ(r1["D_hogg_free_material_1"], "");  // not determined
    EXPECT_EQ(r1["D_msd_material_2"], "");         // absent
    EXPECT_EQ(r1["angle_of_repose"], "38.5");
    EXPECT_EQ(r1["grain_updates_per_second"], "1000000");
    EXPECT_EQ(r1["status"], "finished");
    EXPECT_EQ(row_map(rows, 3)["determined_material_2"], "false");
    EXPECT_EQ(row_map(rows, 5)["status"], "failed");
    EXPECT_EQ(row_map(rows, 5)["D_material_1"], "");
    EXPECT_EQ(row_map(rows, 6)["status"], "unfinished");
    auto r7 = row_map(rows, 7);
    EXPECT_EQ(r7["mode"], "self");
    EXPECT_EQ(r7["grains"], "458");
    EXPECT_EQ(r7["D_left"], "4e-05");
    EXPECT_EQ(r7["D_material_1"], "");
    EXPECT_EQ(r7["ke_ratio_total"], "");
    EXPECT_EQ(row_map(rows, 8)["status"], "finished");  // on disk, but without numbers
    EXPECT_EQ(row_map(rows, 8)["D_left"], "");
    EXPECT_EQ(row_map(rows, 12)["status"], "pending");

    const auto sum = read_csv(dir_ / "sweep_summary.csv");
    ASSERT_EQ(sum.size(), 5u);
    auto s1 = row_map(sum, 1);
    EXPECT_EQ(s1["mode"], "two-component");
    EXPECT_EQ(s1["omega"], "3");
    EXPECT_EQ(s1["seeds"], "3");
    EXPECT_EQ(s1["finished"], "3");
    EXPECT_NEAR(std::stod(s1["D_material_1_mean"]), 3e-5, 1e-18);
    EXPECT_NEAR(std::stod(s1["D_material_1_std"]), 2e-5, 1e-18);
    EXPECT_EQ(s1["D_material_1_n"], "3");
    // Three seeds (1, 3, 5 e-5): Student's t interval of the mean over the
    // seeds, 3e-5 +- t(0.95, 2) 2e-5 / sqrt(3), t = 4.303 from the table
    // (the expansion's 0.8 % of it as the tolerance).
    const double half = 4.303 * 2e-5 / std::sqrt(3.0);
    EXPECT_NEAR(std::stod(s1["D_msd_material_1_lo"]), 3e-5 - half, 0.008 * half);
    EXPECT_NEAR(std::stod(s1["D_msd_material_1_hi"]), 3e-5 + half, 0.008 * half);
    EXPECT_NEAR(std::stod(s1["D_material_2_mean"]), 3e-5, 1e-18);  // the undetermined seed left out
    EXPECT_EQ(s1["D_material_2_n"], "2");
    EXPECT_NEAR(std::stod(s1["ke_ratio_total_mean"]), 2.0, 1e-12);
    EXPECT_NEAR(std::stod(s1["ke_ratio_total_std"]), 1.0, 1e-12);
    EXPECT_EQ(s1["D_left_n"], "0");
    EXPECT_EQ(s1["D_left_mean"], "");
    EXPECT_NEAR(std::stod(s1["angle_of_repose_mean"]), 38.5, 1e-12);
    EXPECT_NEAR(std::stod(s1["surface_share_material_1_mean"]), 0.9, 1e-12);
    auto s2 = row_map(sum, 2);
    EXPECT_EQ(s2["omega"], "5");
    EXPECT_EQ(s2["finished"], "1");
    EXPECT_EQ(s2["D_material_1_mean"], "7e-05");
    EXPECT_EQ(s2["D_material_1_std"], "");  // one seed: no spread
    EXPECT_EQ(s2["D_msd_material_1_lo"], "");  // one seed: no interval
    EXPECT_EQ(s2["D_material_1_n"], "1");
    EXPECT_EQ(row_map(sum, 3)["mode"], "self");
    EXPECT_EQ(row_map(sum, 3)["finished"], "1");
    EXPECT_EQ(row_map(sum, 4)["finished"], "0");
}

// The summary.json that tumble analyze writes, read back by the sweep: a
// synthetic run directory (Hogg-decaying <z>) analysed by analyze_drum_run.
TEST_F(Sweep, ReadsTheSummaryJsonOfARealAnalysis) {
    SweepSettings s;
    s.speeds = {5.0};
    s.modes = {"two-component"};
    const SweepPoint p = expand_sweep(s, dir_)[0];
    fs::create_directories(p.directory);
    DrumRunInfo info;
    info.mode = "two-component";
    info.omega = 5.0;
    info.froude = 25 * 0.04 / 9.81;
    info.revolutions = 10;
    info.seed = 1;
    info.inner_radius = 0.04;
    info.inner_length = 0.12;
    info.dt = 1e-5;
    info.samples_per_revolution = 10;
    info.profile_bins = 4;
    info.grain_updates_per_second = 4.5e6;
    info.components = {{"material-1", 229, 0.5, -1.0}, {"material-2", 771, 0.5, +1.0}};
    write_drum_run_info(p.directory / "drum_run.toml", info);
    {
        DrumSeriesWriter w(p.directory, info);
        const double D[2] = {3e-5, 2e-5};
        for (int k = 0; k <= 100; ++k) {
            const double N = 0.1 * k;
            analysis::DrumState st;
            st.angle_of_repose = N < 1.0 ? 60.0 : 30.0;  // the first revolution (spin-up) is left out of the mean
            for (int c = 0; c < 2; ++c) {
                analysis::ComponentState cs;
                cs.grains = info.components[c].grains;
                cs.mass = 0.5;
                cs.mean_z = info.components[c].start_side * analysis::hogg_mean_position(D[c], N, 0.12) +
                            1e-5 * std::sin(17.0 * k + c);
                cs.mean_z_stderr = 1e-4;
                cs.kinetic_energy = c == 0 ? 1e-4 : 1.5e-4;
                cs.kinetic_per_grain = cs.kinetic_energy / static_cast<double>(cs.grains);
                cs.concentration = {0.1, 0.2, 0.3, 0.4};
                st.components.push_back(cs);
            }
            w.write(N, N * 2 * pi / 5.0, st);
        }
    }
    analyze_drum_run(p.directory);
    const PointResult r = read_point_result(p);
    ASSERT_EQ(r.state, PointState::finished);
    ASSERT_EQ(r.note, "");
    ASSERT_EQ(r.components.size(), 2u);
    EXPECT_TRUE(r.components.at("material-1").determined);
    EXPECT_NEAR(r.components.at("material-1").D, 3e-5, 3e-6);
    EXPECT_NEAR(r.components.at("material-2").D, 2e-5, 2e-6);
    EXPECT_TRUE(std::isfinite(r.components.at("material-2").D_one_term));
    EXPECT_NEAR(r.ke_ratio_total, 1.5, 1e-9);
    EXPECT_NEAR(r.ke_ratio_total_ref, 1.0, 1e-12);
    EXPECT_NEAR(r.angle_of_repose, 30.0, 1e-12);
    EXPECT_NEAR(r.grain_updates_per_second, 4.5e6, 1.0);
}

// ------------------------------------------------------------ end to end

using Result = tumble::test_support::CommandResult;
const auto run = tumble::test_support::run_command;

// The tumble binary to test the sweep command with: TUMBLE_BINARY, or
// TUMBLE_SWEEP_TEST_BINARY from the environment (a build with the command).
std::string tumble_binary() {
    const char* b = std::getenv("TUMBLE_SWEEP_TEST_BINARY");
    return b && *b ? b : TUMBLE_BINARY;
}

// True if `bin sweep --help` prints the sweep command's usage (a binary
// without it prints the top-level help, also with exit code 0).
bool has_sweep_command(const std::string& bin) {
    const Result r = run(bin + " sweep --help");
    return r.exit_code == 0 && r.output.find("sweep [OPTIONS]") != std::string::npos;
}

// END TO END: `tumble sweep` on examples/sweep_tiny.toml (2 speeds x self x
// 2 seeds, 150 grains, 0.3 revolutions; about half a minute on 2 cores),
// then a resume that runs nothing, then one that reruns a removed point.
// Skipped while the binary has no sweep command.
TEST_F(Sweep, EndToEndTinySweep) {
    const std::string bin = tumble_binary();
    if (!has_sweep_command(bin))
        GTEST_SKIP() << bin << " has no `sweep` command yet (wire it into src/cli/main.cpp; docs/SWEEP.md)";
    const std::string file = std::string(TUMBLE_SOURCE_DIR) + "/examples/sweep_tiny.toml";
    const fs::path out = dir_ / "tiny";
    Result r = run(bin + " sweep " + file + " -o " + out.string() + " -j 2");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("ETA"), std::string::npos) << r.output;
    const auto rows = read_csv(out / "sweep.csv");
    ASSERT_EQ(rows.size(), 5u) << slurp(out / "sweep.csv");
    for (std::size_t i = 1; i < rows.size(); ++i) {
        auto m = row_map(rows, i);
        EXPECT_EQ(m["status"], "finished");
        EXPECT_EQ(m["mode"], "self");
        EXPECT_EQ(m["grains"], "150");
        EXPECT_NE(m["D_left"], "");
        EXPECT_NE(m["grain_updates_per_second"], "");
        EXPECT_TRUE(fs::exists(out / "points" / (sweep_point_name("self", std::stod(m["omega"]),
                                                                    std::stoull(m["seed"]))) / "log.txt"));
    }
    EXPECT_EQ(read_csv(out / "sweep_summary.csv").size(), 3u);
    const std::string first = slurp(out / "sweep.csv");

    r = run(bin + " sweep " + file + " -o " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("4 finished before, 0 to run"), std::string::npos) << r.output;
    EXPECT_EQ(slurp(out / "sweep.csv"), first);

    fs::remove(out / "points" / "self_omega5.000_seed2" / "summary.json");
    r = run(bin + " sweep " + file + " -o " + out.string() + " -j 1");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("3 finished before, 1 to run"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("self_omega5.000_seed2: unfinished before"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(out / "points" / "self_omega5.000_seed2" / "summary.json"));
    EXPECT_EQ(slurp(out / "sweep.csv").substr(0, 200), first.substr(0, 200));  // header and first row unchanged

    // A failing point (its lock file cannot be opened) is reported with its
    // log, the others are kept, the exit code is non-zero; once the cause is
    // gone, the next run redoes it.
    const fs::path broken = out / "points" / "self_omega3.000_seed1";
    fs::remove(broken / "summary.json");
    fs::remove(broken / ".tumble.lock");
    fs::create_directories(broken / ".tumble.lock");
    r = run(bin + " sweep " + file + " -o " + out.string());
    EXPECT_NE(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("FAILED self_omega3.000_seed1"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find((broken / "log.txt").string()), std::string::npos) << r.output;
    EXPECT_NE(slurp(broken / "log.txt").find("cannot open"), std::string::npos);
    EXPECT_EQ(point_state(broken), PointState::failed);
    const auto after = read_csv(out / "sweep.csv");
    ASSERT_EQ(after.size(), 5u);
    EXPECT_EQ(row_map(after, 1)["status"], "failed");
    EXPECT_EQ(row_map(after, 2)["status"], "finished");
    fs::remove(broken / ".tumble.lock");
    std::ofstream(broken / ".tumble.lock").put('\n');
    r = run(bin + " sweep " + file + " -o " + out.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("self_omega3.000_seed1: failed before"), std::string::npos) << r.output;
    EXPECT_EQ(point_state(broken), PointState::finished);
}

// An interrupted point with a checkpoint is resumed, not rerun, and ends
// with the same series as a run that was never interrupted. One point of
// 20 grains and 0.1 revolutions (settling ends at step 4526, the run at
// 6663): a few seconds.
TEST_F(Sweep, InterruptedPointResumesFromItsCheckpoint) {
    const std::string bin = tumble_binary();
    const fs::path file = write("one.toml", R"([sweep]
omega = [5.0]
modes = ["self"]
seeds = [1]
revolutions = 0.1
grains_self = 20
grains_two_component = 20
snapshots_per_revolution = 0
)");
    const fs::path out = dir_ / "one";
    const SweepPoint point = expand_sweep(load_sweep_settings(file), out)[0];
    const fs::path reference = dir_ / "reference";
    std::string drum, uninterrupted;
    for (const std::string& a : drum_arguments(point)) {
        drum += " " + a;
        uninterrupted += " " + (a == point.directory.string() ? reference.string() : a);
    }
    ASSERT_EQ(run(bin + uninterrupted + " --no-plot").exit_code, 0);

    const Result stopped = run(bin + drum + " --stop-at-step 5714");
    ASSERT_EQ(stopped.exit_code, 4) << stopped.output;
    EXPECT_EQ(point_state(point.directory), PointState::unfinished);
    const Result r = run(bin + " sweep " + file.string() + " -o " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find(point.name + ": unfinished before; resuming it from its newest checkpoint"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(point_state(point.directory), PointState::finished);
    for (const char* series : {"time_series.csv", "drum_series.csv", "profiles.csv"})
        EXPECT_EQ(slurp(point.directory / series), slurp(reference / series)) << series;

    // Finished, its last checkpoint says so: with summary.json removed the
    // point is run again from the start, not resumed.
    fs::remove(point.directory / "summary.json");
    const Result again = run(bin + " sweep " + file.string() + " -o " + out.string());
    EXPECT_NE(again.output.find("running it again from the start"), std::string::npos) << again.output;
}

// The rows of a sweep table without the one column that measures the
// machine rather than the physics (grain_updates_per_second).
std::vector<std::vector<std::string>> without_speed(std::vector<std::vector<std::string>> rows) {
    const auto at = std::find(rows[0].begin(), rows[0].end(), "grain_updates_per_second") - rows[0].begin();
    for (auto& row : rows)
        if (static_cast<std::size_t>(at) < row.size()) row.erase(row.begin() + at);
    return rows;
}

// A sweep killed (SIGKILL to the sweep and its children) while some points
// are finished and others running, then started again, ends with the same
// table as an uninterrupted sweep: the same numbers in every column but the
// measured speed. Each point is deterministic for its seed, so "the same"
// is exact.
TEST_F(Sweep, KilledHalfWayAndRestartedGivesTheUninterruptedTable) {
    const std::string bin = tumble_binary();
    if (!has_sweep_command(bin)) GTEST_SKIP() << bin << " has no `sweep` command yet";
    const std::string file = std::string(TUMBLE_SOURCE_DIR) + "/examples/sweep_tiny.toml";
    const fs::path whole = dir_ / "whole", killed = dir_ / "killed";
    ASSERT_EQ(run(bin + " sweep -q " + file + " -o " + whole.string() + " -j 2").exit_code, 0);

    // setsid: the sweep leads a process group of its own, with its children.
    const fs::path pid_file = dir_ / "sweep.pid";
    ASSERT_EQ(std::system(("setsid sh -c 'echo $$ > " + pid_file.string() + "; exec " + bin + " sweep -q " + file +
                           " -o " + killed.string() + " -j 1 > /dev/null 2>&1' &")
                              .c_str()),
              0);
    // Wait (at most 2 minutes) until the first point is finished: with -j 1
    // the second is then running.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(2);
    const fs::path first_point = killed / "points" / "self_omega3.000_seed1" / "summary.json";
    while (!fs::exists(first_point) && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    std::this_thread::sleep_for(std::chrono::seconds(1));
    const pid_t group = std::stoi(slurp(pid_file));
    ASSERT_EQ(::kill(-group, SIGKILL), 0) << "the sweep ended before it could be killed";
    for (int k = 0; k < 1000 && ::kill(-group, 0) == 0; ++k)  // gone, and its locks with it
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ASSERT_TRUE(fs::exists(first_point));
    EXPECT_FALSE(fs::exists(killed / "points" / "self_omega5.000_seed2" / "summary.json"));

    const Result again = run(bin + " sweep " + file + " -o " + killed.string() + " -j 2");
    ASSERT_EQ(again.exit_code, 0) << again.output;
    EXPECT_NE(again.output.find("1 finished before, 3 to run"), std::string::npos) << again.output;
    EXPECT_EQ(without_speed(read_csv(killed / "sweep.csv")), without_speed(read_csv(whole / "sweep.csv")));
}

// END TO END under mpirun (skipped without mpirun, or without MPI in this
// build): rank 0 hands the points of the tiny sweep to 2 ranks and gathers
// their results by message; every point runs once, and the table is the
// serial sweep's (each point is deterministic for its seed). Then 3 ranks
// (oversubscribed: more ranks than cores), which resume nothing.
TEST_F(Sweep, EndToEndUnderMpirun) {
    const std::string bin = tumble_binary();
    if (run("mpirun --version").exit_code != 0) GTEST_SKIP() << "no mpirun";
    if (!mpi::built_with_mpi()) GTEST_SKIP() << "built without MPI (TUMBLE_MPI=OFF)";
    const std::string file = std::string(TUMBLE_SOURCE_DIR) + "/examples/sweep_tiny.toml";
    const std::string mpirun = "mpirun --allow-run-as-root --oversubscribe ";
    const fs::path serial = dir_ / "serial", out = dir_ / "mpi";
    ASSERT_EQ(run(bin + " sweep -q " + file + " -o " + serial.string() + " -j 2").exit_code, 0);
    const Result r = run(mpirun + "-np 2 " + bin + " sweep " + file + " -o " + out.string() + " -j 1");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("on each of 2 ranks"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("(rank 1)"), std::string::npos) << r.output;  // rank 1 ran a point, rank 0 heard of it
    for (const char* point : {"self_omega3.000_seed1", "self_omega3.000_seed2", "self_omega5.000_seed1",
                              "self_omega5.000_seed2"}) {
        std::size_t starts = 0;
        for (std::size_t at = r.output.find(std::string("start  ") + point); at != std::string::npos;
             at = r.output.find(std::string("start  ") + point, at + 1))
            ++starts;
        EXPECT_EQ(starts, 1u) << point << "\n" << r.output;
    }
    EXPECT_EQ(without_speed(read_csv(out / "sweep.csv")), without_speed(read_csv(serial / "sweep.csv")));

    const Result again = run(mpirun + "-np 3 " + bin + " sweep " + file + " -o " + out.string());
    ASSERT_EQ(again.exit_code, 0) << again.output;
    EXPECT_NE(again.output.find("4 finished before, 0 to run"), std::string::npos) << again.output;
    EXPECT_EQ(without_speed(read_csv(out / "sweep.csv")), without_speed(read_csv(serial / "sweep.csv")));
}

// Any other command refuses several ranks (it would run the same work on
// each), before any work, naming the way out.
TEST_F(Sweep, OtherCommandsRefuseSeveralRanks) {
    if (run("mpirun --version").exit_code != 0) GTEST_SKIP() << "no mpirun";
    if (!mpi::built_with_mpi()) GTEST_SKIP() << "built without MPI (TUMBLE_MPI=OFF)";
    const Result r = run("mpirun --allow-run-as-root --oversubscribe -np 2 " + tumble_binary() +
                         " bench --size 4 --steps 10 --export " + (dir_ / "bench").string());
    EXPECT_NE(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("only tumble sweep (each rank a share of the points), run, drum, resume and bench"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "bench"));
}

}  // namespace
