// SPDX-License-Identifier: MIT
// End to end: the README's main job, `tumble drum` on its
// default (the paper's two-component drum, 12 revolutions), writes a
// summary.json with, for each component, the grains' MSD D determined and a
// 95 % interval around it. About 40 s (38 s on an AMD Zen 5, 2026-12-05):
// label "long" (ctest --test-dir build -L long).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "../unit/test_support.hpp"
#include "io/json.hpp"

namespace {

using tumble::test_support::run_command;

class DefaultDrum : public tumble::test_support::ScratchTest {};

TEST_F(DefaultDrum, SummaryHasADWithAnIntervalForEachComponent) {
    const auto run = run_command(std::string(TUMBLE_BINARY) + " drum -q --no-plot --out " + (dir_ / "run").string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const tumble::io::Json j = tumble::io::parse_json(
        tumble::test_support::read_file(dir_ / "run" / "summary.json"), "summary.json");
    const tumble::io::Json& components = j.at("components");
    ASSERT_EQ(components.size(), 2u);
    for (const tumble::io::Json& c : components) {
        const tumble::io::Json& msd = c.at("msd");
        EXPECT_TRUE(msd.value("determined", false)) << c.value("name", "");
        const double D = tumble::io::json_number(msd, "D").value_or(NAN),
                     lo = tumble::io::json_number(msd, "D_lo").value_or(NAN),
                     hi = tumble::io::json_number(msd, "D_hi").value_or(NAN);
        EXPECT_LT(lo, D);
        EXPECT_GT(hi, D);
        // The size measured on the development machine (docs/DRUM.md): of
        // order 1e-5 m^2 per revolution.
        EXPECT_GT(D, 3e-6);
        EXPECT_LT(D, 5e-5);
    }
}

}  // namespace
