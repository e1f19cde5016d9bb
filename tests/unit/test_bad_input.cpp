// SPDX-License-Identifier: MIT
// Hostile input: every file of the corpus tests/data/bad/ (malformed,
// truncated, NaN, Inf, 1e308, negative and enormous counts, duplicated keys
// and columns) and generated binary, enormous and endless files are refused
// with an error that names the file and the key, line or column, and with
// bounded memory. Each corpus file says on its first line "# expect: TEXT",
// a part of the message. scripts/fuzz.sh throws random input at the same
// readers.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "io/binary.hpp"
#include "io/checkpoint.hpp"
#include "io/config.hpp"
#include "io/drum_config.hpp"
#include "test_support.hpp"
#include "tumble/sim/simulation.hpp"

namespace {

namespace fs = std::filesystem;
using tumble::io::ConfigError;

const fs::path corpus = fs::path(TUMBLE_SOURCE_DIR) / "tests" / "data" / "bad";

std::string expected_part(const fs::path& file) {
    std::ifstream in(file);
    std::string first;
    std::getline(in, first);
    const std::string mark = "# expect: ";
    EXPECT_EQ(first.rfind(mark, 0), 0u) << file << " has no \"# expect: \" line";
    return first.substr(mark.size());
}

// The message of the ConfigError that loading `scenario` throws.
std::string refusal(const fs::path& scenario) {
    try {
        tumble::io::load_run_config(scenario);
    } catch (const ConfigError& e) {
        return e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << scenario << ": not a ConfigError: " << e.what();
        return e.what();
    }
    ADD_FAILURE() << scenario << " was accepted";
    return "";
}

class BadInput : public tumble::test_support::ScratchTest {
protected:
    // A valid scenario whose particles come from `csv`.
    fs::path scenario_for(const fs::path& csv) {
        return write("with_csv.toml", "[simulation]\nduration = 0.01\n[domain]\nlo = [-0.02, -0.02, 0.0]\n"
                                      "hi = [0.02, 0.02, 0.04]\n[[material]]\nname = \"m\"\nE = 1.0e6\nG = 0.3e6\n"
                                      "nu = 0.25\nxi = 500.0\neta = 500.0\nrho = 1000.0\nradius = 0.0036\n"
                                      "[[pair]]\nmaterials = [\"m\", \"m\"]\nmu = 0.1\nW = 0.2\n"
                                      "[[particles]]\nkind = \"csv\"\nfile = \"" +
                                          csv.string() + "\"\n");
    }
    fs::path garbage(const std::string& name, std::size_t bytes) {
        std::mt19937 random(7);
        std::string text(bytes, '\0');
        for (char& c : text) c = static_cast<char>(random());
        std::ofstream(dir_ / name, std::ios::binary) << text;
        return dir_ / name;
    }
};

TEST_F(BadInput, EveryScenarioOfTheCorpusIsRefusedNamingFileAndKey) {
    std::size_t files = 0;
    for (const auto& entry : fs::directory_iterator(corpus)) {
        if (entry.path().extension() != ".toml") continue;
        ++files;
        const std::string why = refusal(entry.path());
        EXPECT_EQ(why.rfind(entry.path().string() + ": ", 0), 0u) << why;
        EXPECT_NE(why.find(expected_part(entry.path())), std::string::npos) << why;
    }
    EXPECT_GE(files, 10u);
}

TEST_F(BadInput, EveryCsvOfTheCorpusIsRefusedNamingFileLineAndColumn) {
    std::size_t files = 0;
    for (const auto& entry : fs::directory_iterator(corpus)) {
        if (entry.path().extension() != ".csv") continue;
        ++files;
        // Errors found while reading start with the CSV file; errors of the
        // whole scenario (a particle outside the domain) name the scenario's
        // block and the CSV file and line.
        const std::string why = refusal(scenario_for(entry.path()));
        EXPECT_NE(why.find(entry.path().string()), std::string::npos) << why;
        EXPECT_NE(why.find(expected_part(entry.path())), std::string::npos) << why;
    }
    EXPECT_GE(files, 8u);
}

TEST_F(BadInput, BinaryFilesAreRefused) {
    EXPECT_NE(refusal(garbage("binary.toml", 5000)).find("TOML syntax error"), std::string::npos);
    const fs::path csv = garbage("binary.csv", 5000);
    EXPECT_EQ(refusal(scenario_for(csv)).rfind(csv.string() + ": line ", 0), 0u);
    try {
        tumble::io::load_drum_settings(garbage("drum.toml", 5000));
        FAIL();
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("drum.toml: line"), std::string::npos) << e.what();
    }
}

TEST_F(BadInput, EnormousAndEndlessFilesAreRefusedWithoutReadingThemIn) {
    // A sparse file of 4 GiB (no disk space used) and /dev/zero: refused
    // after 64 MiB (scenario) or before reading (CSV: its size; a link to a
    // device is no regular file).
    const fs::path huge = write("huge.toml", "");
    fs::resize_file(huge, std::uintmax_t{4} << 30);
    EXPECT_NE(refusal(huge).find("larger than 64 MiB"), std::string::npos);
    EXPECT_NE(refusal("/dev/zero").find("larger than 64 MiB"), std::string::npos);
    EXPECT_NE(refusal(scenario_for(huge)).find("particles[0].file: " + huge.string() + ": larger than 64 MiB"),
              std::string::npos);
    fs::create_symlink("/dev/zero", dir_ / "zero.csv");
    EXPECT_NE(refusal(scenario_for(dir_ / "zero.csv")).find("particles[0].file: not a regular file"), std::string::npos)
        << "a CSV file must be a regular file";
}

TEST_F(BadInput, ACheckpointClaimingHugeCountsIsRefusedWithoutAllocating) {
    // A checksum-correct file whose first count (the record's entries) claims
    // 2^60: the reader compares it with the bytes left before allocating.
    tumble::Scenario s;
    s.materials = {tumble::Material{"m", 1e6, 0.3e6, 0.25, 500.0, 500.0, 1000.0, 1e-3}};
    s.pair_properties = {{tumble::PairProperties{0.1, 0.0}}};
    s.domain.hi = {0.01, 0.01, 0.01};
    s.particles = {tumble::ParticleSpec{{0.005, 0.005, 0.005}, {}, {}, 1e-3, 0}};
    const tumble::Simulation sim(s);
    std::string bytes = tumble::io::encode_checkpoint({{}, sim.scenario(), sim.capture()});
    const std::uint64_t huge = std::uint64_t{1} << 60;
    std::memcpy(bytes.data() + 20, &huge, sizeof huge);  // after magic (8), version (4), length (8)
    const std::uint32_t crc = tumble::io::crc32(std::string_view(bytes).substr(0, bytes.size() - 4));
    std::memcpy(bytes.data() + bytes.size() - 4, &crc, sizeof crc);
    try {
        tumble::io::decode_checkpoint(bytes, "hostile.tck");
        FAIL();
    } catch (const tumble::Error& e) {
        EXPECT_NE(std::string(e.what()).find("hostile.tck: record: claims 1152921504606846976 elements"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
