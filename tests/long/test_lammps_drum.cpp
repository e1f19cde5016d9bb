// SPDX-License-Identifier: MIT
// Issue 13: the LAMMPS peer of `tumble bench --case long-drum`
// (bench/compare_drum.sh, bench/peers/lammps_drum.in; docs/BENCHMARKS.md,
// "LAMMPS on the same drum") runs on tumble's settled bed and does what the
// drum does: no grain leaves the drum, and the grains' kinetic energy after
// the drum has turned for 2000 steps is of the order of tumble's (the two
// laws differ: LAMMPS has no attraction, and a spring where tumble's drum has
// the paper's saw-tooth). Speed is not tested; the script's table is printed.
//
// Needs LAMMPS (`lmp`, installed as in test_lammps_pour.cpp) and python3;
// skips with a message otherwise. The settled bed is the one beside the
// tumble binary (bench-cache/); made when it is missing (about 6 CPU-minutes).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "../unit/test_support.hpp"
#include "io/json.hpp"

namespace fs = std::filesystem;
using tumble::test_support::find_lammps;
using tumble::test_support::have;
using tumble::test_support::run_command;

TEST(LammpsDrum, PeerKeepsTheGrainsInTheDrumWithTumblesKineticEnergy) {
    std::string why;
    if (!have("python3")) GTEST_SKIP() << "python3 is needed (bench/peers/drum_peer.py)";
    if (!find_lammps(why)) GTEST_SKIP() << why;

    const fs::path source = TUMBLE_SOURCE_DIR;
    const fs::path out = fs::temp_directory_path() / ("tumble-LammpsDrum-" + std::to_string(::getpid()));
    fs::remove_all(out);
    const auto run = run_command("TUMBLE=" + std::string(TUMBLE_BINARY) + " bash " +
                                 (source / "bench" / "compare_drum.sh").string() +
                                 " --repeats 1 --np 1 --steps 1000 --warmup 1000 --out " + out.string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    std::printf("%s", run.output.c_str());

    std::map<std::string, tumble::io::Json> result;  // by code
    std::ifstream in(out / "results.jsonl");
    for (std::string line; std::getline(in, line);) {
        tumble::io::Json j = tumble::io::parse_json(line);
        result.emplace(j.value("code", ""), std::move(j));
    }
    ASSERT_EQ(result.size(), 2u) << "expected one tumble and one LAMMPS result in " << out;
    const tumble::io::Json &t = result.at("tumble"), &l = result.at("lammps");
    EXPECT_EQ(l.at("grains").get<double>(), t.at("grains").get<double>());
    // Grain centres stay inside the drum's inner surface (radius 4 cm,
    // 32 cm either side of the middle): LAMMPS's own count of atoms would
    // stop the run on a grain leaving the box, this also catches one
    // between the wall spheres.
    EXPECT_LT(l.at("largest_axis_distance").get<double>(), 0.04);
    EXPECT_LT(l.at("largest_abs_z").get<double>(), 0.32);
    const double ratio = l.at("kinetic_translational").get<double>() / t.at("kinetic_translational").get<double>();
    EXPECT_GT(ratio, 1.0 / 3.0);
    EXPECT_LT(ratio, 3.0);
    std::printf("[measured] grains' translational kinetic energy after 2000 steps turning: LAMMPS / tumble %.3f\n",
                ratio);
    fs::remove_all(out);
}
