// SPDX-License-Identifier: MIT
// The subcommands. Each returns the process exit code.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "experiments/drum.hpp"
#include "experiments/fields.hpp"
#include "experiments/machine.hpp"
#include "experiments/progress.hpp"
#include "experiments/run_control.hpp"
#include "io/checkpoint.hpp"
#include "io/drum_config.hpp"

namespace tumble::cli {

// The commands are built on the experiments layer (run control, progress,
// limits, the drum protocol).
using namespace tumble::experiments;

struct RunOptions {
    std::string scenario_file;
    std::string output_directory;  // empty: the scenario's [output] directory
    bool force = false;            // overwrite an earlier run's output
    bool quiet = false;
    double progress_every = default_progress_every;  // s between progress lines when not on a terminal; 0: none
    CheckpointPolicy checkpoints;
    int threads = 1;               // 0: every core of the machine (resolve_threads)
    double max_memory_gib = 0.0;   // refuse a run estimated to need more; 0: half the machine's (experiments/limits.hpp)
    bool allow_soft = false;       // accept grains that sink into each other under their weight (check_stiffness)
    std::vector<std::string> fields;  // --fields KEY=VALUE: fields taken during the run (parse_fields_during_run)
};
int run_command(const RunOptions& options);

struct BenchOptions {
    std::string bench_case = "cube";  // "cube" (the paper's benchmark) or "long-drum" (docs/BENCHMARKS.md)
    int size = 21;             // cube: lattice edge, 21 -> 9261 spheres (the paper's), 46 -> 97336
    std::optional<std::int64_t> steps;   // timed steps; default 2000 (cube), 10000 (long drum)
    std::optional<std::int64_t> warmup;  // untimed steps first; default 200 (cube), 2000 (long drum, turning)
    std::uint64_t seed = 1;
    bool json = false;
    int threads = 1;           // 0: every core of the machine (resolve_threads)
    double length = 0.64;      // long drum: inner length, m
    double fill = 0.3;         // long drum: fill fraction
    double skin = 0.0;         // long drum: the neighbour skin of the timed steps, m (0: the bed's, automatic)
    double turned = 0.0;       // long drum: revolutions the settled bed turns before the warm-up (a bed in steady flow; kept too)
    std::string law = "drum";  // long drum: the timed steps' law, "drum" (tumble drum's) or "peer" (the LAMMPS deck's)
    std::string walls = "particles";  // long drum: the drum's walls (keyword of drum_wall_kinds, setup/drum.hpp)
    std::filesystem::path cache;  // long drum: where the settled bed is kept; empty: bench-cache beside the executable
    std::filesystem::path export_dir;  // long drum: write the settled bed there (snapshots/000000.csv) and stop
};
int bench_command(const BenchOptions& options);

using DrumOptions = experiments::DrumRunOptions;
int drum_command(const DrumOptions& options);

// tumble contact: each kind of contact of a scenario file, or of the drum
// (scenario_file empty), at the given impact speeds (docs/MODEL.md).
struct ContactOptions {
    std::string scenario_file;
    io::DrumSettings drum;  // when scenario_file is empty
    bool allow_unsafe_dt = false;  // the drum's --dt may exceed the safe maximum
    bool allow_soft = false;       // as tumble run's (check_stiffness)
    std::vector<double> speeds{0.05, 0.1, 0.3, 1.0, 1.4};  // m/s
    bool json = false;
};
int contact_command(const ContactOptions& options);

// tumble resume DIR: continue a run of `tumble run` or `tumble drum` from its
// newest intact checkpoint (docs/CHECKPOINTS.md). progress_every: seconds
// between progress lines when not on a terminal (0: none). revolutions > 0:
// a drum run's new length (`--revolutions`; a finished run goes on).
int resume_command(const std::string& directory, bool quiet, double progress_every, double revolutions = 0.0);
int resume_run(io::Checkpoint checkpoint, const std::filesystem::path& directory, bool quiet, double progress_every);
int resume_drum(io::Checkpoint checkpoint, const std::filesystem::path& directory, bool quiet, double progress_every,
                double revolutions);

// Re-analyse a drum run directory: summary.json, summary.txt.
// options: the start-up left out of the fits and the band thresholds
// (io::AnalyzeOptions); so_far: the bands of an unfinished run
// (experiments::analyze_bands_so_far).
int analyze_command(const std::string& directory, const io::AnalyzeOptions& options, bool so_far = false);

// The figures (tools/plot_drum.py MODE INPUTS... [--out OUT]); mode "run"
// (a drum run directory), "compare" (several) or "sweep" (a sweep table).
// Returns the script's exit code (2: bad input, 3: no python3/matplotlib).
// A directory of "run" or "compare" that is not a drum run's is refused
// first (experiments::require_drum_run). band_report: the band figure even
// for a run without bands.
int plot_command(const std::string& mode, const std::vector<std::string>& inputs, const std::string& out,
                 bool quiet = false, bool band_report = false);

struct RenderOptions {
    std::string directory;     // a run directory of tumble drum or tumble run
    std::string out;           // the MP4; empty: DIR/NAME.mp4, NAME the run directory's
    int fps = 0;               // 0: chosen for a movie of about 6 s or more, at most 25
    int width = 640;           // pixels of each of the two views
    std::string colour;        // "material" or "tag"; empty: tag for a self-diffusion drum run, else material
    bool frames_only = false;  // frames/NNNNNN.png only, no movie (no ffmpeg needed)
    unsigned jobs = 0;         // threads drawing frames; 0: the machine's logical cores
    bool quiet = false;
};
// A movie of the run's particle snapshots (docs/RENDER.md).
int render_command(const RenderOptions& options);

// tumble fields: the coarse-grained fields of a run directory
// (experiments/fields.hpp, docs/FIELDS.md) into OUT/fields.vti and
// OUT/fields.csv.
struct FieldsOptions {
    RunFieldsOptions run;
    std::string out;              // empty: RUN/fields
    std::string format = "both";  // "vti", "csv" or "both"
    bool quiet = false;
};
int fields_command(const FieldsOptions& options);

}  // namespace tumble::cli
