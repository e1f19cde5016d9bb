// SPDX-License-Identifier: MIT
// The tangential-spring model (shear = "spring") against LAMMPS's
// pair_style granular with the same normal law, on a pour of 300 grains into
// a box with flat walls (docs/BENCHMARKS.md, "The pour against LAMMPS").
//
// For each seed, bench/peers/pour_start.py writes one start (positions and
// velocities) in both formats; tumble runs bench/peers/tumble_pour.toml and
// LAMMPS bench/peers/lammps_pour.in from it, side by side, 0.6 s each (the
// beds are at rest after about 0.4 s). Compared on the final states, with the
// same definitions for both codes: the mean bed height (mean z of the grain
// centres) and the coordination number (2 x grain-grain pairs that overlap,
// divided by the number of grains). The criterion: the mean
// over seeds of the relative difference of the bed height within 1 %. The
// seed-to-seed spread is reported as a 95 % confidence interval of that mean
// (Student's t over the seeds' paired differences).
//
// Needs LAMMPS (`lmp`, Debian package `lammps`: installed by the test when it
// runs as root and the package is missing) and python3; skips with a message
// otherwise. About 10 s per seed on two free cores.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <sstream>
#include <string>
#include <vector>

#include "../unit/test_support.hpp"

namespace fs = std::filesystem;
using tumble::test_support::find_lammps;
using tumble::test_support::have;
using tumble::test_support::run_command;

namespace {

constexpr int kSeeds = 6;
constexpr std::size_t kGrains = 300;  // pour_start.py's default
constexpr double kBox[3] = {0.04, 0.04, 0.20};

struct Grain {
    double x, y, z, vx, vy, vz, radius;
};

struct Bed {
    double mean_height = 0.0;  // mean z of the grain centres, m
    double coordination = 0.0;  // 2 x overlapping grain pairs / grains
    double max_speed = 0.0;     // m/s
    double speed_99 = 0.0;      // m/s, the speed that 99 % of the grains stay below
    std::size_t moving = 0;     // grains faster than 2 cm/s
};

Bed measure(const std::vector<Grain>& g) {
    Bed b;
    std::size_t contacts = 0;
    std::vector<double> speeds;
    for (std::size_t i = 0; i < g.size(); ++i) {
        const double v2 = g[i].vx * g[i].vx + g[i].vy * g[i].vy + g[i].vz * g[i].vz;
        b.mean_height += g[i].z;
        b.max_speed = std::max(b.max_speed, std::sqrt(v2));
        speeds.push_back(std::sqrt(v2));
        if (speeds.back() > 2e-2) ++b.moving;
        for (std::size_t j = i + 1; j < g.size(); ++j) {
            const double dx = g[i].x - g[j].x, dy = g[i].y - g[j].y, dz = g[i].z - g[j].z;
            const double reach = g[i].radius + g[j].radius;
            if (dx * dx + dy * dy + dz * dz < reach * reach) ++contacts;
        }
    }
    b.mean_height /= static_cast<double>(g.size());
    b.coordination = 2.0 * static_cast<double>(contacts) / static_cast<double>(g.size());
    std::sort(speeds.begin(), speeds.end());
    b.speed_99 = speeds[speeds.size() * 99 / 100];
    return b;
}

std::vector<std::string> split(const std::string& line, char sep) {
    std::vector<std::string> out;
    std::stringstream s(line);
    std::string field;
    while (std::getline(s, field, sep))
        if (sep != ' ' || !field.empty()) out.push_back(field);
    return out;
}

// The last snapshot tumble wrote (snapshots/NNNNNN.csv, highest NNNNNN).
std::vector<Grain> read_tumble(const fs::path& run) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(run / "snapshots"))
        if (e.path().extension() == ".csv") files.push_back(e.path());
    if (files.empty()) return {};
    std::sort(files.begin(), files.end());
    std::ifstream in(files.back());
    std::string line;
    std::vector<std::string> header;
    std::vector<Grain> grains;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        const std::vector<std::string> f = split(line, ',');
        if (header.empty()) {
            header = f;
            continue;
        }
        auto col = [&](const char* name) {
            const auto it = std::find(header.begin(), header.end(), name);
            return std::stod(f.at(static_cast<std::size_t>(it - header.begin())));
        };
        grains.push_back({col("x"), col("y"), col("z"), col("vx"), col("vy"), col("vz"), col("radius")});
    }
    return grains;
}

// LAMMPS's write_dump custom: id type radius x y z vx vy vz, sorted by id.
std::vector<Grain> read_lammps(const fs::path& dump) {
    std::ifstream in(dump);
    std::string line;
    std::vector<Grain> grains;
    bool atoms = false;
    while (std::getline(in, line)) {
        if (line.rfind("ITEM: ATOMS", 0) == 0) {
            atoms = true;
            continue;
        }
        if (!atoms || line.empty()) continue;
        const std::vector<std::string> f = split(line, ' ');
        if (f.size() < 9) continue;
        grains.push_back({std::stod(f[3]), std::stod(f[4]), std::stod(f[5]), std::stod(f[6]), std::stod(f[7]),
                          std::stod(f[8]), std::stod(f[2])});
    }
    return grains;
}

bool inside_box(const std::vector<Grain>& g) {
    return std::all_of(g.begin(), g.end(), [](const Grain& p) {
        return p.x > 0 && p.x < kBox[0] && p.y > 0 && p.y < kBox[1] && p.z > 0 && p.z < kBox[2];
    });
}

// Two-sided 95 % quantile of Student's t with `df` degrees of freedom.
double t95(int df) {
    static const double table[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228};
    return df >= 1 && df <= 10 ? table[df - 1] : 1.96;
}

struct Interval {
    double mean, half_width;
};

Interval confidence(const std::vector<double>& x) {
    double mean = 0.0;
    for (double v : x) mean += v;
    mean /= static_cast<double>(x.size());
    double ss = 0.0;
    for (double v : x) ss += (v - mean) * (v - mean);
    const double sd = std::sqrt(ss / static_cast<double>(x.size() - 1));
    return {mean, t95(static_cast<int>(x.size()) - 1) * sd / std::sqrt(static_cast<double>(x.size()))};
}

// The end of a log, for a failure message.
std::string tail_of(const fs::path& file) {
    const std::string text = tumble::test_support::read_file(file);
    return text.size() > 2000 ? text.substr(text.size() - 2000) : text;
}

}  // namespace

TEST(LammpsPour, SpringModelBedHeightMatchesLammpsWithinOnePercent) {
    std::string why;
    if (!have("python3")) GTEST_SKIP() << "python3 is needed to write the pour's start (bench/peers/pour_start.py)";
    if (!find_lammps(why)) GTEST_SKIP() << why;

    const fs::path source = TUMBLE_SOURCE_DIR;
    const fs::path peers = source / "bench" / "peers";
    const fs::path scratch = fs::temp_directory_path() / ("tumble-LammpsPour-" + std::to_string(::getpid()));
    fs::remove_all(scratch);

    std::vector<double> height_diff, coordination_diff;
    for (int seed = 1; seed <= kSeeds; ++seed) {
        const fs::path dir = scratch / ("seed" + std::to_string(seed));
        const auto gen = run_command("python3 " + (peers / "pour_start.py").string() + " --seed " +
                                     std::to_string(seed) + " --out " + dir.string());
        ASSERT_EQ(gen.exit_code, 0) << gen.output;
        fs::copy_file(peers / "tumble_pour.toml", dir / "tumble_pour.toml");

        // Both codes at once, one core each.
        auto tumble_run = std::async(std::launch::async, [&] {
            return run_command(std::string(TUMBLE_BINARY) + " run " + (dir / "tumble_pour.toml").string() +
                               " --out " + (dir / "tumble").string());
        });
        auto lammps_run = std::async(std::launch::async, [&] {
            return run_command("lmp -in " + (peers / "lammps_pour.in").string() + " -log " +
                               (dir / "lammps.log").string() + " -screen none -var start " +
                               (dir / "start.data").string() + " -var final " +
                               (dir / "lammps_final.dump").string());
        });
        const auto t = tumble_run.get();
        const auto l = lammps_run.get();
        ASSERT_EQ(t.exit_code, 0) << t.output;
        ASSERT_EQ(l.exit_code, 0) << l.output << tail_of(dir / "lammps.log");

        const std::vector<Grain> tg = read_tumble(dir / "tumble"), lg = read_lammps(dir / "lammps_final.dump");
        ASSERT_EQ(tg.size(), kGrains) << "tumble's final snapshot in " << dir;
        ASSERT_EQ(lg.size(), kGrains) << "LAMMPS's final dump in " << dir;
        EXPECT_TRUE(inside_box(tg));
        EXPECT_TRUE(inside_box(lg));
        const Bed tb = measure(tg), lb = measure(lg);
        // Settled: the grains fall at about 1 m/s; in the bed at rest 99 % of
        // them are below 1 cm/s, 1 % of the fall speed. What remains is
        // ringing of the packing at mm/s (the spring has no tangential
        // damping, in both codes): micrometres at the contacts' frequency,
        // which moves no grain. Measured on 2026-12-02, the speed 99 % stay
        // below: LAMMPS 1e-5 to 8e-4 m/s in all six seeds, tumble 7e-5 to
        // 7e-4 in four and 2.0e-3, 4.7e-3 in seeds 6 and 1 (its bed rings
        // longer there; the former limit, an rms speed of 1 mm/s, failed on
        // seeds 1 and 3). A lone
        // grain may still roll over the top of the heap (no rolling
        // resistance in either code; tumble, seed 3: one large grain at 9
        // cm/s, the highest, omega R 0.13 m/s), so up to 1 % of the grains
        // may move faster than 2 cm/s (one grain of 300 a centimetre higher
        // moves the mean height by 0.15 %, within the 1 % compared).
        EXPECT_LT(tb.speed_99, 1e-2) << "seed " << seed;
        EXPECT_LT(lb.speed_99, 1e-2) << "seed " << seed;
        EXPECT_LE(tb.moving, kGrains / 100) << "seed " << seed;
        EXPECT_LE(lb.moving, kGrains / 100) << "seed " << seed;
        height_diff.push_back(tb.mean_height / lb.mean_height - 1.0);
        coordination_diff.push_back(tb.coordination / lb.coordination - 1.0);
        std::printf(
            "[measured] seed %d: mean height tumble %.4f mm, LAMMPS %.4f mm (%+.2f %%); coordination tumble %.3f, "
            "LAMMPS %.3f (%+.1f %%); speed below which 99 %% stay %.1e / %.1e m/s, largest %.1e / %.1e m/s\n",
            seed, 1e3 * tb.mean_height, 1e3 * lb.mean_height, 100.0 * height_diff.back(), tb.coordination,
            lb.coordination, 100.0 * coordination_diff.back(), tb.speed_99, lb.speed_99, tb.max_speed,
            lb.max_speed);
    }
    fs::remove_all(scratch);

    const Interval h = confidence(height_diff), z = confidence(coordination_diff);
    std::printf("[measured] %d seeds: mean height tumble/LAMMPS - 1 = %+.2f %% +- %.2f %% (95 %% interval of the mean), "
                "coordination %+.2f %% +- %.2f %%\n",
                kSeeds, 100.0 * h.mean, 100.0 * h.half_width, 100.0 * z.mean, 100.0 * z.half_width);
    EXPECT_LT(std::abs(h.mean), 0.01);
    // The contact network is a far noisier statistic than the height (a few
    // per cent per seed); a systematic difference of 5 % would still show.
    EXPECT_LT(std::abs(z.mean), 0.05);
}
