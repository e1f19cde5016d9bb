// SPDX-License-Identifier: MIT
// A full disk, simulated by a file-size limit (ulimit -f) in a child shell
// that ignores SIGXFSZ, so writes fail with EFBIG as on a full disk: the
// error names the file, and nothing is left that looks like a finished run
// or a valid checkpoint.
#include <gtest/gtest.h>

#include <filesystem>

#include "io/checkpoint.hpp"
#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;

class FullDisk : public tumble::test_support::ScratchTest {
protected:
    // Runs tumble with files limited to `kib` KiB.
    tumble::test_support::CommandResult limited(int kib, const std::string& arguments) {
        return tumble::test_support::run_command("bash -c \"trap '' XFSZ; ulimit -f " + std::to_string(kib) +
                                                 "; exec " + TUMBLE_BINARY + " " + arguments + "\"");
    }
    // No temporary files, no summary, and every checkpoint loads.
    void expect_nothing_looks_valid(const fs::path& run) {
        for (const auto& entry : fs::recursive_directory_iterator(run))
            EXPECT_NE(entry.path().extension(), ".tmp") << entry.path();
        EXPECT_FALSE(fs::exists(run / "summary.json"));
        EXPECT_FALSE(fs::exists(run / "run.json"));
        for (const fs::path& file : tumble::io::checkpoint_files(run))
            EXPECT_NO_THROW(tumble::io::decode_checkpoint(tumble::test_support::read_file(file), file.string()));
    }
};

TEST_F(FullDisk, ACheckpointThatDoesNotFitIsReportedAndRemoved) {
    // The checkpoints of this drum are about 70 KiB; the other files stay under 40.
    const fs::path run = dir_ / "drum";
    const auto r = limited(40, "drum -q --mode self --grains 20 --length 0.03 --diameter 0.03 --omega 10 "
                               "--revolutions 0.2 --no-plot --checkpoint-every-revolutions 0.05 --out " +
                                   run.string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find((run / "checkpoints" / "000001.tck.tmp").string() + ": writing (disk full?) failed"),
              std::string::npos)
        << r.output;
    EXPECT_TRUE(tumble::io::checkpoint_files(run).empty());
    expect_nothing_looks_valid(run);
}

TEST_F(FullDisk, AnOutputFileThatDoesNotFitIsReported) {
    // 2 samples per step in a 16 KiB limit: time_series.csv fills up first.
    const fs::path scenario = write("box.toml", tumble::test_support::walled_box_scenario("0.05", "", R"([output]
time_series_interval = 1e-9
)"));
    const fs::path run = dir_ / "box";
    const auto r = limited(16, "run -q " + scenario.string() + " --out " + run.string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find((run / "time_series.csv").string() + ": write failed (disk full"), std::string::npos)
        << r.output;
    expect_nothing_looks_valid(run);
}

TEST_F(FullDisk, AnUnwritableDirectoryIsReportedWithThePath) {
    const fs::path blocked = write("file", "not a directory");
    const auto r = tumble::test_support::run_command(std::string(TUMBLE_BINARY) +
                                                     " drum -q --grains 20 --revolutions 0.1 --out " +
                                                     (blocked / "run").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find((blocked / "run").string() + ": cannot create the output directory"), std::string::npos)
        << r.output;
}

}  // namespace
