// SPDX-License-Identifier: MIT
// The tumble command line: run, bench, drum, contact, analyze, plot, sweep, render, resume, fields.
#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cli/commands.hpp"
#include "cli/sweep_command.hpp"
#include "experiments/limits.hpp"
#include "io/names.hpp"
#include "tumble/analysis/pair_collision.hpp"
#include "tumble/contact/contact_law.hpp"
#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"
#include "tumble/core/mpi.hpp"
#include "tumble/setup/drum.hpp"

namespace {

// A number that is finite and >= 0 (CLI::NonNegativeNumber lets NaN through).
const CLI::Validator finite_non_negative(
    [](std::string& text) {
        const double v = std::strtod(text.c_str(), nullptr);
        return std::isfinite(v) && v >= 0.0 ? std::string() : "must be a finite number >= 0, got " + text;
    },
    "NUMBER >= 0");
const CLI::Validator finite_positive(
    [](std::string& text) {
        return tumble::experiments::finite_positive_problem(std::strtod(text.c_str(), nullptr), text);
    },
    "NUMBER > 0");
// A thread count (CLI::NonNegativeNumber's message printed DBL_MAX in full).
const CLI::Validator thread_count(
    [](std::string& text) {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        return tumble::experiments::thread_count_problem(end != text.c_str() && *end == '\0' ? v : -1.0, text);
    },
    "THREADS >= 0");
// An impact speed of tumble contact, m/s.
const CLI::Validator impact_speed(
    [](std::string& text) {
        const double v = std::strtod(text.c_str(), nullptr);
        return v > 0.0 && v <= tumble::analysis::max_impact_speed
                   ? std::string()
                   : fmt::format("must be a number > 0 and at most {:g} m/s, got {}", tumble::analysis::max_impact_speed,
                                 text);
    },
    "0 < SPEED <= 1000");
// A seed that drum_run.toml can hold: 0 to 2^63 - 1, in decimal digits.
const CLI::Validator seed_range(
    [](std::string& text) {
        const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
        const std::string largest = "9223372036854775807";
        const bool fits = text.size() < largest.size() || (text.size() == largest.size() && text <= largest);
        return digits && fits ? std::string() : "must be an integer from 0 to 2^63 - 1, got " + text;
    },
    "0 .. 2^63 - 1");
// CLI11 reads an empty value as the type's default: refuse it instead.
const CLI::Validator not_empty(
    [](std::string& text) { return text.empty() ? std::string("needs a value, got an empty one") : std::string(); }, "");

// The checkpoint options that tumble run and tumble drum share.
void add_checkpoint_options(CLI::App* command, tumble::cli::CheckpointPolicy& policy) {
    command->add_option("--checkpoint-every-minutes", policy.every_minutes,
                        "Wall-clock minutes between checkpoints (default 10; 0: not by the clock)")
        ->check(finite_non_negative);
    command->add_option("--stop-at-step", policy.stop_at_step,
                        "Write a checkpoint and stop at this step (exit code 4; for batch time limits and tests)")
        ->check(CLI::PositiveNumber);
}

// --progress-every, of the commands that run for long.
void add_progress_option(CLI::App* command, double& seconds) {
    command->add_option("--progress-every", seconds,
                        "Seconds between progress lines when stderr is not a terminal (nohup, a batch system; "
                        "default 30; 0: none)")
        ->check(finite_non_negative);
}

// The long option names of a command, with their dashes.
std::vector<std::string> long_options(const CLI::App& command) {
    std::vector<std::string> names;
    for (const CLI::Option* option : command.get_options())
        for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
    return names;
}

// "; did you mean 'x'?" when a known name is close to `word`, else "".
std::string suggestion(const std::string& word, const std::vector<std::string>& known) {
    const std::optional<std::string> closest = tumble::io::closest_name(word, known);
    return closest ? "; did you mean '" + *closest + "'?" : std::string();
}

// A command-line mistake, said in tumble's words: an unknown command or
// option with the known one it is closest to, else CLI11's message; then
// where the help is. Returns exit_bad_input (CLI11's own codes, 104 to 109,
// would sit beside tumble's).
int usage_error(const CLI::App& app, const CLI::ParseError& error, int argc, char** argv) {
    std::vector<std::string> commands;
    for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; }))
        commands.push_back(command->get_name());
    std::vector<std::string> arguments(argv + 1, argv + argc);
    const auto word = std::find_if(arguments.begin(), arguments.end(),
                                   [](const std::string& a) { return !a.starts_with("-"); });
    std::string message;
    std::string help = "tumble --help";
    if (word != arguments.end() && std::find(commands.begin(), commands.end(), *word) == commands.end()) {
        std::string list;
        for (const std::string& c : commands) list += (list.empty() ? "" : ", ") + c;
        message = "unknown command '" + *word + "'" + suggestion(*word, commands) + "\ncommands: " + list;
    } else if (word != arguments.end()) {
        const CLI::App& command = *app.get_subcommand(*word);
        const std::vector<std::string> known = long_options(command);
        for (auto a = std::next(word); a != arguments.end(); ++a) {
            const std::string name = a->substr(0, a->find('='));
            if (name.starts_with("--") && std::find(known.begin(), known.end(), name) == known.end())
                message += (message.empty() ? "" : "\n") + std::string("unknown option '") + name + "' of tumble " +
                           *word + suggestion(name, known);
        }
        help = "tumble " + *word + " --help";
    }
    if (message.empty()) message = error.what();
    fmt::print(stderr, "tumble: error: {}\nsee '{}'\n", message, help);
    return tumble::experiments::exit_bad_input;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace tumble::cli;
    std::setvbuf(stdout, nullptr, _IOLBF, 0);  // each report line reaches a log file at once
    // A file-size limit (ulimit -f) would end the process with SIGXFSZ, with
    // no message and the file cut; ignored, the write fails with EFBIG and
    // its writer names the file and the reason ("File too large").
    std::signal(SIGXFSZ, SIG_IGN);
    // The messages that suggest a command name the program as it was invoked.
    if (argc > 0 && argv[0] != nullptr) tumble::experiments::set_program_name(argv[0]);
    CLI::App app{"tumble: discrete-element simulation of visco-elastic spheres (Kohring's contact model)"};
    app.set_version_flag("--version", std::string("tumble ") + TUMBLE_VERSION);
    app.require_subcommand(1);
    app.footer("Environment: TUMBLE_ISA=baseline|avx2|avx512|avx512-wide runs the hot loops on that instruction "
               "set (default: the widest this processor has, 512-bit vectors only on processors that run them at "
               "full rate; docs/BENCHMARKS.md, \"Portable binary\").");

    RunOptions run;
    CLI::App* run_cmd = app.add_subcommand("run", "Simulate a scenario file (TOML; see docs/SCENARIO.md)");
    run_cmd->add_option("scenario", run.scenario_file, "Scenario file")->required();
    run_cmd->add_option("-o,--out", run.output_directory, "Output directory (default: the scenario's [output] directory)");
    run_cmd->add_flag("--force", run.force, "Overwrite the output of an earlier run in that directory");
    run_cmd->add_flag("-q,--quiet", run.quiet, "Print nothing but errors");
    add_progress_option(run_cmd, run.progress_every);
    add_checkpoint_options(run_cmd, run.checkpoints);
    run_cmd->add_option("--checkpoint-every-steps", run.checkpoints.every_steps, "Steps between checkpoints (default: none)")
        ->check(CLI::NonNegativeNumber);
    const char* threads_help = "Threads of the time step (0: every core; default 1)";
    run_cmd->add_option("--threads", run.threads, threads_help)->check(thread_count);
    const char* memory_help = "Refuse a run estimated to need more memory than this, GiB (default: half the machine's)";
    run_cmd->add_option("--max-memory", run.max_memory_gib, memory_help)->check(finite_positive);
    const char* fields_help =
        "Coarse-grained fields averaged during the run into RUN/fields (fields.vti, fields.csv), KEY=VALUE items, "
        "repeated or separated by spaces: every (s, default 0.01), from (s of simulated time, default 0), samples (the "
        "most states), lo, hi (X,Y,Z; default the domain's box), cell, cells (NX,NY,NZ), average, kernel, width, format, "
        "frame (lab, or drum: tumble drum only, the cross-section into RUN/flowing_layer with the drum frame's profile "
        "found from it at the end), span (the drum frame's, default 0.5) (tumble run: they replace the scenario file's "
        "[fields]; docs/FIELDS.md, \"During a run\")";
    const auto add_fields_option = [&](CLI::App* command, std::vector<std::string>& items) {
        command->add_option("--fields", items, fields_help)
            ->expected(1)
            ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    };
    add_fields_option(run_cmd, run.fields);
    run_cmd->add_flag("--allow-soft", run.allow_soft,
                      "Accept a material whose grains sink more than 5 % of their radius into each other under their "
                      "own weight (refused otherwise: usually E in MPa given as Pa)");

    BenchOptions bench;
    CLI::App* bench_cmd = app.add_subcommand(
        "bench", "Speed: the paper's dense periodic cube, or a long flowing drum (docs/BENCHMARKS.md)");
    bench_cmd->add_option("--case", bench.bench_case,
                          "cube (default) or long-drum (tumble drum --length 0.64 --fill 0.3, from a settled bed "
                          "made once and kept)")
        ->check(CLI::IsMember({"cube", "long-drum"}));
    auto* size_opt = bench_cmd->add_option("--size", bench.size, "Cube: spheres per lattice edge (21: 9261, the paper's; 46: 97336)")
        ->check(CLI::Range(4, 400));
    bench_cmd->add_option("--steps", bench.steps, "Timed steps (default 2000; long drum 10000)")->check(CLI::PositiveNumber);
    bench_cmd->add_option("--warmup", bench.warmup, "Untimed steps before timing (default 200; long drum 2000, turning)")
        ->check(CLI::NonNegativeNumber);
    auto* seed_opt = bench_cmd->add_option("--seed", bench.seed, "Cube: seed of the random initial velocities");
    bench_cmd->add_flag("--json", bench.json, "Print one JSON object instead of the table");
    bench_cmd->add_option("--threads", bench.threads, threads_help)->check(thread_count);
    auto* length_opt = bench_cmd->add_option("--length", bench.length, "Long drum: inner length, m (default 0.64)")
        ->check(finite_positive);
    auto* fill_opt = bench_cmd->add_option("--fill", bench.fill, "Long drum: fill fraction (default 0.3)")
        ->check(finite_positive);
    auto* turned_opt = bench_cmd->add_option(
        "--turned", bench.turned,
        "Long drum: start from the settled bed turned this many revolutions at the drum's speed, a bed in steady "
        "flow (made once and kept beside the settled one; default 0: the settled bed)")
        ->check(finite_non_negative);
    auto* skin_opt = bench_cmd->add_option(
        "--skin", bench.skin,
        "Long drum: the neighbour-list skin of the timed steps, m (default 0: the drum's automatic skin, 0.3 x the "
        "largest radius; the bed's list found anew)")
        ->check(finite_non_negative);
    auto* law_opt = bench_cmd->add_option(
        "--law", bench.law,
        "Long drum: the contact law of the timed steps: drum (default: tumble drum's, the paper's) or peer (the "
        "law of the LAMMPS deck bench/peers/lammps_drum.in: no attraction, the tangential spring held at the "
        "friction limit; the same bed and step)")
        ->check(CLI::IsMember({"drum", "peer"}));
    auto* walls_opt = bench_cmd->add_option(
        "--walls", bench.walls,
        "Long drum: particles (default: the wall of spheres, the paper's) or smooth (a smooth cylinder and two "
        "discs); each its own settled bed")
        ->check(CLI::IsMember(tumble::keywords(tumble::drum_wall_kinds)));
    auto* cache_opt = bench_cmd->add_option(
        "--cache", bench.cache, "Long drum: directory of the settled beds (default: bench-cache beside the executable)");
    auto* export_opt = bench_cmd->add_option(
        "--export", bench.export_dir,
        "Long drum: write the settled (or --turned) bed to DIR/snapshots/000000.csv and stop (the start of the LAMMPS peer, "
        "bench/compare_drum.sh)");

    // tumble drum: every setting of the drum file can be given here too.
    DrumOptions drum;
    std::string drum_config;
    std::optional<double> omega, rpm, froude, revolutions, length, diameter, wall_radius, dt, fill;
    std::optional<std::int64_t> grains, seed;
    std::optional<int> samples, bins, band_bins, snapshots;
    std::optional<std::string> mode, out, shear, friction_normal, tangential_stiffness;
    CLI::App* drum_cmd = app.add_subcommand(
        "drum", "The paper's rotating-drum diffusion experiment (defaults: the paper's set-up, two components, "
                "5 rad/s, 12 revolutions; see docs/DRUM.md)");
    drum_cmd->add_option("--config", drum_config, "Drum settings file (TOML; examples/drum_*.toml)");
    drum_cmd->add_option("--mode", mode, "two-component or self");
    auto* grains_opt = drum_cmd->add_option("--grains", grains, "Total number of grains (default 1000)")
                           ->check(CLI::Range(std::int64_t{2}, std::int64_t{10'000'000}));
    drum_cmd->add_option("--fill", fill, "Fill fraction of the drum to aim at, instead of --grains")
        ->check(finite_positive)
        ->excludes(grains_opt);
    auto* omega_opt = drum_cmd->add_option("--omega", omega, "Rotation speed, rad/s");
    auto* rpm_opt = drum_cmd->add_option("--rpm", rpm, "Rotation speed, revolutions per minute");
    auto* froude_opt = drum_cmd->add_option("--froude", froude, "Rotation speed as Froude number omega^2 R / g");
    omega_opt->excludes(rpm_opt)->excludes(froude_opt);
    rpm_opt->excludes(froude_opt);
    drum_cmd->add_option("--revolutions", revolutions, "Revolutions after settling");
    std::optional<double> until_band_change;
    drum_cmd->add_option("--until-band-change", until_band_change,
                         "End the rotation early once the band count has differed from the start's for this many "
                         "revolutions (a prepared start's bands merged or dissolved; docs/BAND-ANALYSIS.md; default 0: off)");
    drum_cmd->add_option("--samples", samples, "Samples per revolution (default 20)");
    drum_cmd->add_option("--bins", bins, "Axial bins of the concentration profile (default 12)");
    drum_cmd->add_option("--band-bins", band_bins, "Axial bins of the band profile (default 0: L / 4 mm; docs/BAND-ANALYSIS.md)");
    drum_cmd->add_option("--snapshots", snapshots, "Particle snapshots per revolution (default 8; 0: none)");
    drum_cmd->add_option("--length", length, "Inner length of the drum, m (default 0.12)");
    drum_cmd->add_option("--diameter", diameter, "Inner diameter of the drum, m (default 0.08)");
    drum_cmd->add_option("--wall-radius", wall_radius, "Radius of the wall particles, m (default 0.003)");
    std::optional<double> spin_up_seconds, spin_up_revolutions;
    auto* spin_s = drum_cmd->add_option("--spin-up", spin_up_seconds,
                                        "Linear spin-up from rest to full speed over this many seconds (default 0)");
    drum_cmd->add_option("--spin-up-revolutions", spin_up_revolutions,
                         "The spin-up's length in revolutions at full speed (omega T / 2 pi)")
        ->excludes(spin_s);
    bool periodic_axis = false;
    drum_cmd->add_flag("--periodic-axis", periodic_axis,
                       "No end caps: the axis is periodic, the drum's length its period");
    std::optional<std::string> drum_walls;
    drum_cmd->add_option("--walls", drum_walls,
                         "What walls the drum: particles (default: a wall of spheres, the paper's), smooth (a "
                         "smooth cylinder and two discs) or mesh (the mantle in triangles: --mesh FILE, or the "
                         "smooth cylinder's)")
        ->check(CLI::IsMember(tumble::keywords(tumble::drum_wall_kinds)));
    std::optional<std::string> drum_mesh;
    std::optional<double> drum_mesh_scale;
    drum_cmd->add_option("--mesh", drum_mesh,
                         "The drum's mantle from this STL file (binary or ASCII), lifters and baffles with it, in the "
                         "drum's frame: the axis z through the origin, the caps at z = +-length/2 (implies --walls mesh)");
    drum_cmd->add_option("--mesh-scale", drum_mesh_scale, "The --mesh file's unit in m (default 1; 1e-3: mm)")
        ->check(finite_positive);
    std::optional<double> cap_friction, small_volume_fraction;
    std::optional<std::string> arrangement, ends;
    std::optional<int> bands;
    std::vector<double> band_widths, boundaries;
    drum_cmd->add_option("--cap-friction", cap_friction,
                         "Friction coefficient between the grains and the end caps (default: the caps' material's, "
                         "the wall's 0.2)")
        ->check(finite_non_negative);
    drum_cmd->add_option("--arrangement", arrangement,
                         "Axial arrangement at the start: halves (default: large left, small right), mixed, bands "
                         "or boundaries")
        ->check(CLI::IsMember(tumble::keywords(tumble::arrangements)));
    drum_cmd->add_option("--bands", bands, "With --arrangement bands: the number of alternating bands (>= 2)");
    drum_cmd->add_option("--band-widths", band_widths,
                         "With --arrangement bands: the bands' widths as fractions of the length, summing to 1 "
                         "(w1,w2,...; default equal)")
        ->delimiter(',');
    drum_cmd->add_option("--boundaries", boundaries,
                         "With --arrangement boundaries: the z (m, from the drum's centre) between bands, "
                         "increasing (z1,z2,...)")
        ->delimiter(',');
    drum_cmd->add_option("--ends", ends,
                         "Bands, boundaries: the species of the left end band, small (default) or large (odd band "
                         "counts: both ends)")
        ->check(CLI::IsMember(tumble::keywords(tumble::species_names)));
    drum_cmd->add_option("--small-volume-fraction", small_volume_fraction,
                         "The small grains' share of the grains' volume, 0 < F < 1 (default: equal masses, 0.5)");
    drum_cmd->add_option("--dt", dt, "Time step, s (default: chosen from the materials)");
    std::optional<double> skin;
    drum_cmd->add_option("--skin", skin,
                         "Neighbour-list skin, m: pairs within contact plus this are listed, the list rebuilt when a "
                         "grain has moved half of it (default 0: 0.3 x the largest radius; speed only)");
    drum_cmd->add_option("--shear", shear, "Reading of the friction limit: paper (default), coulomb or spring (docs/MODEL.md)")
        ->check(CLI::IsMember(tumble::keywords(tumble::shear_models)));
    std::optional<double> surface_energy;
    drum_cmd->add_option("--surface-energy", surface_energy,
                         "Surface energy W of every pair, J/m^2: the attraction and pull-off force (default: each "
                         "pair's own, the paper's 0.2; 0: cohesionless grains)");
    drum_cmd->add_option("--friction-normal", friction_normal,
                         "Normal force that limits friction: net (the paper's, default) or jkr")
        ->check(CLI::IsMember(tumble::keywords(tumble::friction_normals)));
    drum_cmd->add_option("--tangential-stiffness", tangential_stiffness,
                         "Stiffness of the shear and twisting springs: paper (16/3 G* a, default) or mindlin "
                         "(8 G* a; docs/MODEL.md)")
        ->check(CLI::IsMember(tumble::keywords(tumble::tangential_stiffnesses)));
    drum_cmd->add_flag("--allow-unsafe-dt", drum.allow_unsafe_dt,
                       "Accept a --dt above the safe maximum (experts and tests; the blow-up check still stops the run)");
    drum_cmd->add_option("--seed", seed, "Seed of the random filling (0 to 2^63 - 1)")->check(seed_range);
    drum_cmd->add_option("-o,--out", out, "Run directory (default drum-out)");
    drum_cmd->add_flag("--force", drum.force, "Overwrite an earlier run in that directory");
    drum_cmd->add_flag("-q,--quiet", drum.quiet, "Print nothing but errors");
    add_progress_option(drum_cmd, drum.progress_every);
    bool no_plot = false;
    drum_cmd->add_flag("--no-plot", no_plot, "Do not draw the figures at the end");
    add_checkpoint_options(drum_cmd, drum.checkpoints);
    drum_cmd->add_option("--checkpoint-every-revolutions", drum.checkpoint_revolutions,
                         "Revolutions between checkpoints while the drum turns (default 1; 0: not by revolutions)")
        ->check(finite_non_negative);
    drum_cmd->add_option("--threads", drum.threads, threads_help)->check(thread_count);
    drum_cmd->add_option("--max-memory", drum.max_memory_gib, memory_help)->check(finite_positive);
    add_fields_option(drum_cmd, drum.fields);
    drum_cmd->add_flag("--large-drum", drum.large_drum,
                       "Accept a drum whose wall takes more than 50 times as many spheres as it holds grains and more "
                       "than 100,000 (refused otherwise: usually a size in cm given as m)");
    for (CLI::Option* option : drum_cmd->get_options())
        if (option->get_expected_min() > 0) option->check(not_empty);

    ContactOptions contact;
    bool contact_drum = false;
    std::string contact_drum_config;
    std::optional<std::string> contact_mode;
    std::optional<double> contact_dt, contact_wall_radius, contact_surface_energy;
    std::optional<std::string> contact_tangential_stiffness;
    CLI::App* contact_cmd = app.add_subcommand(
        "contact", "Each pair of materials of a scenario or of the drum: collision time, restitution at the step and "
                   "converged, equilibrium overlap, pull-off force, sticking speed, and the time step's criterion "
                   "(docs/MODEL.md)");
    auto* contact_file = contact_cmd->add_option("scenario", contact.scenario_file, "Scenario file (TOML)");
    auto* contact_drum_flag = contact_cmd->add_flag("--drum", contact_drum, "The drum (tumble drum's defaults and the options below)")
                                  ->excludes(contact_file);
    contact_cmd->add_option("--config", contact_drum_config, "Drum settings file (with --drum)")->needs(contact_drum_flag);
    contact_cmd->add_option("--mode", contact_mode, "Drum mode: two-component or self (with --drum)")->needs(contact_drum_flag);
    contact_cmd->add_option("--wall-radius", contact_wall_radius, "Radius of the drum's wall particles, m (with --drum)")
        ->needs(contact_drum_flag);
    contact_cmd->add_option("--dt", contact_dt, "Time step of the drum, s (with --drum; default: chosen)")
        ->needs(contact_drum_flag);
    std::optional<std::string> contact_walls;
    contact_cmd->add_option("--walls", contact_walls, "The drum's walls: particles (default) or smooth (with --drum)")
        ->check(CLI::IsMember(tumble::keywords(tumble::drum_wall_kinds)))
        ->needs(contact_drum_flag);
    contact_cmd->add_option("--surface-energy", contact_surface_energy,
                            "Surface energy W of every pair of the drum, J/m^2 (with --drum; default the paper's 0.2)")
        ->needs(contact_drum_flag);
    contact_cmd->add_option("--tangential-stiffness", contact_tangential_stiffness,
                            "Stiffness of the shear and twisting springs of the drum: paper or mindlin (with --drum)")
        ->check(CLI::IsMember(tumble::keywords(tumble::tangential_stiffnesses)))
        ->needs(contact_drum_flag);
    contact_cmd->add_flag("--allow-unsafe-dt", contact.allow_unsafe_dt,
                          "Accept a --dt above the safe maximum (to see what a larger step would do)")
        ->needs(contact_drum_flag);
    contact_cmd->add_flag("--allow-soft", contact.allow_soft,
                          "Accept materials so soft, or pairs so sticky, that grains sink into each other "
                          "(refused otherwise, as by tumble run)");
    contact_cmd->add_option("--speeds", contact.speeds, "Impact speeds, m/s (default 0.05 0.1 0.3 1 1.4)")
        ->check(impact_speed);
    contact_cmd->add_flag("--json", contact.json, "Print one JSON object instead of the table");

    std::string resume_dir;
    bool resume_quiet = false;
    double resume_progress_every = tumble::experiments::default_progress_every;
    CLI::App* resume_cmd = app.add_subcommand(
        "resume", "Continue an interrupted run (tumble run or drum) from its newest intact checkpoint "
                  "(docs/CHECKPOINTS.md)");
    resume_cmd->add_option("directory", resume_dir, "Run directory")->required();
    resume_cmd->add_flag("-q,--quiet", resume_quiet, "Print nothing but errors");
    add_progress_option(resume_cmd, resume_progress_every);
    double resume_revolutions = 0.0;
    resume_cmd->add_option("--revolutions", resume_revolutions,
                           "A drum run: turn it to this many revolutions in all, more than it has turned: a run that "
                           "has finished goes on from its end (docs/CHECKPOINTS.md)")
        ->check(finite_positive);

    std::string analyze_dir;
    CLI::App* analyze_cmd = app.add_subcommand("analyze", "Analyse a drum run directory again (summary.json, summary.txt)");
    analyze_cmd->add_option("directory", analyze_dir, "Run directory of tumble drum")->required();
    double first_revolution = 1.0;
    auto* first_revolution_opt = analyze_cmd->add_option(
        "--first-revolution", first_revolution, "Leave the start-up out of the fits: use revolutions N >= this (default 1)")
        ->check(finite_non_negative);
    bool so_far = false;
    analyze_cmd->add_flag("--so-far", so_far,
                          "The bands of the revolutions written so far, of a run stopped, unfinished or going on, into "
                          "DIR/so_far/ (docs/BAND-ANALYSIS.md); the run's own files untouched")
        ->excludes(first_revolution_opt);
    // The band segmentation's thresholds (analysis::BandOptions; docs/BAND-ANALYSIS.md);
    // checked, naming the option, before anything is read.
    tumble::analysis::BandOptions band_options;
    analyze_cmd->add_option("--band-z-enter", band_options.z_enter,
                            "A new band's mean deviation in standard errors of a random mix (default 4)");
    analyze_cmd->add_option("--band-z-leave", band_options.z_leave,
                            "The same for a band to stay, at most --band-z-enter (default 2)");
    analyze_cmd->add_option("--band-min-contrast", band_options.min_contrast,
                            "A new band's least mean deviation in volume fraction (default 0.05)");
    analyze_cmd->add_option("--band-min-contrast-leave", band_options.min_contrast_leave,
                            "The same for a band to stay, at most --band-min-contrast (default 0.025)");
    analyze_cmd->add_option("--band-smoothing", band_options.smoothing,
                            "Bins of the running mean that decides the sign of the deviation (default 3)");
    analyze_cmd->add_option("--band-min-width", band_options.min_width, "A band's least width in bins (default 2)");
    bool analyze_band_report = false;
    analyze_cmd->add_flag("--band-report", analyze_band_report,
                          "Print the band analysis even for a run without bands (by default only a banded start, "
                          "--until-band-change, or bands that formed during the run print it; its files are written "
                          "either way)");

    std::vector<std::string> plot_inputs;
    std::string plot_out;
    bool plot_compare = false;
    CLI::App* plot_cmd = app.add_subcommand("plot", "The paper's figures from drum run directories (PNG and SVG)");
    plot_cmd->add_option("directories", plot_inputs, "Drum run directories (several with --compare)")->required();
    plot_cmd->add_flag("--compare", plot_compare, "Overlay <z>(N) of several runs (the paper's figs. 2 and 4)");
    plot_cmd->add_option("-o,--out", plot_out, "Where the figures go (default DIR/figures)");
    bool plot_band_report = false;
    plot_cmd->add_flag("--band-report", plot_band_report,
                       "Draw the band figure (fig_bands) even for a run without bands (by default only for a run "
                       "whose summary reports bands)");

    RenderOptions render;
    CLI::App* render_cmd = app.add_subcommand(
        "render", "A movie (MP4) of a run's particle snapshots: two views (a drum along its axis and from the side), "
                  "the clock and a legend (frames in DIR/frames; see docs/RENDER.md)");
    render_cmd->add_option("directory", render.directory, "Run directory of tumble drum or tumble run")->required();
    render_cmd->add_option("-o,--out", render.out, "The movie file (default DIR/NAME.mp4, NAME the directory's)");
    render_cmd->add_option("--fps", render.fps,
                           "Frames per second of the movie (default: a movie of about 6 s or more, at most 25)")
        ->check(CLI::Range(1, 240));
    render_cmd->add_option("--width", render.width, "Pixels of each of the two views (default 640)")
        ->check(CLI::Range(16, 8192));
    render_cmd->add_option("--color", render.colour,
                           "Grains coloured by material or tag (default: tag, the starting half, for a "
                           "self-diffusion drum run; material otherwise)")
        ->check(CLI::IsMember({"material", "tag"}));
    render_cmd->add_flag("--frames-only", render.frames_only, "Write the frames only, no movie (no ffmpeg needed)");
    render_cmd->add_option("-j,--jobs", render.jobs, "Threads drawing frames (default: the logical cores)")
        ->check(CLI::PositiveNumber);
    render_cmd->add_flag("-q,--quiet", render.quiet, "Print nothing but errors");

    FieldsOptions fields;
    std::vector<double> fields_lo, fields_hi, fields_cells;
    std::optional<double> fields_cell, fields_width;
    std::string fields_kernel = "gaussian";
    CLI::App* fields_cmd = app.add_subcommand(
        "fields", "Coarse-grained fields of a run on a grid: solid fraction, velocity, temperature, stress, "
                  "shear rate, inertial number and friction, as VTK image data and CSV (docs/FIELDS.md)");
    fields_cmd->add_option("directory", fields.run.run_directory, "Run directory of tumble run or tumble drum")
        ->required();
    fields_cmd->add_option("--lo", fields_lo, "The grid's lower corner X,Y,Z, m (default: the grains' extent)")
        ->delimiter(',')
        ->expected(3);
    fields_cmd->add_option("--hi", fields_hi, "The grid's upper corner X,Y,Z, m (default: the grains' extent)")
        ->delimiter(',')
        ->expected(3);
    auto* cell_opt = fields_cmd->add_option("--cell", fields_cell,
                                            "Cell size along every resolved axis, m (default: the width); hi moves "
                                            "up to a whole number of cells");
    fields_cmd->add_option("--cells", fields_cells, "Cells along x, y and z, NX,NY,NZ (1 on an averaged axis)")
        ->delimiter(',')
        ->expected(3)
        ->excludes(cell_opt);
    fields_cmd->add_option("--average", fields.run.settings.average,
                           "Axes averaged over [lo, hi], e.g. z (a drum's cross-section) or xy (a profile in z)");
    fields_cmd->add_option("--kernel", fields_kernel, "gaussian (cut off at 3 widths; default) or lucy")
        ->check(CLI::IsMember({"gaussian", "lucy"}));
    fields_cmd->add_option("--width", fields_width, "Kernel width w, m (default: the grains' mean radius)");
    fields_cmd->add_option("--frame", fields.run.frame,
                           "lab (default) or drum: a drum run's cross-section (averaged along z), its free surface, "
                           "and the depth profile below it (profile.csv, drum_frame.json)")
        ->check(CLI::IsMember({"lab", "drum"}));
    fields_cmd->add_option("--span", fields.run.span,
                           "The drum frame: the middle part of the free surface's length that the surface fit and "
                           "the profile use, in (0, 1] (default 0.5)");
    std::vector<double> fields_frame_cells;
    fields_cmd->add_option("--frame-cells", fields_frame_cells,
                           "The drum frame: cells NS,NZ along the surface (across the span) and the axis of a grid "
                           "in the drum's coordinates besides the profile (frame.csv; default 1,1: none)")
        ->delimiter(',')
        ->expected(2);
    fields_cmd->add_option("--samples", fields.run.samples, "States averaged (default 1)");
    fields_cmd->add_option("--every", fields.run.every, "Simulated seconds between the states (default 0.01)");
    fields_cmd->add_option("--checkpoint", fields.run.checkpoint,
                           "The checkpoint the states start from (default: the run's newest)");
    fields_cmd->add_option("-o,--out", fields.out,
                           "Where fields.vti and fields.csv go (default DIR/fields; with --frame drum "
                           "DIR/flowing_layer)");
    fields_cmd->add_option("--format", fields.format, "vti, csv or both (default)")
        ->check(CLI::IsMember({"vti", "csv", "both"}));
    fields_cmd->add_option("--max-memory", fields.run.settings.max_memory_gib,
                           "Refuse a grid that needs more memory than this many GiB (default: half the machine's)")
        ->check(finite_non_negative);
    fields_cmd->add_flag("-q,--quiet", fields.quiet, "Print nothing but errors");

    SweepOptions sweep;
    CLI::App* sweep_cmd = app.add_subcommand(
        "sweep", "The drum experiment over rotation speeds, modes and seeds, one child run per point "
                 "(resumable; under mpirun or srun the ranks share the points; see docs/SWEEP.md)");
    sweep_cmd->add_option("sweep_file", sweep.sweep_file, "Sweep file (TOML; examples/sweep_*.toml)")->required();
    sweep_cmd->add_option("-o,--out", sweep.output_directory, "Sweep directory (default: the file's [output] directory)");
    sweep_cmd->add_option("-j,--jobs", sweep.jobs,
                          "Points run at once (per MPI rank; default: the cores of this node / its ranks)")
        ->check(CLI::PositiveNumber);
    sweep_cmd->add_flag("--list", sweep.list, "Print the points and their state; run nothing");
    sweep_cmd->add_flag("-q,--quiet", sweep.quiet, "Print nothing but errors and failed points");
    add_progress_option(sweep_cmd, sweep.progress_every);

    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {  // --help, --version
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        return usage_error(app, e, argc, argv);
    }
    // MPI, if a launcher started this process (core/mpi.hpp); finalised on
    // return. An error on one of several ranks ends them all.
    std::optional<tumble::mpi::Session> mpi;
    try {
        mpi.emplace(argc, argv);
        if (tumble::mpi::size() > 1 && !sweep_cmd->parsed() && !run_cmd->parsed() && !drum_cmd->parsed() &&
            !resume_cmd->parsed() && !(bench_cmd->parsed() && bench.bench_case == "long-drum"))
            throw tumble::Error("only tumble sweep (each rank a share of the points), run, drum, resume and bench "
                                "--case long-drum (one simulation shared among the ranks) run on several MPI ranks; "
                                "run this command without mpirun or srun");
        if (run_cmd->parsed()) return run_command(run);
        if (bench_cmd->parsed()) {
            const bool drum_case = bench.bench_case == "long-drum";
            for (CLI::Option* option :
                 {size_opt, seed_opt, length_opt, fill_opt, turned_opt, skin_opt, law_opt, walls_opt, cache_opt,
                  export_opt})
                if (option->count() > 0 && (option == size_opt || option == seed_opt) == drum_case)
                    throw tumble::Error("bench: " + option->get_name() + " does not apply to --case " + bench.bench_case);
            return bench_command(bench);
        }
        if (analyze_cmd->parsed()) {
            tumble::analysis::check_band_options(band_options, [](const std::string& field) {
                std::string option = "--band-" + field;
                std::replace(option.begin(), option.end(), '_', '-');
                return option;
            });
            return analyze_command(analyze_dir, {first_revolution, band_options, analyze_band_report}, so_far);
        }
        if (plot_cmd->parsed())
            return plot_command(plot_compare ? "compare" : "run", plot_inputs, plot_out, false, plot_band_report);
        if (sweep_cmd->parsed()) return sweep_command(sweep);
        if (fields_cmd->parsed()) {
            FieldSettings& f = fields.run.settings;
            if (!fields_lo.empty()) f.lo = tumble::Vec3{fields_lo[0], fields_lo[1], fields_lo[2]};
            if (!fields_hi.empty()) f.hi = tumble::Vec3{fields_hi[0], fields_hi[1], fields_hi[2]};
            if (!fields_cells.empty()) f.cells = std::array<double, 3>{fields_cells[0], fields_cells[1], fields_cells[2]};
            if (!fields_frame_cells.empty()) fields.run.frame_cells = {fields_frame_cells[0], fields_frame_cells[1]};
            f.cell = fields_cell;
            f.width = fields_width;
            f.kernel = fields_kernel == "lucy" ? tumble::analysis::CgKernel::lucy : tumble::analysis::CgKernel::gaussian;
            f.vti = fields.format != "csv";
            return fields_command(fields);
        }
        if (render_cmd->parsed()) return render_command(render);
        if (resume_cmd->parsed()) return resume_command(resume_dir, resume_quiet, resume_progress_every, resume_revolutions);
        if (contact_cmd->parsed()) {
            if (contact.scenario_file.empty() && !contact_drum)
                throw tumble::Error("contact: give a scenario file or --drum");
            tumble::io::DrumSettings& d = contact.drum;
            if (!contact_drum_config.empty()) d = tumble::io::load_drum_settings(contact_drum_config);
            if (contact_mode) d.mode = *contact_mode;
            if (contact_wall_radius) d.geometry.wall_radius = *contact_wall_radius;
            if (contact_dt) d.dt = *contact_dt;
            if (contact_walls) d.geometry.walls = tumble::find_keyword(tumble::drum_wall_kinds, *contact_walls)->value;
            if (contact_surface_energy) d.surface_energy = *contact_surface_energy;
            if (contact_tangential_stiffness)
                d.tangential_stiffness =
                    tumble::find_keyword(tumble::tangential_stiffnesses, *contact_tangential_stiffness)->value;
            tumble::io::check_drum_settings(d, "command line");
            return contact_command(contact);
        }
        if (drum_cmd->parsed()) {
            tumble::io::DrumSettings& d = drum.settings;
            if (!drum_config.empty()) d = tumble::io::load_drum_settings(drum_config);
            using tumble::io::SpeedUnit;
            if (omega) d.speed = *omega, d.speed_unit = SpeedUnit::rad_per_s;
            if (rpm) d.speed = *rpm, d.speed_unit = SpeedUnit::rpm;
            if (froude) d.speed = *froude, d.speed_unit = SpeedUnit::froude;
            if (mode) d.mode = *mode;
            if (grains) d.grains = static_cast<std::size_t>(*grains), d.fill_fraction = 0.0;
            if (fill) d.fill_fraction = *fill;
            if (revolutions) d.revolutions = *revolutions;
            if (until_band_change) d.until_band_change = *until_band_change;
            if (samples) d.samples_per_revolution = *samples;
            if (bins) d.profile_bins = *bins;
            if (band_bins) d.band_bins = *band_bins;
            if (snapshots) d.snapshots_per_revolution = *snapshots;
            if (length) d.geometry.length = *length;
            if (diameter) d.geometry.diameter = *diameter;
            if (wall_radius) d.geometry.wall_radius = *wall_radius;
            if (periodic_axis) d.geometry.periodic_axis = true;
            if (drum_walls) d.geometry.walls = tumble::find_keyword(tumble::drum_wall_kinds, *drum_walls)->value;
            if (drum_mesh) d.mesh = std::filesystem::absolute(*drum_mesh);
            if (drum_mesh_scale) d.mesh_scale = *drum_mesh_scale;
            if (drum_walls && *drum_walls != "mesh" && !d.mesh.empty())
                throw tumble::io::ConfigError("command line", "--walls",
                                              *drum_walls + " walls, but the mantle is the mesh " + d.mesh.string());
            if (drum_mesh || drum_mesh_scale || drum_walls) tumble::io::load_drum_mantle(d, "command line", "--mesh");
            if (cap_friction) d.fill.cap_friction = *cap_friction;
            if (arrangement) d.fill.arrangement = tumble::find_keyword(tumble::arrangements, *arrangement)->value;
            if (bands) d.fill.bands = *bands;
            if (!band_widths.empty()) d.fill.band_widths = band_widths;
            if (!boundaries.empty()) d.fill.boundaries = boundaries;
            if (ends) {
                using tumble::Arrangement;
                if (d.fill.arrangement != Arrangement::bands && d.fill.arrangement != Arrangement::boundaries)
                    throw tumble::Error("command line: --ends applies to --arrangement bands or boundaries, not " +
                                        std::string(tumble::keyword_of(tumble::arrangements, d.fill.arrangement)));
                d.fill.ends = tumble::find_keyword(tumble::species_names, *ends)->value;
            }
            if (small_volume_fraction) d.fill.small_volume_fraction = *small_volume_fraction;
            if (spin_up_seconds) d.spin_up_time = *spin_up_seconds;
            if (spin_up_revolutions) d.spin_up_time = 2.0 * tumble::pi * *spin_up_revolutions / d.omega();
            if (dt) d.dt = *dt;
            if (skin) d.skin = *skin;
            if (shear) d.shear = tumble::find_keyword(tumble::shear_models, *shear)->value;
            if (friction_normal) d.friction_normal = tumble::find_keyword(tumble::friction_normals, *friction_normal)->value;
            if (tangential_stiffness)
                d.tangential_stiffness =
                    tumble::find_keyword(tumble::tangential_stiffnesses, *tangential_stiffness)->value;
            if (surface_energy) d.surface_energy = *surface_energy;
            if (seed) d.seed = static_cast<std::uint64_t>(*seed);
            if (out) d.output = *out;
            drum.plot = !no_plot;
            tumble::io::check_drum_settings(d, "command line");
            return drum_command(drum);
        }
    } catch (const BlewUp& e) {
        fmt::print(stderr, "tumble: {}error: {}\n", tumble::mpi::line_prefix(), e.what());
        tumble::mpi::abort_others(exit_blew_up);
        return exit_blew_up;
    } catch (const tumble::Error& e) {
        fmt::print(stderr, "tumble: {}error: {}\n", tumble::mpi::line_prefix(), e.what());
        tumble::mpi::abort_others(exit_bad_input);
        return exit_bad_input;
    } catch (const std::exception& e) {
        fmt::print(stderr, "tumble: {}unexpected error: {}\n", tumble::mpi::line_prefix(), e.what());
        tumble::mpi::abort_others(exit_unexpected);
        return exit_unexpected;
    }
    return 1;
}
