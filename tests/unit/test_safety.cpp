// SPDX-License-Identifier: MIT
// Never silently wrong: one process per run directory, a run is
// checked at its end and finished only when its results are written, and
// every input (command line, scenario, checkpoint) is checked before the
// work. Each test reproduces one such failure and expects the
// clear error or the uninterrupted result. tests/data/bad/run and
// tests/data/bad/cli hold the refused inputs, one case per class.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "io/checkpoint.hpp"
#include "io/run_lock.hpp"
#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;
namespace io = tumble::io;
using tumble::test_support::read_file;

// The small drum of test_resume.cpp: settles at step 3657, turns 2932
// steps per 0.2 revolutions.
std::string drum(const std::string& revolutions) {
    return " drum -q --mode self --grains 20 --length 0.03 --diameter 0.03 --omega 10 --samples 50 --snapshots 20 "
           "--no-plot --revolutions " + revolutions;
}
const std::string small_drum = drum("0.2");
const char* const drum_files[] = {"time_series.csv", "drum_series.csv", "profiles.csv", "particles.pvd",
                                  "contacts.pvd"};
const fs::path corpus = fs::path(TUMBLE_SOURCE_DIR) / "tests" / "data" / "bad";

tumble::test_support::CommandResult tumble(const std::string& arguments) {
    return tumble::test_support::run_command(std::string(TUMBLE_BINARY) + " " + arguments);
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The step column of the last row of a time_series.csv.
std::string last_step(const fs::path& series) {
    const std::string text = read_file(series);
    const std::size_t start = text.rfind('\n', text.size() - 2) + 1;
    const std::size_t comma = text.find(',', start);
    return text.substr(comma + 1, text.find(',', comma + 1) - comma - 1);
}

class Safety : public tumble::test_support::ScratchTest {
protected:
    fs::path drum_reference(const std::string& revolutions = "0.2") {
        const fs::path out = dir_ / "reference";
        const auto r = tumble(drum(revolutions) + " --out " + out.string());
        EXPECT_EQ(r.exit_code, 0) << r.output;
        return out;
    }
    void expect_same_drum_output(const fs::path& a, const fs::path& b) {
        for (const char* name : drum_files) EXPECT_EQ(read_file(a / name), read_file(b / name)) << name;
        EXPECT_TRUE(fs::exists(b / "summary.json"));
    }
    fs::path walled_box(const std::string& duration = "0.02") {
        return write("box.toml", tumble::test_support::walled_box_scenario(duration, "", "[output]\n"
                                                                                          "time_series_interval = 0.001\n"));
    }
    // Starts tumble with its output in dir_/LOG; returns the pid.
    pid_t start(const std::string& arguments, const std::string& log) {
        const std::string command =
            std::string("exec ") + TUMBLE_BINARY + " " + arguments + " > " + (dir_ / log).string() + " 2>&1";
        const pid_t pid = fork();
        if (pid == 0) {
            execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
            _exit(127);
        }
        return pid;
    }
    static int exit_code(pid_t pid) {
        int status = 0;
        waitpid(pid, &status, 0);
        return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
    }
    // A stopped run of the walled box and its newest checkpoint, to be altered.
    io::Checkpoint stopped_box(const fs::path& out) {
        const auto r = tumble("run -q " + walled_box().string() + " --out " + out.string() + " --stop-at-step 20");
        EXPECT_EQ(r.exit_code, 4) << r.output;
        return io::load_newest_checkpoint(out).checkpoint;
    }
};

// ---- 1. one process per run directory

TEST_F(Safety, TwoResumesAtOnceOneRefusesAndTheResultIsTheUninterruptedOne) {
    const fs::path full = drum_reference("1");
    const fs::path out = dir_ / "run";
    ASSERT_EQ(tumble(drum("1") + " --out " + out.string() + " --stop-at-step 1000").exit_code, 4);
    // The second starts when the first holds the lock (its pid is in the
    // lock file), before it has gone far.
    const pid_t a = start("resume -q " + out.string(), "a.log");
    for (int k = 0; k < 2000 && read_file(out / io::run_lock_file) != std::to_string(a) + "\n"; ++k)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    const pid_t b = start("resume -q " + out.string(), "b.log");
    const int code_a = exit_code(a), code_b = exit_code(b);
    const std::string refused = read_file(dir_ / (code_a == 0 ? "b.log" : "a.log"));
    EXPECT_EQ(std::min(code_a, code_b), 0);
    EXPECT_EQ(std::max(code_a, code_b), 2) << refused;
    EXPECT_TRUE(std::regex_search(refused, std::regex("in use by another tumble process \\(pid [0-9]+")))
        << refused;
    expect_same_drum_output(full, out);
}

TEST_F(Safety, EveryWritingCommandRefusesADirectoryInUseNamingTheHolder) {
    const fs::path scenario = walled_box("0.002");
    const fs::path out = dir_ / "run", sweep = dir_ / "sweep";
    ASSERT_EQ(tumble("run -q " + scenario.string() + " --out " + out.string()).exit_code, 0);
    const std::string before = read_file(out / "time_series.csv");
    fs::create_directories(sweep);
    const io::RunLock held(out), held_sweep(sweep);  // this test process holds both
    const std::string holder = "in use by another tumble process (pid " + std::to_string(::getpid()) + ",";
    for (const std::string& command :
         {"run -q --force " + scenario.string() + " --out " + out.string(), small_drum + " --force --out " + out.string(),
          "resume -q " + out.string(), "analyze " + out.string(),
          "sweep -q " + std::string(TUMBLE_SOURCE_DIR) + "/examples/sweep_tiny.toml -o " + sweep.string()}) {
        const auto r = tumble(command);
        EXPECT_EQ(r.exit_code, 2) << command << "\n" << r.output;
        EXPECT_TRUE(contains(r.output, holder)) << command << "\n" << r.output;
    }
    EXPECT_EQ(read_file(out / "time_series.csv"), before);
    EXPECT_FALSE(fs::exists(sweep / "points"));
}

// ---- 2. checked ends

TEST_F(Safety, ARunThatEndsUnphysicalBeforeTheFirstCheckIsAnError) {
    // 1000 m/s, ten thousand times the kinetic energy the time step allows
    // for, and fewer steps than the 100 between two checks.
    const fs::path scenario = write("fast.toml", R"([simulation]
duration = 0.0005
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.1, 0.1, 0.1]
periodic = [true, true, true]
)" + tumble::test_support::material_m_toml + R"([[particles]]
kind = "list"
material = "m"
particles = [{ position = [0.05, 0.05, 0.05], velocity = [1000.0, 0.0, 0.0] }]
)");
    const fs::path out = dir_ / "run";
    const auto r = tumble("run -q " + scenario.string() + " --out " + out.string());
    EXPECT_EQ(r.exit_code, 5) << r.output;
    EXPECT_TRUE(contains(r.output, "the simulation blew up at step")) << r.output;
    EXPECT_FALSE(fs::exists(out / "run.json"));
    EXPECT_TRUE(io::checkpoint_files(out).empty());
}

TEST_F(Safety, ARunThatTurnsNonFiniteBetweenChecksStopsWithAClearErrorInBoundedMemory) {
    // E = 1e150 (its pair moduli still finite; 1e308 is refused up front) at
    // a step forced far above its safe maximum: the first contact's force
    // overflows; the neighbour list is rebuilt with NaN positions before the
    // next health check, which made a grid of 10^18 cells (std::bad_alloc).
    std::string text = tumble::test_support::walled_box_scenario("0.3", "gravity = [0.0, 0.0, -9.81]\n");
    text.replace(text.find("E = 1.0e6"), 9, "E = 1e150");
    text += "[time_step]\ndt = 1e-5\nallow_unsafe = true\n";
    const fs::path out = dir_ / "run";
    const auto r = tumble("run -q " + write("stiff.toml", text).string() + " --out " + out.string());
    // Caught by the health check (exit 5) or, if a rebuild comes first, by
    // the neighbour search (exit 2; Neighbor.CellListRefusesANonFinitePosition).
    EXPECT_TRUE(r.exit_code == 5 || r.exit_code == 2) << r.output;
    EXPECT_TRUE(contains(r.output, "the simulation blew up")) << r.output;
    EXPECT_FALSE(fs::exists(out / "run.json"));
    EXPECT_TRUE(io::checkpoint_files(out).empty()) << "no checkpoint, finished or not, of a broken state";
}

// ---- 3. a run is finished only when its results are written

// Copies the run stopped at its last step, resumes it with a kill before the
// Nth file rename (N = 1, 2, ... until the resume gets through), resumes it
// again, and compares with the uninterrupted run.
void kill_at_every_rename(const fs::path& stopped, const fs::path& work,
                          const std::function<void(const fs::path&)>& expect_finished) {
    for (int n = 1; n < 20; ++n) {
        fs::remove_all(work);
        fs::copy(stopped, work, fs::copy_options::recursive);
        const auto killed = tumble::test_support::run_command("TUMBLE_TEST_KILL_AT_RENAME=" + std::to_string(n) + " " +
                                                              TUMBLE_BINARY + " resume -q " + work.string());
        if (killed.exit_code == 0) {
            EXPECT_GT(n, 2) << "the finalisation writes its results between two checkpoints";
            expect_finished(work);
            return;
        }
        EXPECT_EQ(killed.exit_code, 128 + 9) << "rename " << n << ": " << killed.output;  // SIGKILL by the hook
        const auto resumed = tumble("resume -q " + work.string());
        ASSERT_EQ(resumed.exit_code, 0) << "rename " << n << ": " << resumed.output;
        expect_finished(work);
        const auto again = tumble("resume " + work.string());
        EXPECT_TRUE(contains(again.output, "has finished")) << again.output;
    }
    ADD_FAILURE() << "the finalisation never got through";
}

TEST_F(Safety, AScenarioRunKilledAtEveryWriteOfItsEndResumesToTheUninterruptedResult) {
    const fs::path scenario = walled_box();
    const fs::path full = dir_ / "full", stopped = dir_ / "stopped";
    ASSERT_EQ(tumble("run -q " + scenario.string() + " --out " + full.string()).exit_code, 0);
    const std::string end = last_step(full / "time_series.csv");
    ASSERT_EQ(tumble("run -q " + scenario.string() + " --out " + stopped.string() + " --stop-at-step " + end).exit_code,
              4);
    kill_at_every_rename(stopped, dir_ / "work", [&](const fs::path& run) {
        EXPECT_EQ(read_file(run / "time_series.csv"), read_file(full / "time_series.csv"));
        EXPECT_TRUE(contains(read_file(run / "run.json"), "\"steps\": " + end));
    });
}

TEST_F(Safety, ADrumRunKilledAtEveryWriteOfItsEndResumesToTheUninterruptedResult) {
    const fs::path full = drum_reference(), stopped = dir_ / "stopped";
    const std::string end = last_step(full / "time_series.csv");
    ASSERT_EQ(tumble(small_drum + " --out " + stopped.string() + " --stop-at-step " + end).exit_code, 4);
    kill_at_every_rename(stopped, dir_ / "work", [&](const fs::path& run) { expect_same_drum_output(full, run); });
}

// ---- 4. a checkpoint is input

TEST_F(Safety, ACheckpointWithValidChecksumButImpossibleContentsIsRefused) {
    struct Case {
        const char* what;
        std::function<void(io::Checkpoint&)> alter;
        const char* expect;
    };
    const std::vector<Case> cases = {
        {"material -7", [](io::Checkpoint& c) { c.state.particles.material[0] = -7; }, "differs from the scenario's"},
        {"material 1000", [](io::Checkpoint& c) { c.state.particles.material[3] = 1000; }, "differs from the scenario's"},
        {"motion 77", [](io::Checkpoint& c) { c.state.particles.motion[1] = 77; }, "differs from the scenario's"},
        {"steps 2^62", [](io::Checkpoint& c) { c.record.set("run.steps", std::int64_t{1} << 62); }, "run.steps"},
        {"threads", [](io::Checkpoint& c) { c.record.set("threads", std::int64_t{100000}); }, "threads: need 1 to"},
    };
    for (const Case& k : cases) {
        const fs::path out = dir_ / "run";
        fs::remove_all(out);
        io::Checkpoint c = stopped_box(out);
        const std::string series = read_file(out / "time_series.csv");
        k.alter(c);
        io::write_checkpoint(out, c);
        const auto r = tumble("resume -q " + out.string());
        EXPECT_EQ(r.exit_code, 2) << k.what << ": " << r.output;
        EXPECT_TRUE(contains(r.output, k.expect)) << k.what << ": " << r.output;
        EXPECT_EQ(read_file(out / "time_series.csv"), series) << k.what;
    }
}

TEST_F(Safety, ACheckpointWhoseRecordDoesNotFitItsFilesIsPassedOverForThePreviousOne) {
    // Each forged with a valid checksum (the checkpoint written anew): a
    // length of time_series.csv that ends inside a row (resumed, it left a
    // cut row), and a snapshot time that is no time (particles.pvd got
    // timestep="nan").
    const fs::path scenario = write("snapshots.toml", tumble::test_support::walled_box_scenario(
                                                          "0.02", "", "[output]\ntime_series_interval = 0.001\n"
                                                                      "snapshot_interval = 0.005\n"));
    const fs::path full = dir_ / "full";
    ASSERT_EQ(tumble("run -q " + scenario.string() + " --out " + full.string()).exit_code, 0);
    struct Case {
        const char* what;
        std::function<void(io::Checkpoint&)> alter;
        const char* expect;
    };
    const std::vector<Case> cases = {
        {"length",
         [](io::Checkpoint& c) {
             c.record.set("file:time_series.csv", c.record.integer("file:time_series.csv") - 5);
         },
         "bytes, ends inside a row"},
        {"snapshot times",
         [](io::Checkpoint& c) {
             std::vector<double> times = c.record.numbers("snapshot_times");
             times.back() = std::nan("");
             c.record.set("snapshot_times", times);
         },
         "record key \"snapshot_times\" holds nan, not a time in order up to the state's time"},
    };
    for (const Case& k : cases) {
        const fs::path out = dir_ / "run";
        fs::remove_all(out);
        ASSERT_EQ(tumble("run -q " + scenario.string() + " --out " + out.string() + " --stop-at-step 12").exit_code, 4);
        io::Checkpoint c = io::load_newest_checkpoint(out).checkpoint;
        ASSERT_FALSE(c.record.numbers("snapshot_times").empty());
        k.alter(c);
        io::write_checkpoint(out, c);
        const auto r = tumble("resume " + out.string());
        EXPECT_EQ(r.exit_code, 0) << k.what << ": " << r.output;
        EXPECT_TRUE(contains(r.output, "000002.tck: ")) << k.what << ": " << r.output;
        EXPECT_TRUE(contains(r.output, k.expect)) << k.what << ": " << r.output;
        EXPECT_EQ(read_file(out / "time_series.csv"), read_file(full / "time_series.csv")) << k.what;
        EXPECT_EQ(read_file(out / "particles.pvd"), read_file(full / "particles.pvd")) << k.what;
    }
}

TEST_F(Safety, AFinishedFlagWithoutTheResultsIsNotTrusted) {
    // Forged at step 20 of the run (with a valid checksum): resume said
    // "has finished; nothing to do" and the run had no run.json.
    const fs::path full = dir_ / "full", out = dir_ / "run";
    ASSERT_EQ(tumble("run -q " + walled_box().string() + " --out " + full.string()).exit_code, 0);
    io::Checkpoint c = stopped_box(out);
    c.record.set("finished", std::int64_t{1});
    io::write_checkpoint(out, c);
    const auto r = tumble("resume -q " + out.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "says the run has finished, but " + (out / "run.json").string() + " is missing"))
        << r.output;
    EXPECT_EQ(read_file(out / "time_series.csv"), read_file(full / "time_series.csv"));
    EXPECT_TRUE(fs::exists(out / "run.json"));
    const auto again = tumble("resume " + out.string());
    EXPECT_TRUE(contains(again.output, "has finished")) << again.output;
}

// ---- 5. bounded memory: a checkpoint that is no file or too large is skipped

TEST_F(Safety, ACheckpointLinkedToDevZeroOrSparseAndHugeFallsBackToThePreviousOne) {
    const fs::path scenario = walled_box();
    const fs::path full = dir_ / "full";
    ASSERT_EQ(tumble("run -q " + scenario.string() + " --out " + full.string()).exit_code, 0);
    for (const char* kind : {"dev-zero", "sparse"}) {
        const fs::path out = dir_ / kind;
        ASSERT_EQ(tumble("run -q " + scenario.string() + " --out " + out.string() + " --stop-at-step 40").exit_code, 4);
        const fs::path next = out / "checkpoints" / "000002.tck";
        if (std::string(kind) == "dev-zero") {
            fs::create_symlink("/dev/zero", next);
        } else {
            std::ofstream(next).put('x');
            fs::resize_file(next, std::uintmax_t{4} << 30);
        }
        const auto r = tumble("resume -q " + out.string());
        ASSERT_EQ(r.exit_code, 0) << kind << ": " << r.output;
        EXPECT_TRUE(contains(r.output, "using the previous checkpoint")) << kind << ": " << r.output;
        EXPECT_EQ(read_file(out / "time_series.csv"), read_file(full / "time_series.csv")) << kind;
    }
}

// ---- 6. a series cut short by a power cut: the previous checkpoint fits

TEST_F(Safety, ASeriesShorterThanTheNewestCheckpointSaysFallsBackToThePreviousOne) {
    const fs::path scenario = walled_box();
    const fs::path full = dir_ / "full", out = dir_ / "cut";
    ASSERT_EQ(tumble("run -q " + scenario.string() + " --out " + full.string()).exit_code, 0);
    ASSERT_EQ(tumble("run -q " + scenario.string() + " --out " + out.string() +
                     " --checkpoint-every-steps 90 --stop-at-step 210")
                  .exit_code,
              4);
    const auto files = io::checkpoint_files(out);
    ASSERT_EQ(files.size(), 2u);
    const auto older = io::decode_checkpoint(read_file(files[0]), files[0].string()).record.integer("file:time_series.csv");
    fs::resize_file(out / "time_series.csv", static_cast<std::uintmax_t>(older) + 10);
    const auto r = tumble("resume -q " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "shorter than when the checkpoint was written")) << r.output;
    EXPECT_EQ(read_file(out / "time_series.csv"), read_file(full / "time_series.csv"));
}

// ---- 7. --force removes only what tumble wrote, and the old results first

TEST_F(Safety, ForceKeepsAUsersOwnFoldersAndRemovesTheOldResultsFirst) {
    const fs::path mine = dir_ / "mine";
    write("mine/snapshots/notes.txt", "my own notes\n");
    write("mine/checkpoints/keep.txt", "mine\n");
    const auto refused = tumble("run -q --force " + walled_box().string() + " --out " + mine.string());
    EXPECT_EQ(refused.exit_code, 2);
    EXPECT_TRUE(contains(refused.output, "snapshots: exists, but tumble did not write")) << refused.output;
    EXPECT_EQ(read_file(mine / "snapshots" / "notes.txt"), "my own notes\n");
    EXPECT_TRUE(fs::exists(mine / "checkpoints" / "keep.txt"));

    const fs::path out = drum_reference();
    ASSERT_TRUE(fs::exists(out / "summary.json"));
    const auto again = tumble(small_drum + " --force --out " + out.string() + " --stop-at-step 100");
    EXPECT_EQ(again.exit_code, 4) << again.output;
    EXPECT_FALSE(fs::exists(out / "summary.json"));
    EXPECT_FALSE(fs::exists(out / "drum_series.csv"));
}

// ---- 8. an unfinished run is not analysed as if it were finished

TEST_F(Safety, AnalyzeRefusesAnUnfinishedRun) {
    const fs::path out = dir_ / "run";
    ASSERT_EQ(tumble(small_drum + " --out " + out.string() + " --stop-at-step 4063").exit_code, 4);
    const auto r = tumble("analyze " + out.string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.output, "the run is unfinished")) << r.output;
    EXPECT_FALSE(fs::exists(out / "summary.json"));
    // Stopped before its first checkpoint (none left), without a summary.
    fs::remove_all(out / "checkpoints");
    const auto none = tumble("analyze " + out.string());
    EXPECT_EQ(none.exit_code, 2) << none.output;
    EXPECT_TRUE(contains(none.output, "the run is unfinished (no checkpoint and no summary.json")) << none.output;
    EXPECT_FALSE(fs::exists(out / "summary.json"));
}

// ---- 8b. a size that is a unit slip is refused before any work

// `--diameter 8` meant as 8 cm built 2.9 million wall spheres for 1000
// grains and ran for minutes with no output. A wall of more than 50 times
// the grains and more than 100,000 spheres is refused with the numbers;
// --large-drum lets a drum that is meant through.
TEST_F(Safety, ADrumWallFarLargerThanItsGrainsIsRefusedUnlessConfirmed) {
    const fs::path out = dir_ / "eight-metres";
    const auto r = tumble(" drum -q --no-plot --diameter 8 --out " + out.string());
    EXPECT_EQ(r.exit_code, 2);
    for (const char* part : {"diameter 8 m", "spheres for 1000 grains", "Sizes are in metres", "--large-drum"})
        EXPECT_TRUE(contains(r.output, part)) << part << " missing in: " << r.output;
    EXPECT_FALSE(fs::exists(out));  // nothing written
    // A metre-wide drum (about 140,000 wall spheres for 1000 grains) runs
    // when confirmed; the 64 cm drum of docs/BENCHMARKS.md needs no flag.
    const std::string one_step = " drum -q --no-plot --snapshots 0 --stop-at-step 1 --out ";
    EXPECT_EQ(tumble(one_step + (dir_ / "metre").string() + " --diameter 1 --length 1").exit_code, 2);
    EXPECT_EQ(tumble(one_step + (dir_ / "metre-confirmed").string() + " --diameter 1 --length 1 --large-drum").exit_code,
              4);
    EXPECT_EQ(tumble(one_step + (dir_ / "long").string() + " --length 0.64 --fill 0.3").exit_code, 4);
}

// A material refused as too soft (tests/data/bad/run/soft_*.toml, E in Pa
// where MPa was meant) runs when --allow-soft confirms it.
TEST_F(Safety, ASoftMaterialRunsWhenConfirmed) {
    const fs::path scenario = corpus / "run" / "soft_under_weight.toml";
    EXPECT_EQ(tumble("run -q " + scenario.string() + " --out " + (dir_ / "refused").string()).exit_code, 2);
    EXPECT_FALSE(fs::exists(dir_ / "refused"));
    EXPECT_EQ(tumble("run -q " + scenario.string() + " --allow-soft --out " + (dir_ / "soft").string()).exit_code, 0);
    EXPECT_TRUE(fs::exists(dir_ / "soft" / "time_series.csv"));
}

// ---- 8c. absurd sizes and starts are refused before any work

// A lattice of 10^7 spheres built 3.6 GB for 29 s before the memory check
// refused it: the reader now counts the spheres from the block's keys and
// the memory check comes before any is made. 10^7 spheres at 1.96 kB each
// (3.41 neighbour pairs at the automatic skin) are 18.3 GiB.
TEST_F(Safety, AnEnormousLatticeIsRefusedBeforeItIsBuilt) {
    const fs::path scenario = write("huge.toml", R"([simulation]
duration = 0.01
[domain]
lo = [0.0, 0.0, 0.0]
hi = [1.0, 1.0, 10.0]
)" + tumble::test_support::material_m_toml + R"([[particles]]
kind = "lattice"
material = "m"
origin = [0.005, 0.005, 0.005]
counts = [100, 100, 1000]
spacing = 0.008
)");
    const fs::path out = dir_ / "huge";
    const auto started = std::chrono::steady_clock::now();
    const auto r = tumble("run -q " + scenario.string() + " --max-memory 1 --out " + out.string());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_TRUE(contains(r.output, scenario.string() +
                                       ": the run would need about 18.3 GiB of memory for 10000000 spheres "
                                       "(particles[0].counts), 3.41 neighbour pairs each, more than the limit of 1 "
                                       "GiB (--max-memory GIB; default half the machine's memory)"))
        << r.output;
    EXPECT_LT(seconds, 5.0) << "the spheres were made before the refusal";
    EXPECT_FALSE(fs::exists(out));
}

// A mesh wall counts in the memory a run will need: a floor of 199,712
// triangles (a 316 x 316 grid of squares, 0.5 mm each) under 8 spheres is
// some 0.37 GiB (1000 bytes a triangle, twice over), refused at a limit of
// 0.1 GiB, naming the triangles, before any step.
TEST_F(Safety, AHugeMeshIsRefusedByTheMemoryLimit) {
    constexpr int n = 316;
    std::string stl(80, ' ');
    const std::uint32_t count = 2 * n * n;
    stl.append(reinterpret_cast<const char*>(&count), 4);
    auto corner = [&](int i, int j) {
        const float xyz[3] = {0.5f * static_cast<float>(i), 0.5f * static_cast<float>(j), 0.0f};
        stl.append(reinterpret_cast<const char*>(xyz), 12);
    };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (const int half : {0, 1}) {
                stl.append(12, '\0');  // the normal (recomputed from the corners)
                corner(i, j);
                half == 0 ? corner(i + 1, j) : corner(i + 1, j + 1);
                half == 0 ? corner(i + 1, j + 1) : corner(i, j + 1);
                stl.append(2, '\0');
            }
    write("floor.stl", stl);
    const fs::path scenario = write("mesh.toml", R"([simulation]
duration = 0.01
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.16, 0.16, 0.05]
)" + tumble::test_support::material_m_toml + R"([[wall]]
name = "floor"
shape = "mesh"
material = "m"
file = "floor.stl"
scale = 1e-3
[[particles]]
kind = "lattice"
material = "m"
origin = [0.02, 0.02, 0.02]
counts = [2, 2, 2]
spacing = 0.02
)");
    const fs::path out = dir_ / "mesh";
    const auto r = tumble("run -q " + scenario.string() + " --max-memory 0.1 --out " + out.string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_TRUE(contains(r.output, "and 199712 mesh triangles (0.37")) << r.output;
    EXPECT_TRUE(contains(r.output, "more than the limit of 0.1 GiB")) << r.output;
    EXPECT_FALSE(fs::exists(out));
}

// Two spheres overlapping by 0.7 of their radius, allowed by
// simulation.max_initial_overlap = 0.9, relaxed within the first 100
// steps and ran to exit 0, unless a checkpoint at step 1 had the blow-up
// check see them (exit 5). The blow-up check stops a run at overlaps above
// 0.5: a start above it is refused before any work, whatever the
// checkpoints, and one below it runs the same either way.
TEST_F(Safety, AHeavyInitialOverlapIsRefusedBeforeAnyWorkWhateverTheCheckpoints) {
    // Centres at -x and x, overlapping by 2 R - 2 x.
    const auto two = [&](const std::string& x, const std::string& simulation) {
        return write("two.toml", "[simulation]\nduration = 0.005\n" + simulation + R"([domain]
lo = [-0.02, -0.01, -0.01]
hi = [0.02, 0.01, 0.01]
)" + tumble::test_support::material_m_toml + "[[particles]]\nkind = \"list\"\nmaterial = \"m\"\nparticles = [ "
                                              "{ position = [-" + x + ", 0.0, 0.0] }, { position = [" + x +
                                              ", 0.0, 0.0] } ]\n");
    };
    for (const std::string every : {"", " --checkpoint-every-steps 1"}) {
        const fs::path out = dir_ / "overlap";
        auto r = tumble("run -q " + two("0.00234", "max_initial_overlap = 0.9\n").string() + every + " --out " +
                        out.string());
        EXPECT_EQ(r.exit_code, 2) << r.output;
        EXPECT_TRUE(contains(r.output, "two.toml: simulation.max_initial_overlap: must be at most 0.5, the overlap at "
                                       "which the blow-up check stops a run, got 0.9 (line 3)"))
            << r.output;
        EXPECT_FALSE(fs::exists(out));
        r = tumble("run -q " + two("0.00234", "").string() + every + " --out " + out.string());
        EXPECT_EQ(r.exit_code, 2) << r.output;
        EXPECT_TRUE(contains(r.output, "two.toml: particles[0].particles[1]: the particle at (0.00234, 0, 0) overlaps "
                                       "particles[0].particles[0] at (-0.00234, 0, 0) by 0.7 of the smaller radius, "
                                       "more than simulation.max_initial_overlap = 0.05"))
            << r.output;
        EXPECT_FALSE(fs::exists(out));
        // 0.45 of the radius, allowed.
        r = tumble("run -q " + two("0.00279", "max_initial_overlap = 0.5\n").string() + every + " --out " +
                   out.string());
        EXPECT_EQ(r.exit_code, 0) << every << "\n" << r.output;
        fs::remove_all(out);
    }
}

// ---- 9. a sweep stopped by a signal (the messages are in the corpora, and
// the particle files in test_bad_input.cpp)

TEST_F(Safety, ASweepStoppedBySigtermStopsItsRunningPointWithACheckpoint) {
    const fs::path sweep = dir_ / "sweep";
    const pid_t pid = start("sweep " + std::string(TUMBLE_SOURCE_DIR) + "/examples/sweep_tiny.toml -j 1 -o " +
                                sweep.string(),
                            "sweep.log");
    const fs::path point = sweep / "points" / "self_omega3.000_seed1";
    for (int k = 0; k < 6000 && !fs::exists(point / "time_series.csv"); ++k)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    ::kill(pid, SIGTERM);
    EXPECT_EQ(exit_code(pid), 4);
    const std::string log = read_file(dir_ / "sweep.log");
    EXPECT_TRUE(contains(log, "stopped self_omega3.000_seed1 with a checkpoint")) << log;
    EXPECT_NO_THROW(io::RunLock{point}) << "the point's run has ended";
    EXPECT_TRUE(io::resumable(point));
}

// ---- 2, 3, 4, 5, 9: the corpus of refused runs and command lines

// Each file says on its first line "# expect: TEXT"; nothing may be written.
std::string expected_part(const fs::path& file) {
    std::ifstream in(file);
    std::string first;
    std::getline(in, first);
    return first.substr(std::string("# expect: ").size());
}

TEST_F(Safety, EveryRunOfTheCorpusIsRefusedBeforeAnythingIsWritten) {
    std::size_t files = 0;
    for (const auto& entry : fs::directory_iterator(corpus / "run")) {
        ++files;
        const fs::path out = dir_ / entry.path().stem();
        const auto r = tumble("run -q " + entry.path().string() + " --out " + out.string());
        EXPECT_EQ(r.exit_code, 2) << entry.path() << "\n" << r.output;
        EXPECT_TRUE(contains(r.output, entry.path().string() + ": ")) << r.output;
        EXPECT_TRUE(contains(r.output, expected_part(entry.path()))) << r.output;
        EXPECT_FALSE(fs::exists(out)) << entry.path();
    }
    EXPECT_GE(files, 4u);
}

TEST_F(Safety, EveryCommandLineOfTheCorpusIsRefusedBeforeAnythingIsWritten) {
    std::size_t files = 0;
    for (const auto& entry : fs::directory_iterator(corpus / "cli")) {
        ++files;
        std::ifstream in(entry.path());
        std::string expect, arguments;
        std::getline(in, expect);
        std::getline(in, arguments);
        const fs::path out = dir_ / entry.path().stem();
        arguments = std::regex_replace(arguments, std::regex("OUT"), out.string());
        arguments = std::regex_replace(arguments, std::regex("SOURCE"), TUMBLE_SOURCE_DIR);
        const auto r = tumble(arguments);
        EXPECT_NE(r.exit_code, 0) << entry.path() << "\n" << r.output;
        EXPECT_TRUE(contains(r.output, expected_part(entry.path()))) << entry.path() << "\n" << r.output;
        EXPECT_FALSE(fs::exists(out)) << entry.path();
    }
    EXPECT_GE(files, 10u);
}

}  // namespace
