// SPDX-License-Identifier: MIT
// The band analysis end to end (docs/BAND-ANALYSIS.md): a small two-component drum
// writes band_profile.csv during the rotation, and its analysis the band
// counts (bands.csv, bands.json, summary.json) and the kymograph;
// `tumble analyze` recomputes them byte for byte; a bad --band-bins is
// refused before any work.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>

#include "io/band_output.hpp"
#include "io/csv_table.hpp"
#include "io/json.hpp"
#include "io/png.hpp"
#include "io/run_lock.hpp"
#include "io/snapshots.hpp"
#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;
using tumble::test_support::read_file;

tumble::test_support::CommandResult tumble_run(const std::string& arguments) {
    return tumble::test_support::run_command(std::string(TUMBLE_BINARY) + " " + arguments);
}

class BandRun : public tumble::test_support::ScratchTest {};

TEST_F(BandRun, SmallDrumWritesTheKymographAndBandCounts) {
    // 300 grains in a drum 6 cm long (15 band bins of 4 mm), 1 revolution at
    // 8 rad/s, 8 samples per revolution, a step of 1/20000 revolution (just
    // below the automatic one): band samples at N = 0, 0.25, 0.5, 0.75 and 1,
    // the end of the run falling on a band sample, written once.
    const fs::path out = dir_ / "drum";
    const auto r = tumble_run("drum -q --grains 300 --length 0.06 --omega 8 --revolutions 1 --samples 8 "
                              "--dt 3.926990816987241e-05 --snapshots 0 --no-plot --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const tumble::io::DrumRunInfo info = tumble::io::read_drum_run_info(out / "drum_run.toml");
    EXPECT_EQ(info.band_bins, 15);
    const tumble::io::BandRecord record = tumble::io::read_band_profile(out / "band_profile.csv", info);
    const std::size_t samples = record.field.revolutions.size();
    ASSERT_EQ(samples, 5u);
    for (std::size_t k = 0; k < samples; ++k) EXPECT_NEAR(record.field.revolutions[k], 0.25 * k, 1e-9);
    double grains = 0.0;
    for (double n : record.field.grains.back()) grains += n;
    EXPECT_DOUBLE_EQ(grains, 300.0);

    // The halves start as two bands: material-1 (large) left, material-2 right.
    const tumble::io::CsvTable bands = tumble::io::read_csv_table(out / "bands.csv");
    ASSERT_EQ(bands.rows.size(), samples);
    EXPECT_EQ(bands.numbers("bands").front(), 2.0);
    EXPECT_EQ(bands.numbers("left_end_rich").front(), 0.0);
    EXPECT_EQ(bands.numbers("right_end_rich").front(), 1.0);
    const tumble::io::Json summary = tumble::io::parse_json(read_file(out / "summary.json"));
    ASSERT_TRUE(summary.contains("bands"));
    EXPECT_EQ(summary["bands"]["samples"], samples);
    // The halves start's two halves only mix: no bands beyond the start's,
    // so the run's summary has no band lines and plot no band figure (the
    // band files are written all the same); tumble analyze --band-report
    // prints them.
    EXPECT_FALSE(summary["bands"]["reported"].get<bool>());
    EXPECT_EQ(read_file(out / "summary.txt").find("bands of"), std::string::npos);
    const auto report = tumble_run("analyze --band-report " + out.string());
    ASSERT_EQ(report.exit_code, 0) << report.output;
    EXPECT_NE(report.output.find("bands of material-2"), std::string::npos) << report.output;
    EXPECT_TRUE(tumble::io::parse_json(read_file(out / "summary.json"))["bands"]["reported"].get<bool>());
    // One revolution is one block of the end layers, too short for an
    // interval: summary.txt says so instead of printing NaN bounds.
    const std::string text = read_file(out / "summary.txt");
    const std::size_t layers = text.find("end layers");
    ASSERT_NE(layers, std::string::npos) << text;
    const std::string line = text.substr(layers, text.find('\n', layers) - layers);
    EXPECT_NE(line.find("no interval: fewer than 3 independent revolutions"), std::string::npos) << line;
    EXPECT_EQ(line.find("nan"), std::string::npos) << line;
    // Nor anywhere else: the run is too short for the profile collapse
    // (no profile at N >= 1 after the start-up) and for the blur of the
    // start's boundary (no block of 10 revolutions): each says why.
    EXPECT_FALSE(std::regex_search(text, std::regex("\\bnan\\b"))) << text;
    EXPECT_NE(text.find("blur of the start's 1 boundary"), std::string::npos) << text;
    EXPECT_NE(text.find("not measured (no block of 10 revolutions"), std::string::npos) << text;
    // (The last profile is at N = 0.9999999999999997: steps x dt, below 1.)
    EXPECT_NE(text.find("no comparison: no profile at N >= 1\n"), std::string::npos) << text;
    EXPECT_TRUE(summary["profile_collapse"]["rms"].is_null());
    EXPECT_EQ(summary["bands"]["species"], "material-2");
    EXPECT_EQ(summary["bands"]["initial"]["bands"], 2);
    EXPECT_NE(read_file(out / "summary.txt").find("bands of material-2"), std::string::npos);
    const tumble::io::render::Image kymograph = tumble::io::read_png(out / "kymograph.png");
    EXPECT_EQ(kymograph.width(), 15 * 32);  // 32 pixels per bin (at least 480 wide)
    const int rows = static_cast<int>(samples);
    EXPECT_EQ(kymograph.height(), rows * ((320 + rows - 1) / rows));  // whole pixels per sample, at least 320 tall

    // tumble analyze: the same files again.
    EXPECT_EQ(tumble::io::read_csv_table(out / "band_spectrum.csv").rows.size(), samples);
    const std::string json = read_file(out / "bands.json"), csv = read_file(out / "bands.csv");
    fs::remove(out / "bands.json");
    fs::remove(out / "kymograph.png");
    const auto again = tumble_run("analyze --band-report " + out.string());
    ASSERT_EQ(again.exit_code, 0) << again.output;
    EXPECT_EQ(read_file(out / "bands.json"), json);
    EXPECT_EQ(read_file(out / "bands.csv"), csv);
    EXPECT_TRUE(fs::exists(out / "kymograph.png"));

    // The radial core about the bed's centre, per block of revolutions.
    EXPECT_NE(read_file(out / "band_profile.csv").find(",bed_periphery_fraction,"), std::string::npos);
    EXPECT_EQ(summary["bands"]["radial_core"]["reference"], "bed centroid");
    EXPECT_EQ(summary["bands"]["radial_core"]["blocks"].size(), 2u);  // [0, 1) and [1, 2): the end, N = 1
    EXPECT_EQ(bands.numbers("periphery_fraction").size(), samples);

    // Thresholds from the command line, recorded.
    const auto loose = tumble_run("analyze --band-z-enter 3 --band-min-contrast 0.04 --band-min-width 3 " + out.string());
    ASSERT_EQ(loose.exit_code, 0) << loose.output;
    const tumble::io::Json thresholds = tumble::io::parse_json(read_file(out / "bands.json"))["thresholds"];
    EXPECT_EQ(thresholds["z_enter"], 3.0);
    EXPECT_EQ(thresholds["min_contrast"], 0.04);
    EXPECT_EQ(thresholds["min_width_bins"], 3);
    EXPECT_EQ(thresholds["z_leave"], 2.0);

    // A band_profile.csv begun by a tumble before the radial core about the
    // bed's centre (rows core_fraction and wall_fraction, from the axis) and
    // continued by this one: read, those samples' core left out, and said.
    std::string old = read_file(out / "band_profile.csv");
    for (int k = 0; k < 2; ++k)
        for (auto [from, to] : {std::pair{",bed_core_fraction,", ",core_fraction,"},
                                std::pair{",bed_periphery_fraction,", ",wall_fraction,"}})
            old.replace(old.find(from), std::string(from).size(), to);
    write("drum/band_profile.csv", old);
    const auto mixed = tumble_run("analyze --band-report " + out.string());
    ASSERT_EQ(mixed.exit_code, 0) << mixed.output;
    EXPECT_NE(mixed.output.find("2 of the " + std::to_string(samples) + " samples of band_profile.csv were measured "
                                "from the drum axis"),
              std::string::npos)
        << mixed.output;
    const std::vector<double> core = tumble::io::read_csv_table(out / "bands.csv").numbers("core_fraction");
    EXPECT_TRUE(std::isnan(core[0]) && std::isnan(core[1]) && std::isfinite(core[2]));
}

TEST_F(BandRun, BadBandThresholdsAreRefusedNamingTheOption) {
    // Before any work: the directory is not even looked at.
    const auto r = tumble_run("analyze --band-z-leave 5 " + (dir_ / "none").string());
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.output.find("--band-z-leave must lie in 0 .. --band-z-enter (4), got 5"), std::string::npos) << r.output;
    const auto width = tumble_run("analyze --so-far --band-min-width 0 " + (dir_ / "none").string());
    EXPECT_NE(width.exit_code, 0);
    EXPECT_NE(width.output.find("--band-min-width must be at least 1"), std::string::npos) << width.output;
}

// A run stopped part way (a long band study, paused): tumble
// analyze refuses it, --so-far analyses its bands so far into DIR/so_far/
// and leaves the run's files alone, also while the run goes on, and the run
// then resumes.
TEST_F(BandRun, SoFarAnalysesAStoppedRunWithoutFinishingIt) {
    const fs::path out = dir_ / "stopped";
    const auto r = tumble_run("drum -q --grains 300 --length 0.06 --omega 8 --revolutions 1 --samples 8 --snapshots 4 "
                              "--arrangement bands --bands 3 --ends small --no-plot --stop-at-step 24700 --out " +
                              out.string());
    ASSERT_EQ(r.exit_code, 4) << r.output;  // stopped with a checkpoint
    EXPECT_NE(tumble_run("analyze " + out.string()).exit_code, 0);
    const auto so_far = tumble_run("analyze --so-far " + out.string());
    ASSERT_EQ(so_far.exit_code, 0) << so_far.output;
    EXPECT_FALSE(fs::exists(out / "summary.json"));
    EXPECT_FALSE(fs::exists(out / "bands.json"));
    const tumble::io::Json bands = tumble::io::parse_json(read_file(out / "so_far" / "bands.json"));
    ASSERT_GE(bands["samples"].get<int>(), 1) << so_far.output;  // at least the start of the rotation
    EXPECT_EQ(bands["initial"]["bands"], 3);  // small, large, small
    EXPECT_TRUE(fs::exists(out / "so_far" / "kymograph.png"));
    EXPECT_NE(read_file(out / "so_far" / "summary.txt").find("bands of material-2"), std::string::npos);
    // The small grains crossing the middle band of large ones, from the
    // snapshots so far (too few crossings in a revolution to determine D).
    EXPECT_GT(bands["crossing"]["band_revolutions"].get<double>(), 0.0) << so_far.output;
    EXPECT_FALSE(bands["crossing"]["determined"].get<bool>());
    EXPECT_FALSE(bands["crossing"].contains("msd"));

    // While the run goes on (its lock held, as the running process holds
    // it), with a band sample and a snapshot half written: --so-far reads
    // what is whole and says what it left out.
    {
        const tumble::io::RunLock running(out);
        const std::string profile = read_file(out / "band_profile.csv");
        const std::vector<fs::path> snapshots = tumble::io::list_snapshot_csv(out);
        ASSERT_FALSE(snapshots.empty());
        const fs::path half = out / "snapshots" / "999999.csv";
        {
            // One whole row of a new sample (a copy of the first) and the
            // start of its second.
            const std::size_t row1 = profile.find('\n') + 1, row2 = profile.find('\n', row1) + 1;
            std::ofstream(out / "band_profile.csv", std::ios::app)
                << profile.substr(row1, row2 - row1) << profile.substr(row2, 10);
            std::ofstream(half) << read_file(snapshots.back()).substr(0, 300);
        }
        EXPECT_NE(tumble_run("analyze " + out.string()).exit_code, 0);  // in use
        const auto live = tumble_run("analyze --so-far " + out.string());
        ASSERT_EQ(live.exit_code, 0) << live.output;
        EXPECT_NE(live.output.find("the run is going on: its newest snapshot and band sample"), std::string::npos)
            << live.output;
        const tumble::io::Json again = tumble::io::parse_json(read_file(out / "so_far" / "bands.json"));
        EXPECT_EQ(again["samples"], bands["samples"]);
        EXPECT_EQ(again["crossing"]["band_revolutions"], bands["crossing"]["band_revolutions"]);
        std::ofstream(out / "band_profile.csv", std::ios::trunc) << profile;  // as the run left it
        fs::remove(half);
    }
    const auto resumed = tumble_run("resume -q " + out.string());
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    EXPECT_TRUE(fs::exists(out / "summary.json"));
    const tumble::io::Json crossing = tumble::io::parse_json(read_file(out / "summary.json"))["bands"]["crossing"];
    EXPECT_GT(crossing["band_revolutions"].get<double>(), 0.5);  // four snapshots a revolution, the band there throughout
    EXPECT_TRUE(crossing["msd"].contains("D"));  // with the MSD's D to compare (null: too short to fit)
    EXPECT_NE(read_file(out / "summary.txt").find("crossing of the inner material-1 bands by material-2"),
              std::string::npos);
    // A band start has no side of the drum per component: <z>(0) unmirrored,
    // not "started at z > 0" (the halves' wording).
    EXPECT_EQ(read_file(out / "summary.txt").find("started at z"), std::string::npos);
    EXPECT_NE(read_file(out / "summary.txt").find("material-2 ("), std::string::npos);
    EXPECT_NE(read_file(out / "summary.txt").find(" grains, bands start): <z>(0) = "), std::string::npos);

    // What the snapshots cover: here the whole rotation. A run continued
    // from a kept checkpoint elsewhere lacks its early snapshots; analyze
    // then says that everything measured from them covers the later
    // revolutions only (BANDS.md, "Files written by the analysis").
    const tumble::io::Json all = tumble::io::parse_json(read_file(out / "summary.json"))["snapshots"];
    // N = 0, 0.25, 0.5, 0.75 and 1 (the run's last step falls on N = 1).
    EXPECT_EQ(all["count"], 5);
    EXPECT_TRUE(all["from_start"].get<bool>());
    EXPECT_NE(read_file(out / "summary.txt").find("particle snapshots of the rotation: 5, N = 0 to 1 (every "
                                                  "0.25 revolutions)\n"),
              std::string::npos);
    const std::vector<fs::path> files = tumble::io::list_snapshot_csv(out);
    ASSERT_GE(files.size(), 2u);
    fs::remove(files[0]);
    fs::remove(files[1]);
    const auto later = tumble_run("analyze " + out.string());
    ASSERT_EQ(later.exit_code, 0) << later.output;
    const tumble::io::Json part = tumble::io::parse_json(read_file(out / "summary.json"));
    EXPECT_EQ(part["snapshots"]["count"], 3);
    EXPECT_FALSE(part["snapshots"]["from_start"].get<bool>());
    EXPECT_NEAR(part["snapshots"]["first_revolution"].get<double>(), 0.5, 1e-4);
    EXPECT_NE(later.output.find("those before N = 0.5 are missing"), std::string::npos) << later.output;
    EXPECT_NE(later.output.find("covers N >= 0.5 only"), std::string::npos) << later.output;
    EXPECT_LT(part["bands"]["crossing"]["band_revolutions"].get<double>(),
              crossing["band_revolutions"].get<double>());
}

TEST_F(BandRun, UntilBandChangeEndsTheRunOnceTheCountHasHeld) {
    // Four prepared bands in the small drum lose their middle bands within
    // two revolutions of 4 (bands.csv: 4, then 2 from N = 0.75, then none).
    // With --until-band-change 1 the run must end at the first band sample
    // (every 1/4 revolution) at which its count has differed from the
    // start's for a whole revolution, and be finished there; stopped on the
    // way and resumed, the same files.
    const std::string drum = "drum -q --grains 300 --length 0.06 --omega 8 --revolutions 4 --samples 8 "
                             "--dt 3.926990816987241e-05 --snapshots 0 --no-plot --arrangement bands --bands 4 "
                             "--until-band-change 1 --out ";
    const fs::path out = dir_ / "until", stopped = dir_ / "stopped";
    const auto r = tumble_run(drum + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const tumble::io::CsvTable bands = tumble::io::read_csv_table(out / "bands.csv");
    const std::vector<double> N = bands.numbers("revolutions"), count = bands.numbers("bands");
    ASSERT_GE(N.size(), 3u);
    std::size_t k = N.size();  // the samples from k on differ from the start's count
    while (k > 1 && count[k - 1] != count.front()) --k;
    ASSERT_LT(k, N.size()) << "the run ended with the start's band count";
    const double since = N[k], end = N.back();
    EXPECT_GE(end - since, 1.0 - 1e-9);
    EXPECT_LT(end - since, 1.25 - 1e-9);  // not a band sample later than needed
    EXPECT_LT(end, 3.5);                  // ended early
    const tumble::io::Json summary = tumble::io::parse_json(read_file(out / "summary.json"));
    EXPECT_NEAR(summary["revolutions"].get<double>(), end, 1e-9);
    EXPECT_EQ(summary["revolutions_asked"].get<double>(), 4.0);
    const tumble::io::Json& until = summary["until_band_change"];
    EXPECT_TRUE(until["ended"].get<bool>());
    EXPECT_NEAR(until["since"].get<double>(), since, 1e-9);
    EXPECT_EQ(until["bands_at_start"].get<double>(), count.front());
    EXPECT_EQ(until["bands_at_end"].get<double>(), count.back());
    EXPECT_NE(read_file(out / "summary.txt").find("ended early (--until-band-change 1)"), std::string::npos);
    const auto again = tumble_run("resume " + out.string());
    ASSERT_EQ(again.exit_code, 0) << again.output;
    EXPECT_NE(again.output.find("nothing to do"), std::string::npos) << again.output;

    // Stopped near N = 1 (settling takes about 10,000 steps, a revolution
    // 20,000) and resumed: the samples before the stop are read back and the
    // run ends where the uninterrupted one did.
    ASSERT_EQ(tumble_run(drum + stopped.string() + " --stop-at-step 30000").exit_code, 4);
    const auto resumed = tumble_run("resume -q " + stopped.string());
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    EXPECT_EQ(read_file(stopped / "bands.csv"), read_file(out / "bands.csv"));
    EXPECT_EQ(read_file(stopped / "drum_series.csv"), read_file(out / "drum_series.csv"));
}

TEST_F(BandRun, AWatchedRunThatDidNotEndEarlyReportsNoCountsOfAChange) {
    // The small drum of the test above keeps its four bands until N = 0.75:
    // stopped at 0.5, the watch never ends it, and the run turns all it was
    // asked. summary.json's until_band_change must then not
    // report band counts the watch never recorded (it said 0 and 0 for
    // runs that kept their bands); the run's counts are bands.initial and
    // bands.final.
    const fs::path out = dir_ / "kept";
    const auto r = tumble_run("drum -q --grains 300 --length 0.06 --omega 8 --revolutions 0.5 --samples 8 "
                              "--dt 3.926990816987241e-05 --snapshots 0 --no-plot --arrangement bands --bands 4 "
                              "--until-band-change 0.25 --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const tumble::io::Json summary = tumble::io::parse_json(read_file(out / "summary.json"));
    const tumble::io::Json& until = summary["until_band_change"];
    EXPECT_FALSE(until["ended"].get<bool>());
    EXPECT_TRUE(until["since"].is_null());
    EXPECT_TRUE(until["bands_at_start"].is_null());
    EXPECT_TRUE(until["bands_at_end"].is_null());
    EXPECT_EQ(summary["bands"]["initial"]["bands"].get<double>(), 4.0);  // the prepared start, as the analysis counts it
    EXPECT_EQ(read_file(out / "summary.txt").find("ended early"), std::string::npos);
}

TEST_F(BandRun, BadUntilBandChangeIsRefusedNamingIt) {
    for (const std::string value : {"-1", "12", "nan"}) {
        const auto r = tumble_run("drum -q --revolutions 12 --until-band-change " + value + " --out " +
                                  (dir_ / "never").string());
        EXPECT_NE(r.exit_code, 0) << value;
        EXPECT_NE(r.output.find("until_band_change"), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(dir_ / "never"));
    }
}

TEST_F(BandRun, BadBandBinsIsRefusedBeforeAnyWork) {
    const auto r = tumble_run("drum -q --band-bins 1 --out " + (dir_ / "never").string());
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.output.find("band_bins"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "never"));
}

}  // namespace
