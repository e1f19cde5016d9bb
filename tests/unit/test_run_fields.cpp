// SPDX-License-Identifier: MIT
// Fields taken during a run (tumble run --fields; docs/FIELDS.md, "During a
// run") are those tumble fields computes afterwards from the same states.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;
using tumble::test_support::read_file;

class RunFields : public tumble::test_support::ScratchTest {
protected:
    tumble::test_support::CommandResult tumble(const std::string& arguments) {
        return tumble::test_support::run_command(std::string(TUMBLE_BINARY) + " " + arguments);
    }
};

// The largest |contact_stress_zz| over the rows of a fields.csv, Pa.
double largest_contact_stress(const fs::path& csv) {
    std::istringstream in(read_file(csv));
    std::string line, cell;
    std::getline(in, line);
    std::istringstream header(line);
    std::size_t column = 0;
    while (std::getline(header, cell, ',') && cell != "contact_stress_zz") ++column;
    double largest = 0.0;
    while (std::getline(in, line)) {
        std::istringstream row(line);
        for (std::size_t k = 0; k <= column; ++k) std::getline(row, cell, ',');
        largest = std::max(largest, std::abs(std::stod(cell)));
    }
    return largest;
}

// The small scenario (2000 steps of 10 us, 60 grains falling onto a floor,
// periodic sideways) averaged over x and y: a profile in z.
const std::string grid = "--lo -0.03,-0.03,0 --hi 0.03,0.03,0.06 --average xy --cells 1,1,24 --kernel lucy --width 0.004";

TEST_F(RunFields, EqualThoseOfTumbleFieldsFromTheSameStatesBitForBit) {
    const fs::path scenario = write("small.toml", tumble::test_support::small_scenario);
    // Run A takes 5 states 2 ms apart from t = 10 ms (steps 1000, 1200, ...,
    // 1800): the times from its file's [fields] (every replaced by the
    // command line's), the grid from the command line.
    const fs::path with_fields = write("fields.toml", std::string(tumble::test_support::small_scenario) +
                                                          "[fields]\nfrom = 0.01\nevery = 0.5\nsamples = 5\n");
    const auto a = tumble("run -q " + with_fields.string() + " --out " + (dir_ / "a").string() +
                          " --fields every=0.002 --fields 'lo=-0.03,-0.03,0 hi=0.03,0.03,0.06 average=xy "
                          "cells=1,1,24 kernel=lucy width=0.004'");
    ASSERT_EQ(a.exit_code, 0) << a.output;
    // Run B, the same, stops at step 999 with a checkpoint, from which tumble
    // fields takes its 5 states 2 ms apart: steps 1000 to 1800 again.
    const fs::path b = dir_ / "b";
    const auto stopped = tumble("run -q " + scenario.string() + " --out " + b.string() + " --stop-at-step 999");
    ASSERT_EQ(stopped.exit_code, 4) << stopped.output;  // exit_stopped: a checkpoint to resume from
    const auto after = tumble("fields -q " + b.string() + " --samples 5 --every 0.002 " + grid + " -o " +
                              (dir_ / "after").string());
    ASSERT_EQ(after.exit_code, 0) << after.output;
    // Tolerance: none, bit for bit. The states are the same (the simulation
    // is deterministic, a checkpoint continues it bit for bit, and recording
    // the contacts of a step does not change it), and both sum them with the
    // same FieldAccumulator in the same order.
    // The grains collide and stick (W = 0.2 J/m^2): the states have contacts,
    // and the comparison covers the contact stress.
    EXPECT_GT(largest_contact_stress(dir_ / "a" / "fields" / "fields.csv"), 0.1);  // Pa; 1.2 Pa measured
    for (const char* file : {"fields.csv", "fields.vti"}) {
        const std::string during = read_file(dir_ / "a" / "fields" / file);
        EXPECT_GT(during.size(), 1000u) << file;  // 25 nodes of 46 fields: not an empty file
        EXPECT_EQ(during, read_file(dir_ / "after" / file)) << file;
    }
    // Taking the fields does not change the run: B resumed to the end has
    // A's time series, byte for byte (tolerance none: the same steps).
    const auto resumed = tumble("resume -q " + b.string());
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    EXPECT_EQ(read_file(dir_ / "a" / "time_series.csv"), read_file(b / "time_series.csv"));
    EXPECT_FALSE(fs::exists(b / "fields"));  // a run that asked for none takes none when resumed

    // Run C asks for A's fields, stops at step 1300 (two of the five states
    // taken, at steps 1000 and 1200) and is resumed: its checkpoint keeps
    // the sums, and the resumed run writes A's files, bit for bit
    // (tolerance none: the same sums of the same states in the same order).
    const fs::path c = dir_ / "c";
    const auto c_stopped = tumble("run -q " + with_fields.string() + " --out " + c.string() +
                                  " --stop-at-step 1300 --fields every=0.002 --fields 'lo=-0.03,-0.03,0 "
                                  "hi=0.03,0.03,0.06 average=xy cells=1,1,24 kernel=lucy width=0.004'");
    ASSERT_EQ(c_stopped.exit_code, 4) << c_stopped.output;
    EXPECT_FALSE(fs::exists(c / "fields"));
    const auto c_resumed = tumble("resume -q " + c.string());
    ASSERT_EQ(c_resumed.exit_code, 0) << c_resumed.output;
    for (const char* file : {"fields.csv", "fields.vti"})
        EXPECT_EQ(read_file(dir_ / "a" / "fields" / file), read_file(c / "fields" / file)) << file;
}

}  // namespace
