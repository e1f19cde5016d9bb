// SPDX-License-Identifier: MIT
// `mpirun -np N tumble run` (one simulation shared among the ranks,
// sim/slabs.hpp) end to end: it runs, the same ranks give the same bytes,
// it stops with a checkpoint per rank and resumes on as many ranks bitwise,
// and the wrong rank count is refused with the way out. Skipped without
// mpirun or without MPI in this build.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "test_support.hpp"
#include "tumble/core/mpi.hpp"

namespace {

namespace fs = std::filesystem;
using tumble::test_support::read_file;
using tumble::test_support::run_command;

class MpiRun : public tumble::test_support::ScratchTest {
protected:
    void SetUp() override {
        ScratchTest::SetUp();
        if (run_command("mpirun --version").exit_code != 0) GTEST_SKIP() << "no mpirun";
        if (!tumble::mpi::built_with_mpi()) GTEST_SKIP() << "built without MPI (TUMBLE_MPI=OFF)";
        // The demonstration tray of examples/demo.toml, 0.1 s (3,940 steps:
        // grains pour, collide and settle), no snapshots.
        std::string text = read_file(std::string(TUMBLE_SOURCE_DIR) + "/examples/demo.toml");
        text.replace(text.find("duration = 0.5 "), 15, "duration = 0.1 ");
        text.replace(text.find("snapshot_interval = 0.05 "), 25, "snapshot_interval = 0.0  ");
        scenario_ = write("demo.toml", text).string();
    }
    std::string mpirun(int ranks, const std::string& args) {
        return "OMP_NUM_THREADS=1 mpirun --allow-run-as-root --oversubscribe -np " + std::to_string(ranks) + " " +
               TUMBLE_BINARY + " " + args;
    }
    std::string scenario_;
};

TEST_F(MpiRun, TwoRanksRunStopAndResumeBitwise) {
    const fs::path a = dir_ / "a", b = dir_ / "b", stopped = dir_ / "stopped";
    auto r = run_command(mpirun(2, "run " + scenario_ + " -o " + a.string()));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("shared among 2 MPI ranks"), std::string::npos) << r.output;
    // Where the time went, told once (by rank 0), with the ranks' spread and the exchange between them.
    EXPECT_NE(r.output.find("time by phase of the run (this process: since its start or resume):"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("steps on 2 ranks"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("\n  exchange "), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(a / "run.json"));
    EXPECT_TRUE(fs::exists(a / "checkpoints" / "000002.r1.tck"));  // the final checkpoint, one file per rank
    // The same ranks, the same bytes.
    ASSERT_EQ(run_command(mpirun(2, "run -q " + scenario_ + " -o " + b.string())).exit_code, 0);
    EXPECT_EQ(read_file(a / "time_series.csv"), read_file(b / "time_series.csv"));
    // Stopped at step 1000 (exit 4), resumed on 2 ranks: the uninterrupted run's series, bit for bit.
    r = run_command(mpirun(2, "run -q " + scenario_ + " -o " + stopped.string() + " --stop-at-step 1000"));
    ASSERT_EQ(r.exit_code, 4) << r.output;
    ASSERT_TRUE(fs::exists(stopped / "checkpoints" / "000001.r0.tck"));
    ASSERT_TRUE(fs::exists(stopped / "checkpoints" / "000001.r1.tck"));
    r = run_command(mpirun(2, "resume " + stopped.string()));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(read_file(a / "time_series.csv"), read_file(stopped / "time_series.csv"));
}

// A run stopped on one process goes on on 2 ranks (each keeps its slab of
// the one checkpoint): the series up to the stop is the same, the rest
// differs from the one-process run only by round-off grown in the flow;
// from then on the run is one of 2 ranks.
TEST_F(MpiRun, OneProcessRunGoesOnOnTwoRanks) {
    const fs::path whole = dir_ / "whole", moved = dir_ / "moved";
    ASSERT_EQ(run_command(std::string(TUMBLE_BINARY) + " run -q " + scenario_ + " -o " + whole.string()).exit_code, 0);
    auto r = run_command(std::string(TUMBLE_BINARY) + " run -q " + scenario_ + " -o " + moved.string() +
                         " --stop-at-step 1000");
    ASSERT_EQ(r.exit_code, 4) << r.output;
    r = run_command(mpirun(2, "resume -q " + moved.string()));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const std::string a = read_file(whole / "time_series.csv"), b = read_file(moved / "time_series.csv");
    const std::size_t rows_to_stop = 1 + 1000 / 197 + 1;  // header, samples every 197 steps up to step 1000
    std::size_t at = 0;
    for (std::size_t k = 0; k < rows_to_stop; ++k) at = a.find('\n', at) + 1;
    EXPECT_EQ(a.substr(0, at), b.substr(0, at));
    EXPECT_EQ(std::count(a.begin(), a.end(), '\n'), std::count(b.begin(), b.end(), '\n'));
    // Numbered on from the one process's 000001.tck: the names sort in the order of the moments.
    EXPECT_TRUE(fs::exists(moved / "checkpoints" / "000001.tck"));
    EXPECT_TRUE(fs::exists(moved / "checkpoints" / "000002.r1.tck"));
    r = run_command(std::string(TUMBLE_BINARY) + " resume " + moved.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("has finished"), std::string::npos) << r.output;
}

// A run of 2 ranks goes on on one process and on 3 ranks: every rank reads
// every rank's file (the whole state, whole_state()) and keeps its part.
// The series up to the stop is the same; the ranks' files of the
// continuation are numbered as one.
TEST_F(MpiRun, TwoRankRunGoesOnOnOneProcessAndOnThreeRanks) {
    const fs::path whole = dir_ / "whole";
    ASSERT_EQ(run_command(mpirun(2, "run -q " + scenario_ + " -o " + whole.string())).exit_code, 0);
    const std::string a = read_file(whole / "time_series.csv");
    for (int ranks : {1, 3}) {
        const fs::path dir = dir_ / ("on" + std::to_string(ranks));
        auto r = run_command(mpirun(2, "run -q " + scenario_ + " -o " + dir.string() + " --stop-at-step 1000"));
        ASSERT_EQ(r.exit_code, 4) << r.output;
        r = run_command(ranks == 1 ? std::string(TUMBLE_BINARY) + " resume -q " + dir.string()
                                   : mpirun(ranks, "resume -q " + dir.string()));
        ASSERT_EQ(r.exit_code, 0) << ranks << " ranks: " << r.output;
        const std::string b = read_file(dir / "time_series.csv");
        const std::size_t rows_to_stop = 1 + 1000 / 197 + 1;
        std::size_t at = 0;
        for (std::size_t k = 0; k < rows_to_stop; ++k) at = a.find('\n', at) + 1;
        EXPECT_EQ(a.substr(0, at), b.substr(0, at)) << ranks << " ranks";
        EXPECT_EQ(std::count(a.begin(), a.end(), '\n'), std::count(b.begin(), b.end(), '\n')) << ranks << " ranks";
        if (ranks == 3) {
            EXPECT_TRUE(fs::exists(dir / "checkpoints" / "000003.r2.tck"));  // numbered on from the 2 ranks' 000001
            EXPECT_FALSE(fs::exists(dir / "checkpoints" / "000001.r2.tck"));
        } else {
            EXPECT_TRUE(fs::exists(dir / "checkpoints" / "000002.tck"));  // a run of one process from then on
        }
        // On one process the 2 ranks' stop checkpoint (000001.rR.tck,
        // unfinished) is still there, older than the continuation's end
        // (on 3 ranks, ranks 0 and 1 have pruned theirs): resumed again, on one
        // process or on 2 ranks, the run has finished (until 2026-12-02 the
        // ranks' files were taken over a newer one-process file, and the run
        // went back to step 1000, cutting its series back).
        if (ranks == 1) {
            ASSERT_TRUE(fs::exists(dir / "checkpoints" / "000001.r0.tck"));
        }
        for (int again : {1, 2}) {
            r = run_command(again == 1 ? std::string(TUMBLE_BINARY) + " resume " + dir.string()
                                       : mpirun(again, "resume " + dir.string()));
            ASSERT_EQ(r.exit_code, 0) << r.output;
            EXPECT_NE(r.output.find("has finished"), std::string::npos) << ranks << " then " << again << ": " << r.output;
        }
        EXPECT_EQ(read_file(dir / "time_series.csv"), b) << ranks << " ranks";
    }
}

// Snapshots of a shared run are gathered on rank 0 into the files a run on
// one process writes (io/snapshot_data.hpp): at step 0, before the runs part
// ways by round-off, the same bytes in all four formats; afterwards the same
// files, one per snapshot, and the ParaView indexes.
TEST_F(MpiRun, SnapshotsAreTheFilesOfOneProcess) {
    std::string text = read_file(scenario_);
    text.replace(text.find("snapshot_interval = 0.0  "), 25, "snapshot_interval = 0.05 ");
    const std::string file = write("snap.toml", text).string();
    const fs::path one = dir_ / "one", two = dir_ / "two";
    ASSERT_EQ(run_command(std::string(TUMBLE_BINARY) + " run -q " + file + " -o " + one.string()).exit_code, 0);
    const auto r = run_command(mpirun(2, "run -q " + file + " -o " + two.string()));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const char* name : {"000000.csv", "000000.vtu", "000000.vtp", "000000.xyz"})
        EXPECT_EQ(read_file(one / "snapshots" / name), read_file(two / "snapshots" / name)) << name;
    for (const char* name : {"000002.csv", "000002.vtu", "000002.vtp", "000002.xyz"})
        EXPECT_TRUE(fs::exists(two / "snapshots" / name)) << name;
    EXPECT_EQ(read_file(one / "particles.pvd"), read_file(two / "particles.pvd"));
    EXPECT_EQ(read_file(one / "contacts.pvd"), read_file(two / "contacts.pvd"));
}

// tumble drum on 2 ranks: rank 0 measures the gathered spheres and writes
// every series; stopped in the rotation and resumed on 2 ranks it writes
// the uninterrupted run's series bit for bit (the band profile included).
TEST_F(MpiRun, DrumOnTwoRanksStopsAndResumesBitwise) {
    const std::string drum = "drum -q --grains 300 --length 0.12 --revolutions 0.5 --no-plot --threads 1 -o ";
    const fs::path whole = dir_ / "whole", stopped = dir_ / "stopped";
    auto r = run_command(mpirun(2, drum + whole.string()));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    r = run_command(mpirun(2, drum + stopped.string() + " --stop-at-step 9000"));  // settled by step ~6,400
    ASSERT_EQ(r.exit_code, 4) << r.output;
    r = run_command(mpirun(2, "resume -q " + stopped.string()));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const char* name : {"drum_series.csv", "profiles.csv", "band_profile.csv", "time_series.csv", "bands.csv"})
        EXPECT_EQ(read_file(whole / name), read_file(stopped / name)) << name;
    EXPECT_TRUE(fs::exists(whole / "summary.json"));
}

// The ranks' files must be of one moment of one run: rank 1's newest file
// replaced by its previous one, or by rank 0's file of the same number, is
// refused at once (exit 2, no hang) with the files and what differs; a
// damaged newest file of one rank takes both ranks back to their previous
// checkpoint.
TEST_F(MpiRun, RanksFilesOfDifferentMomentsAreRefused) {
    const fs::path dir = dir_ / "mixed", cp = dir / "checkpoints";
    auto r = run_command(mpirun(2, "run -q " + scenario_ + " -o " + dir.string() +
                                       " --checkpoint-every-steps 400 --stop-at-step 1000"));
    ASSERT_EQ(r.exit_code, 4) << r.output;
    // Kept: 000002 (step 800) and 000003 (step 1000) of each rank.
    ASSERT_TRUE(fs::exists(cp / "000002.r1.tck") && fs::exists(cp / "000003.r1.tck")) << r.output;
    const fs::path backup = dir_ / "000003.r1.tck";
    fs::copy_file(cp / "000003.r1.tck", backup);
    // Bounded: before the ranks compared their files this spun or aborted.
    const std::string resume = "timeout 120 env " + mpirun(2, "resume -q " + dir.string());

    fs::copy_file(cp / "000002.r1.tck", cp / "000003.r1.tck", fs::copy_options::overwrite_existing);
    r = run_command(resume);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find((cp / "000003.r1.tck").string() + ": step 800"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("rank 0's 000003.r0.tck step 1000"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("the ranks' files are of different moments"), std::string::npos) << r.output;

    fs::copy_file(cp / "000003.r0.tck", cp / "000003.r1.tck", fs::copy_options::overwrite_existing);
    r = run_command(resume);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find((cp / "000003.r1.tck").string() + ": record key \"rank\" is 0"), std::string::npos)
        << r.output;

    // Damaged (cut short): both ranks go on from 000002, with a warning.
    fs::copy_file(backup, cp / "000003.r1.tck", fs::copy_options::overwrite_existing);
    fs::resize_file(cp / "000003.r1.tck", fs::file_size(backup) / 2);
    r = run_command("timeout 300 env " + mpirun(2, "resume " + dir.string()));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find((cp / "000003.r0.tck").string() + ": not every rank has an intact checkpoint"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("from " + (cp / "000002.r0.tck").string()), std::string::npos) << r.output;
}

}  // namespace
