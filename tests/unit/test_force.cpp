// SPDX-License-Identifier: MIT
// --force clears every file tumble writes into a run directory: each file
// that run, drum (with bands), analyze, plot and render write is on the one
// list that --force clears (io::run_files), so a new output cannot be left
// out of it unseen; and a new run into a directory that held a drum with
// bands keeps none of the drum's files.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "io/output.hpp"
#include "io/run_lock.hpp"
#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;

// 300 grains starting as two bands (the halves), 1 revolution: band
// samples, 4 particle snapshots, the band analysis with the blur of the
// start's boundary.
const std::string banded_drum = "drum -q --grains 300 --length 0.06 --omega 8 --revolutions 1 --samples 8 "
                                "--snapshots 4 --dt 3.926990816987241e-05 --no-plot";

// The files of the drum's band analysis that a scenario run does not write.
const char* const band_files[] = {"bands.json",     "bands.csv",      "band_positions.csv", "band_spectrum.csv",
                                  "band_edges.csv", "kymograph.png", "band_profile.csv"};

class Force : public tumble::test_support::ScratchTest {
protected:
    tumble::test_support::CommandResult tumble(const std::string& arguments) {
        return tumble::test_support::run_command(std::string(TUMBLE_BINARY) + " " + arguments);
    }
    fs::path box() {
        // With a smooth wall (a plate over the box), so that its drawings are written too.
        return write("box.toml", tumble::test_support::walled_box_scenario(
                                     "0.02", "",
                                     "[[wall]]\nname = \"lid\"\nshape = \"disc\"\nmaterial = \"m\"\n"
                                     "point = [0.0, 0.0, 0.05]\nradius = 0.01\n"
                                     "[output]\ntime_series_interval = 0.001\nsnapshot_interval = 0.01\n"));
    }
    static std::set<std::string> entries(const fs::path& dir) {
        std::set<std::string> names;
        for (const auto& entry : fs::directory_iterator(dir)) names.insert(entry.path().filename().string());
        return names;
    }
    // The entries of `dir` that --force would not clear.
    static std::vector<std::string> not_cleared(const fs::path& dir) {
        const auto& list = tumble::io::run_files;
        std::vector<std::string> left;
        for (const std::string& name : entries(dir))
            if (std::find(std::begin(list), std::end(list), name) == std::end(list) &&
                name != tumble::io::run_lock_file && dir / name != tumble::io::default_movie_file(dir))
                left.push_back(name);
        return left;
    }
};

TEST_F(Force, EveryFileEachCommandWritesIsOnTheListItClears) {
    const fs::path run = dir_ / "run", drum = dir_ / "drum";
    auto r = tumble("run -q " + box().string() + " --out " + run.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    r = tumble(banded_drum + " --out " + drum.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    // The analysis from the start (--first-revolution 0), so that the
    // files that need revolutions after the start-up are written too.
    for (const std::string& command :
         {"analyze --first-revolution 0 " + drum.string(), "analyze --so-far " + drum.string(), "plot " + drum.string(),
          "render -q --width 16 " + drum.string(), "render -q --width 16 " + run.string(),
          "fields -q --average xyz " + run.string()}) {
        r = tumble(command);
        ASSERT_EQ(r.exit_code, 0) << command << ": " << r.output;
    }
    EXPECT_EQ(not_cleared(run), std::vector<std::string>{});
    EXPECT_EQ(not_cleared(drum), std::vector<std::string>{});
    // And the list holds nothing else: every name on it was written here.
    for (std::string_view name : tumble::io::run_files)
        EXPECT_TRUE(fs::exists(run / name) || fs::exists(drum / name)) << name;
    EXPECT_TRUE(fs::exists(tumble::io::default_movie_file(drum)));
    EXPECT_TRUE(fs::exists(tumble::io::default_movie_file(run)));

    // --force clears them all: a run into each directory leaves what a run
    // into a new one leaves.
    for (const fs::path& dir : {run, drum}) {
        r = tumble("run -q --force " + box().string() + " --out " + dir.string());
        ASSERT_EQ(r.exit_code, 0) << r.output;
    }
    const fs::path fresh = dir_ / "fresh";
    r = tumble("run -q " + box().string() + " --out " + fresh.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(entries(run), entries(fresh));
    EXPECT_EQ(entries(drum), entries(fresh));
}

TEST_F(Force, ARunIntoADrumsDirectoryKeepsNoneOfItsBandFiles) {
    const fs::path dir = dir_ / "out";
    auto r = tumble(banded_drum + " --out " + dir.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const char* name : band_files) ASSERT_TRUE(fs::exists(dir / name)) << name;
    r = tumble("run -q --force " + box().string() + " --out " + dir.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const char* name : band_files) EXPECT_FALSE(fs::exists(dir / name)) << name;
}

TEST_F(Force, ADrumStoppedAfterForceKeepsNoEarlierBandsJson) {
    // Stopped early with a checkpoint, as a kill would stop it: what is left
    // is this run's, none of the earlier run's results.
    const fs::path dir = dir_ / "out";
    auto r = tumble(banded_drum + " --out " + dir.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    ASSERT_TRUE(fs::exists(dir / "bands.json"));
    r = tumble(banded_drum + " --force --stop-at-step 100 --out " + dir.string());
    ASSERT_EQ(r.exit_code, 4) << r.output;
    for (const char* name : {"bands.json", "bands.csv", "kymograph.png", "summary.json", "summary.txt"})
        EXPECT_FALSE(fs::exists(dir / name)) << name;
}

}  // namespace
