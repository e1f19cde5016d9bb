// SPDX-License-Identifier: MIT
// The tumble command line: run, bench.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cli/commands.hpp"
#include "tumble/core/error.hpp"

int main(int argc, char** argv) {
    using namespace tumble::cli;
    CLI::App app{"tumble: discrete-element simulation of visco-elastic spheres (Kohring's contact model)"};
    app.set_version_flag("--version", std::string("tumble ") + TUMBLE_VERSION);
    app.require_subcommand(1);

    RunOptions run;
    CLI::App* run_cmd = app.add_subcommand("run", "Simulate a scenario file (TOML; see docs/SCENARIO.md)");
    run_cmd->add_option("scenario", run.scenario_file, "Scenario file")->required();
    run_cmd->add_option("-o,--out", run.output_directory, "Output directory (default: the scenario's [output] directory)");
    run_cmd->add_flag("--force", run.force, "Overwrite the output of an earlier run in that directory");
    run_cmd->add_flag("-q,--quiet", run.quiet, "Print nothing but errors");

    BenchOptions bench;
    CLI::App* bench_cmd = app.add_subcommand("bench", "Speed on the paper's dense periodic cube (SPEC-NOTES \"Speed\")");
    bench_cmd->add_option("--size", bench.size, "Spheres per lattice edge (21: 9261, the paper's; 46: 97336)")
        ->check(CLI::Range(4, 400));
    bench_cmd->add_option("--steps", bench.steps, "Timed steps")->check(CLI::PositiveNumber);
    bench_cmd->add_option("--warmup", bench.warmup, "Untimed steps before timing")->check(CLI::NonNegativeNumber);
    bench_cmd->add_option("--seed", bench.seed, "Seed of the random initial velocities");
    bench_cmd->add_flag("--json", bench.json, "Print one JSON object instead of the table");

    CLI11_PARSE(app, argc, argv);
    try {
        if (run_cmd->parsed()) return run_command(run);
        if (bench_cmd->parsed()) return bench_command(bench);
    } catch (const tumble::Error& e) {
        fmt::print(stderr, "tumble: error: {}\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        fmt::print(stderr, "tumble: unexpected error: {}\n", e.what());
        return 3;
    }
    return 1;
}
