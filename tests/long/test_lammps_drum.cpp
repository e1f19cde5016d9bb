// SPDX-License-Identifier: MIT
// The LAMMPS peer of `tumble bench --case long-drum`
// (bench/compare_drum.sh, bench/peers/lammps_drum.in; docs/BENCHMARKS.md,
// "LAMMPS on the same drum") runs on tumble's settled bed and does what the
// drum does: no grain leaves the drum; with the deck's own law in tumble
// (`tumble bench --law peer`: no attraction, the tangential spring held at
// the friction limit) the two codes agree on the flowing bed, and with the
// drum's law (attraction, the paper's saw-tooth) they differ as the laws do.
// Speed is not tested; the script's table is printed.
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

TEST(LammpsDrum, PeerAgreesWithTumbleOnTheSameLawAndKeepsTheGrainsInTheDrum) {
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

    std::map<std::string, tumble::io::Json> result;  // by code and law
    std::ifstream in(out / "results.jsonl");
    for (std::string line; std::getline(in, line);) {
        tumble::io::Json j = tumble::io::parse_json(line);
        result.emplace(j.value("code", "") + " " + j.value("law", ""), std::move(j));
    }
    ASSERT_EQ(result.size(), 3u) << "expected tumble on both laws and one LAMMPS result in " << out;
    const tumble::io::Json &drum = result.at("tumble drum"), &same = result.at("tumble peer"),
                           &l = result.at("lammps peer");
    EXPECT_EQ(l.at("grains").get<double>(), drum.at("grains").get<double>());
    // Grain centres stay inside the drum's inner surface (radius 4 cm,
    // 32 cm either side of the middle): LAMMPS's own count of atoms would
    // stop the run on a grain leaving the box, this also catches one
    // between the wall spheres.
    EXPECT_LT(l.at("largest_axis_distance").get<double>(), 0.04);
    EXPECT_LT(l.at("largest_abs_z").get<double>(), 0.32);

    // The same law from the same bed for 2000 steps (0.08 s, the cohesive
    // bed loosening as the drum starts): what is left between the codes is
    // listed in docs/BENCHMARKS.md ("Every modelling difference": the
    // dashpot over the step against the half-step velocity, the spin's
    // lever R - h/2 against R, LAMMPS's twisting cap 13 % higher, no
    // history at LAMMPS's start). Measured on an AMD Zen 5: LAMMPS / tumble
    // 0.999 (translational), 0.978 (rotational kinetic energy), contacts
    // 1.006. The tolerances allow a few times that and fail the law that
    // is not the deck's: tumble's drum law holds 21 % more contacts here
    // (the attraction) and 36 % less rotational energy.
    const auto ratio = [&](const char* key) { return l.at(key).get<double>() / same.at(key).get<double>(); };
    EXPECT_NEAR(ratio("kinetic_translational"), 1.0, 0.05);
    EXPECT_NEAR(ratio("kinetic_rotational"), 1.0, 0.10);
    EXPECT_NEAR(ratio("contacts"), 1.0, 0.03);
    // The drum's law: the same order of energy (a factor 3 either way).
    const double drum_ratio = l.at("kinetic_translational").get<double>() / drum.at("kinetic_translational").get<double>();
    EXPECT_GT(drum_ratio, 1.0 / 3.0);
    EXPECT_LT(drum_ratio, 3.0);
    std::printf("[measured] after 2000 steps turning, LAMMPS / tumble on the same law: kinetic energy %.3f "
                "(translational), %.3f (rotational), contacts %.3f; on the drum's law %.3f (translational)\n",
                ratio("kinetic_translational"), ratio("kinetic_rotational"), ratio("contacts"), drum_ratio);
    fs::remove_all(out);
}
