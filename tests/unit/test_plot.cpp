// SPDX-License-Identifier: MIT
// tools/plot_drum.py, the paper's figures from drum output: on a tiny real run
// directory, on a synthetic sweep table, and on bad input (exit code 2 naming
// the file). Skipped where no python3 with numpy and matplotlib is found.
#include <gtest/gtest.h>

#include "test_support.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using Result = tumble::test_support::CommandResult;
using tumble::test_support::run_command;

std::string quoted(const fs::path& p) {
    std::string q(1, '\'');
    q += p.string();
    q += '\'';
    return q;
}

// A python3 with numpy and matplotlib: the one on PATH, else the system one.
std::string find_python() {
    for (const std::string candidate : {"python3", "/usr/bin/python3"}) {
        if (run_command(candidate + " -c 'import numpy, matplotlib'").exit_code == 0)
            return candidate;
    }
    return "";
}

const fs::path script = fs::path(TUMBLE_SOURCE_DIR) / "tools" / "plot_drum.py";

Result plot(const std::string& python, const std::string& arguments) {
    return run_command(python + " " + quoted(script) + " " + arguments);
}

void expect_figure(const fs::path& dir, const std::string& name) {
    const fs::path png = dir / (name + ".png");
    const fs::path svg = dir / (name + ".svg");
    ASSERT_TRUE(fs::exists(png)) << png;
    ASSERT_TRUE(fs::exists(svg)) << svg;
    EXPECT_GT(fs::file_size(png), 5000u) << png;
    EXPECT_GT(fs::file_size(svg), 5000u) << svg;
    std::ifstream in(png, std::ios::binary);
    char signature[8] = {};
    in.read(signature, 8);
    EXPECT_EQ(std::string(signature, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << png;
    std::ifstream svg_in(svg);
    std::stringstream text;
    text << svg_in.rdbuf();
    EXPECT_NE(text.str().find("<svg"), std::string::npos) << svg;
}

class Plot : public ::testing::Test {
protected:
    void SetUp() override {
        python_ = find_python();
        if (python_.empty()) GTEST_SKIP() << "no python3 with numpy and matplotlib";
        dir_ = fs::temp_directory_path() / ("tumble_test_plot_" + std::to_string(::getpid()) +
                                            "_" + ::testing::UnitTest::GetInstance()
                                                      ->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        if (!dir_.empty()) fs::remove_all(dir_);
    }
    std::string python_;
    fs::path dir_;
};

TEST_F(Plot, RunDirectoryGivesTheRunFigures) {
    const fs::path run = dir_ / "run";
    const Result drum = run_command(std::string(TUMBLE_BINARY) +
                                    " drum --grains 150 --omega 8 --revolutions 0.25"
                                    " --samples 20 --snapshots 12 -q --out " + quoted(run));
    ASSERT_EQ(drum.exit_code, 0) << drum.output;

    const fs::path figures = dir_ / "figures";
    const Result result = plot(python_, "run " + quoted(run) + " --out " + quoted(figures));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    for (const char* name : {"fig1_setup", "fig_z", "fig_profiles", "fig_energy", "fig_depth"}) {
        expect_figure(figures, name);
        EXPECT_NE(result.output.find((figures / (std::string(name) + ".png")).string()),
                  std::string::npos) << "the list of files written names " << name;
    }
    // A halves start whose halves only mix has no bands: no band figure
    // unless asked for (--band-report; `tumble plot --band-report`).
    EXPECT_FALSE(fs::exists(figures / "fig_bands.png")) << result.output;
    const fs::path with_bands = dir_ / "with_bands";
    const Result asked = plot(python_, "run " + quoted(run) + " --band-report --out " + quoted(with_bands));
    ASSERT_EQ(asked.exit_code, 0) << asked.output;
    expect_figure(with_bands, "fig_bands");
    // Without the snapshots the set-up and depth figures are skipped with a
    // note, not a crash.
    fs::remove_all(run / "snapshots");
    fs::remove(run / "depth_mobility.csv");
    const fs::path figures2 = dir_ / "figures2";
    const Result again = plot(python_, "run " + quoted(run) + " --out " + quoted(figures2));
    ASSERT_EQ(again.exit_code, 0) << again.output;
    EXPECT_NE(again.output.find("fig1_setup skipped"), std::string::npos) << again.output;
    EXPECT_NE(again.output.find("fig_depth skipped"), std::string::npos) << again.output;
    EXPECT_FALSE(fs::exists(figures2 / "fig1_setup.png"));
    expect_figure(figures2, "fig_z");

    // compare: two runs (here the same one twice) in one figure.
    const fs::path figures3 = dir_ / "figures3";
    const Result compare =
        plot(python_, "compare " + quoted(run) + " " + quoted(run) + " --out " + quoted(figures3));
    ASSERT_EQ(compare.exit_code, 0) << compare.output;
    expect_figure(figures3, "fig_z_compare");
}

TEST_F(Plot, SweepTableGivesTheSweepFigures) {
    const fs::path table = dir_ / "sweep.csv";
    {
        std::ofstream out(table);
        out << "omega,froude,mode,seed,D_left,D_stderr_left,D_right,D_stderr_right,"
               "D_material-1,D_stderr_material-1,D_material-2,D_stderr_material-2,"
               "ke_ratio_total,ke_ratio_total_ref,ke_ratio_per_grain,ke_ratio_per_grain_ref,"
               "surface_share_left,surface_share_material-2\n"
               "2,0.0163,self,1,1.0e-5,2e-6,1.2e-5,2e-6,,,,,,,,,0.9,\n"
               "2,0.0163,self,2,1.1e-5,2e-6,0.9e-5,2e-6,,,,,,,,,0.92,\n"
               "5,0.102,self,1,2.0e-5,3e-6,2.4e-5,3e-6,,,,,,,,,0.88,\n"
               "5,0.102,self,2,2.2e-5,3e-6,,,,,,,,,,,,\n"
               "10,0.408,self,1,3.5e-5,5e-6,3.1e-5,5e-6,,,,,,,,,0.85,\n"
               "2,0.0163,two-component,1,,,,,3.0e-5,4e-6,2.0e-5,4e-6,1.4,0.998,0.42,0.296,,0.7\n"
               "2,0.0163,two-component,2,,,,,3.3e-5,4e-6,2.2e-5,4e-6,1.5,0.995,0.44,0.296,,0.72\n"
               "5,0.102,two-component,1,,,,,3.3e-5,4e-6,2.3e-5,5e-6,1.52,0.998,0.451,0.296,,0.6\n"
               "10,0.408,two-component,1,,,,,2.9e-5,4e-6,,,1.7,0.998,0.5,0.296,,\n";
    }
    const fs::path figures = dir_ / "figures";
    const Result result = plot(python_, "sweep " + quoted(table) + " --out " + quoted(figures));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    for (const char* name : {"fig3_self_D_vs_omega", "fig5_two_component_D_vs_omega",
                             "fig6_ke_ratio_vs_omega", "fig_D_vs_froude", "fig_surface_share_vs_omega"})
        expect_figure(figures, name);

    // A table with only two-component rows: Fig. 3 is skipped with a note.
    const fs::path two = dir_ / "two.csv";
    {
        std::ofstream out(two);
        out << "omega,froude,mode,seed,D_material-1,D_stderr_material-1,D_material-2,"
               "D_stderr_material-2\n"
               "2,0.0163,two-component,1,3.0e-5,4e-6,2.0e-5,4e-6\n"
               "5,0.102,two-component,1,3.3e-5,4e-6,2.3e-5,5e-6\n";
    }
    const Result partial = plot(python_, "sweep " + quoted(two) + " --out " + quoted(dir_ / "f2"));
    ASSERT_EQ(partial.exit_code, 0) << partial.output;
    EXPECT_NE(partial.output.find("fig3_self_D_vs_omega skipped"), std::string::npos)
        << partial.output;
    EXPECT_NE(partial.output.find("fig_surface_share_vs_omega skipped"), std::string::npos)
        << partial.output;
    expect_figure(dir_ / "f2", "fig5_two_component_D_vs_omega");
}

TEST_F(Plot, MissingInputIsExitCodeTwoNamingTheFile) {
    const fs::path missing_dir = dir_ / "no_such_run";
    Result r = plot(python_, "run " + quoted(missing_dir));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(missing_dir.string()), std::string::npos) << r.output;

    const fs::path missing_table = dir_ / "no_such_sweep.csv";
    r = plot(python_, "sweep " + quoted(missing_table));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(missing_table.string()), std::string::npos) << r.output;

    // A directory that is not a drum run: the missing drum_run.toml is named.
    const fs::path empty = dir_ / "empty";
    fs::create_directories(empty);
    r = plot(python_, "run " + quoted(empty));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("drum_run.toml"), std::string::npos) << r.output;

    r = plot(python_, "compare " + quoted(empty));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("drum_run.toml"), std::string::npos) << r.output;
}

}  // namespace
