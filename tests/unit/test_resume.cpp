// SPDX-License-Identifier: MIT
// tumble resume (docs/CHECKPOINTS.md): a run stopped, killed or interrupted
// at any point and resumed ends with the same files, byte for byte, as the
// run that was never interrupted.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "io/checkpoint.hpp"
#include "io/drum_output.hpp"
#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;
using tumble::test_support::read_file;

// A drum small enough to settle and turn in a fraction of a second: 20
// grains in a drum 3 cm long and across (173 wall spheres), 0.2 revolutions.
// Settling ends at step 3657; the rotation has 2932 steps (dt = tau/25).
const std::string small_drum =
    " drum -q --mode self --grains 20 --length 0.03 --diameter 0.03 --omega 10 --samples 50 --snapshots 20 --no-plot";

tumble::test_support::CommandResult tumble_run(const std::string& arguments) {
    return tumble::test_support::run_command(std::string(TUMBLE_BINARY) + " " + arguments);
}

// The files whose bytes an interruption must not change (drum_run.toml and
// the summary hold the wall-clock time, which does).
const char* const drum_files[] = {"time_series.csv", "drum_series.csv", "profiles.csv",
                                  "band_profile.csv", "particles.pvd",    "contacts.pvd"};

class Resume : public tumble::test_support::ScratchTest {
protected:
    fs::path reference(const std::string& revolutions = "0.2") {
        const fs::path out = dir_ / "reference";
        const auto r = tumble_run(small_drum + " --revolutions " + revolutions + " --out " + out.string());
        EXPECT_EQ(r.exit_code, 0) << r.output;
        return out;
    }
    void expect_same_output(const fs::path& a, const fs::path& b) {
        for (const char* name : drum_files) EXPECT_EQ(read_file(a / name), read_file(b / name)) << name;
        std::size_t snapshots = 0;
        for (const auto& entry : fs::directory_iterator(a / "snapshots")) {
            EXPECT_EQ(read_file(entry.path()), read_file(b / "snapshots" / entry.path().filename()))
                << entry.path().filename();
            ++snapshots;
        }
        EXPECT_GT(snapshots, 0u);
    }
    // Starts tumble as a child process; its output goes to dir_/child.log.
    pid_t start(const std::string& arguments) {
        const std::string command = std::string("exec ") + TUMBLE_BINARY + " " + arguments + " > " +
                                    (dir_ / "child.log").string() + " 2>&1";
        const pid_t pid = fork();
        if (pid == 0) {
            execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
            _exit(127);
        }
        return pid;
    }
    // Waits until checkpoint number n or a later one has been written (or 60 s).
    static void wait_for_checkpoint(const fs::path& run, int n) {
        auto newest = [&] {
            const auto files = tumble::io::checkpoint_files(run);
            return files.empty() ? 0 : std::stoi(files.back().stem().string());
        };
        for (int k = 0; k < 6000 && newest() < n; ++k) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    static int exit_code(pid_t pid) {
        int status = 0;
        waitpid(pid, &status, 0);
        return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
    }
};

TEST_F(Resume, StoppedAtAnyStepAndResumedGivesTheSameBytes) {
    const fs::path full = reference();
    // While settling, at the settling boundary, inside rotation between
    // neighbour-list builds, and one step before the end.
    for (const char* step : {"1000", "3657", "4063", "4702", "6588"}) {
        const fs::path out = dir_ / (std::string("stop-") + step);
        const auto stopped = tumble_run(small_drum + " --revolutions 0.2 --out " + out.string() + " --stop-at-step " + step);
        ASSERT_EQ(stopped.exit_code, 4) << stopped.output;
        // The hint names the program as it was invoked (here TUMBLE_BINARY's path).
        EXPECT_NE(stopped.output.find(std::string(TUMBLE_BINARY) + " resume " + out.string()), std::string::npos)
            << stopped.output;
        const auto resumed = tumble_run("resume -q " + out.string());
        ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
        expect_same_output(full, out);
        const auto again = tumble_run("resume " + out.string());
        EXPECT_EQ(again.exit_code, 0);
        EXPECT_NE(again.output.find("has finished"), std::string::npos) << again.output;
    }
}

// A drum with its own fill (bands between given boundaries, a
// volume fraction, the caps' own friction) resumes to the same bytes: the
// checkpoint holds the particles and the caps' material, its record the
// arrangement.
TEST_F(Resume, ArrangedDrumWithCapFrictionResumesToTheSameBytes) {
    const std::string drum = " drum -q --grains 20 --length 0.03 --diameter 0.03 --omega 10 --samples 50 --snapshots 20 "
                             "--no-plot --revolutions 0.1 --arrangement boundaries --boundaries 0.0 --ends large "
                             "--small-volume-fraction 0.4 --cap-friction 0.6 --out ";
    const fs::path full = dir_ / "full";
    ASSERT_EQ(tumble_run(drum + full.string()).exit_code, 0);
    for (const char* step : {"2000", "4500"}) {  // settling (to about step 3660 at 4.29e-5 s), rotating (to 5130)
        const fs::path out = dir_ / (std::string("stop-") + step);
        ASSERT_EQ(tumble_run(drum + out.string() + " --stop-at-step " + step).exit_code, 4);
        const auto resumed = tumble_run("resume -q " + out.string());
        ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
        expect_same_output(full, out);
        const tumble::io::DrumRunInfo info = tumble::io::read_drum_run_info(out / "drum_run.toml");
        EXPECT_EQ(info.arrangement, "boundaries");
        EXPECT_EQ(info.band_edges, (std::vector<double>{-0.015, 0.0, 0.015}));
        EXPECT_EQ(info.cap_friction, 0.6);
    }
}

TEST_F(Resume, ADamagedNewestCheckpointFallsBackToThePreviousOne) {
    const fs::path full = reference();
    const fs::path out = dir_ / "damaged";
    const auto stopped = tumble_run(small_drum + " --revolutions 0.2 --checkpoint-every-revolutions 0.02 --out " +
                                    out.string() + " --stop-at-step 4702");
    ASSERT_EQ(stopped.exit_code, 4) << stopped.output;
    const std::vector<fs::path> files = tumble::io::checkpoint_files(out);
    ASSERT_EQ(files.size(), 2u);
    std::string bytes = read_file(files.back());
    bytes[bytes.size() / 2] ^= 1;
    std::ofstream(files.back(), std::ios::binary | std::ios::trunc) << bytes;
    const auto resumed = tumble_run("resume -q " + out.string());
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    EXPECT_NE(resumed.output.find("checksum mismatch (damaged); using the previous checkpoint"), std::string::npos)
        << resumed.output;
    expect_same_output(full, out);
}

TEST_F(Resume, KilledMidRunAndResumedGivesTheSameBytes) {
    // kill -9 after the second checkpoint: the files hold rows written after
    // it, which the resume cuts back and writes again.
    const fs::path full = reference("1");
    const fs::path out = dir_ / "killed";
    const pid_t child = start(small_drum + " --revolutions 1 --checkpoint-every-revolutions 0.05 --out " + out.string());
    wait_for_checkpoint(out, 3);
    kill(child, SIGKILL);
    ASSERT_EQ(exit_code(child), -SIGKILL) << "the run ended before it was killed";
    const auto resumed = tumble_run("resume -q " + out.string());
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    expect_same_output(full, out);
}

TEST_F(Resume, KilledWhileWritingCheckpointsLeavesALoadableOne) {
    // A checkpoint every 0.001 revolutions (31 steps): the process spends
    // most of its time writing them (each is flushed to the disk), so the
    // kills land inside writes.
    const fs::path full = reference();
    for (int delay_ms : {100, 170}) {
        const fs::path out = dir_ / ("kill-" + std::to_string(delay_ms));
        const pid_t child =
            start(small_drum + " --revolutions 0.2 --checkpoint-every-revolutions 0.001 --out " + out.string());
        wait_for_checkpoint(out, 1);
        std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
        kill(child, SIGKILL);
        ASSERT_EQ(exit_code(child), -SIGKILL) << "the run ended before it was killed";
        const auto resumed = tumble_run("resume -q " + out.string());
        ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
        expect_same_output(full, out);
    }
}

TEST_F(Resume, SigintAndSigtermWriteACheckpointAndSayHowToGoOn) {
    const fs::path full = reference("1");
    for (int signal : {SIGINT, SIGTERM}) {
        const fs::path out = dir_ / ("signal-" + std::to_string(signal));
        const pid_t child = start(small_drum + " --revolutions 1 --checkpoint-every-revolutions 0.1 --out " + out.string());
        wait_for_checkpoint(out, 1);
        kill(child, signal);
        EXPECT_EQ(exit_code(child), 4);
        const std::string log = read_file(dir_ / "child.log");
        EXPECT_NE(log.find("stopped by a signal"), std::string::npos) << log;
        EXPECT_NE(log.find(std::string(TUMBLE_BINARY) + " resume " + out.string()), std::string::npos) << log;
        const auto resumed = tumble_run("resume -q " + out.string());
        ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
        expect_same_output(full, out);
    }
}

TEST_F(Resume, ScenarioRunsResumeToo) {
    const fs::path scenario = write("box.toml", tumble::test_support::walled_box_scenario("0.05", "", R"([output]
time_series_interval = 0.001
snapshot_interval = 0.01
)"));
    const auto full = tumble_run("run -q " + scenario.string() + " --out " + (dir_ / "full").string());
    ASSERT_EQ(full.exit_code, 0) << full.output;
    const fs::path out = dir_ / "stopped";
    const auto stopped = tumble_run("run -q " + scenario.string() + " --out " + out.string() + " --stop-at-step 370");
    ASSERT_EQ(stopped.exit_code, 4) << stopped.output;
    // --revolutions is a drum run's: refused for this one, before it goes on.
    const auto lengthened = tumble_run("resume -q " + out.string() + " --revolutions 2");
    EXPECT_EQ(lengthened.exit_code, 2) << lengthened.output;
    EXPECT_NE(lengthened.output.find("--revolutions: the run in " + out.string() + " is not a drum run"), std::string::npos)
        << lengthened.output;
    const auto resumed = tumble_run("resume -q " + out.string());
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    EXPECT_EQ(read_file(dir_ / "full" / "time_series.csv"), read_file(out / "time_series.csv"));
    EXPECT_EQ(read_file(dir_ / "full" / "particles.pvd"), read_file(out / "particles.pvd"));
    ASSERT_TRUE(fs::exists(out / "snapshots" / "000004.vtu"));
    for (const char* snapshot : {"000004.csv", "000004.vtu", "000004.vtp"})
        EXPECT_EQ(read_file(dir_ / "full" / "snapshots" / snapshot), read_file(out / "snapshots" / snapshot));
}

// tumble resume --revolutions lengthens a drum run (the band study runs on
// past its first 150 revolutions). Asked for fewer revolutions than it has
// turned, it refuses before anything is touched (the summary stays); asked
// for more, a finished run of 0.2 revolutions goes on from its end and
// writes every snapshot as the run asked for 0.4 from the start, bit for
// bit (a checkpoint holds the whole state), then its summary anew.
TEST_F(Resume, AFinishedDrumRunIsLengthenedToTheLongerRun) {
    const fs::path full = reference("0.4");
    const fs::path out = dir_ / "lengthened";
    ASSERT_EQ(tumble_run(small_drum + " --revolutions 0.2 --out " + out.string()).exit_code, 0);
    const std::string summary = read_file(out / "summary.json");
    const auto fewer = tumble_run("resume -q " + out.string() + " --revolutions 0.1");
    EXPECT_EQ(fewer.exit_code, 2) << fewer.output;
    EXPECT_NE(fewer.output.find("has turned 0.2 revolutions already"), std::string::npos) << fewer.output;
    EXPECT_EQ(read_file(out / "summary.json"), summary);
    const auto endless = tumble_run("resume -q " + out.string() + " --revolutions inf");
    EXPECT_NE(endless.exit_code, 0);
    EXPECT_NE(endless.output.find("--revolutions: must be a finite number > 0, got inf"), std::string::npos)
        << endless.output;
    EXPECT_EQ(read_file(out / "summary.json"), summary);
    // Finite, but more steps than any run can take: refused as that, not
    // as fewer revolutions than turned (the step count overflowed).
    const auto huge = tumble_run("resume -q " + out.string() + " --revolutions 1e308");
    EXPECT_EQ(huge.exit_code, 2) << huge.output;
    EXPECT_NE(huge.output.find("--revolutions: "), std::string::npos) << huge.output;
    EXPECT_NE(huge.output.find("more than any run can take"), std::string::npos) << huge.output;
    EXPECT_EQ(huge.output.find("already"), std::string::npos) << huge.output;
    EXPECT_EQ(read_file(out / "summary.json"), summary);
    const auto longer = tumble_run("resume -q " + out.string() + " --revolutions 0.4");
    ASSERT_EQ(longer.exit_code, 0) << longer.output;
    std::size_t snapshots = 0;
    for (const auto& entry : fs::directory_iterator(full / "snapshots")) {
        EXPECT_EQ(read_file(entry.path()), read_file(out / "snapshots" / entry.path().filename()))
            << entry.path().filename();
        ++snapshots;
    }
    EXPECT_GE(snapshots, 4u * 8u);  // 8 snapshots of 4 formats at 20 a revolution
    EXPECT_EQ(tumble::io::read_drum_run_info(out / "drum_run.toml").revolutions, 0.4);
    EXPECT_NE(read_file(out / "summary.json"), summary);
    const auto again = tumble_run("resume " + out.string());
    EXPECT_NE(again.output.find("has finished"), std::string::npos) << again.output;
}

// A lengthened run's settings (drum_run.toml) say its new length as soon as
// it goes on, not only when it has finished: stopped on the way, the file
// says 1 revolution, and a plain resume finishes there.
TEST_F(Resume, ALengthenedRunSaysItsNewLengthWhileItRuns) {
    const fs::path out = dir_ / "lengthened";
    ASSERT_EQ(
        tumble_run(small_drum + " --revolutions 0.2 --checkpoint-every-revolutions 0.05 --out " + out.string()).exit_code,
        0);
    const int last = std::stoi(tumble::io::checkpoint_files(out).back().stem().string());
    const pid_t child = start("resume -q " + out.string() + " --revolutions 1");
    wait_for_checkpoint(out, last + 1);
    kill(child, SIGTERM);
    ASSERT_EQ(exit_code(child), 4) << "the lengthened run ended before it was stopped";
    EXPECT_EQ(tumble::io::read_drum_run_info(out / "drum_run.toml").revolutions, 1.0);
    EXPECT_FALSE(fs::exists(out / "summary.json"));
    const auto resumed = tumble_run("resume -q " + out.string());
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    EXPECT_EQ(tumble::io::read_drum_run_info(out / "drum_run.toml").revolutions, 1.0);
    EXPECT_TRUE(fs::exists(out / "summary.json"));
}

TEST_F(Resume, AnExistingRunDirectoryIsRefusedWithoutForce) {
    const fs::path out = reference();
    const auto again = tumble_run(small_drum + " --revolutions 0.2 --out " + out.string());
    EXPECT_EQ(again.exit_code, 2);
    EXPECT_NE(again.output.find("--force"), std::string::npos) << again.output;
}

}  // namespace
