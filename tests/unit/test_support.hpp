// SPDX-License-Identifier: MIT
// What several tests share: running a command, finding LAMMPS, reading a
// file, a small scenario, and a scratch directory per test.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace tumble::test_support {

struct CommandResult {
    int exit_code;       // -1 if the command did not exit normally
    std::string output;  // stdout and stderr
};

// Runs a shell command line and collects what it prints.
inline CommandResult run_command(const std::string& command) {
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return {-1, "popen failed"};
    std::string output;
    char buffer[4096];
    while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
    const int status = pclose(pipe);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

inline bool have(const std::string& program) { return run_command("command -v " + program).exit_code == 0; }

// LAMMPS's `lmp`, installed from Debian's package when missing and root
// (the tests against LAMMPS in tests/long). False when there is none; `why`
// then says why.
inline bool find_lammps(std::string& why) {
    if (have("lmp")) return true;
    if (::geteuid() != 0) {
        why = "LAMMPS (lmp) is not installed and the test is not root: install the Debian package "
              "(apt-get install lammps) to run the LAMMPS comparison";
        return false;
    }
    std::printf("[setup] lmp missing: apt-get install -y lammps\n");
    const std::string install = "DEBIAN_FRONTEND=noninteractive apt-get install -y -q lammps";
    if (run_command(install).exit_code != 0)
        run_command("DEBIAN_FRONTEND=noninteractive apt-get update -q && " + install);
    if (have("lmp")) return true;
    why = "LAMMPS (lmp) is not installed and `apt-get install lammps` failed: install it to run the LAMMPS comparison";
    return false;
}

inline std::string read_file(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// A small, fast scenario: 60 grains of the paper's material 1 falling onto a
// flat floor, with random velocities so the run exercises the RNG.
inline const char* const small_scenario = R"(
[simulation]
duration = 0.02
seed = 11
gravity = [0.0, 0.0, -9.81]

[domain]
lo = [-0.03, -0.03, 0.0]
hi = [0.03, 0.03, 0.06]
walls = [false, false, true]
wall_material = "material-1"

[neighbor]
skin = 0.0002

[time_step]
dt = 1e-5

[[material]]
name = "material-1"
E = 1.0e6
G = 0.3e6
nu = 0.25
xi = 500.0
eta = 500.0
rho = 1000.0
radius = 0.0036

[[pair]]
materials = ["material-1", "material-1"]
mu = 0.1
W = 0.2

[[particles]]
kind = "random_fill"
material = "material-1"
lo = [-0.03, -0.03, 0.0]
hi = [0.03, 0.03, 0.04]
count = 60
speed = 0.3

[output]
time_series_interval = 0.001
snapshot_interval = 0.01
)";

// A fresh directory per test, removed afterwards:
// <tmp>/tumble-<suite>-<test>-<pid>: the process id keeps apart the same
// test run at once from several checkouts (or build directories).
class ScratchTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = std::filesystem::temp_directory_path() /
               ("tumble-" + std::string(info->test_suite_name()) + "-" + info->name() + "-" +
                std::to_string(::getpid()));
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::filesystem::path write(const std::string& name, const std::string& text) {
        std::filesystem::create_directories((dir_ / name).parent_path());
        std::ofstream(dir_ / name) << text;
        return dir_ / name;
    }
    std::filesystem::path dir_;
};

// The paper's material 1 as material "m" of a scenario file, with its pair.
inline const std::string material_m_toml = R"([[material]]
name = "m"
E = 1.0e6
G = 0.3e6
nu = 0.25
xi = 500.0
eta = 500.0
rho = 1000.0
radius = 0.0036
[[pair]]
materials = ["m", "m"]
mu = 0.1
W = 0.2
)";

// A small scenario (TOML): 30 spheres of the paper's material 1 dropped at
// random into a walled 4 cm box, for `duration` seconds. `simulation` adds
// keys to [simulation] (e.g. gravity), `rest` tables at the end (e.g. [output]).
inline std::string walled_box_scenario(const std::string& duration, const std::string& simulation = "",
                                       const std::string& rest = "") {
    return "[simulation]\nduration = " + duration + "\n" + simulation + R"([domain]
lo = [-0.02, -0.02, 0.0]
hi = [0.02, 0.02, 0.04]
walls = [true, true, true]
wall_material = "m"
)" + material_m_toml + R"([[particles]]
kind = "random_fill"
material = "m"
lo = [-0.015, -0.015, 0.005]
hi = [0.015, 0.015, 0.035]
count = 30
)" + rest;
}

}  // namespace tumble::test_support
