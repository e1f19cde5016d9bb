// SPDX-License-Identifier: MIT
// The drum experiment of the paper as a library (docs/DRUM.md): what the
// command line (`tumble drum`, `resume`, `analyze`) and, later, a Python
// module call. It writes a run directory (io/) and drives the engine; it
// prints progress and the summary unless quiet, and draws no figures.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "experiments/fields.hpp"
#include "experiments/progress.hpp"
#include "experiments/run_control.hpp"
#include "io/checkpoint.hpp"
#include "io/drum_config.hpp"
#include "io/drum_output.hpp"
#include "tumble/analysis/drum_measure.hpp"
#include "tumble/sim/simulation.hpp"

namespace tumble::experiments {

// One sample of the rotation (N = 0, then --samples per revolution, and the
// final state), as written to drum_series.csv and profiles.csv: what a
// caller's hook sees. The references are valid during the call only.
struct DrumSample {
    double revolutions = 0.0;  // N since the start of rotation
    const analysis::DrumState& state;
    const Simulation& simulation;
};
// Called after each sample is written. An exception it throws ends the run
// (the run directory keeps its newest checkpoint: resume continues it).
using DrumSampleHook = std::function<void(const DrumSample&)>;

struct DrumRunOptions {
    io::DrumSettings settings;  // from --config and the command line
    bool force = false;         // overwrite an earlier run in the directory (one tumble wrote)
    bool quiet = false;
    double progress_every = default_progress_every;  // s between progress lines when not on a terminal; 0: none
    bool plot = true;           // the caller should draw the figures at the end (kept for a resume)
    CheckpointPolicy checkpoints;         // every_steps unused: see checkpoint_revolutions
    double checkpoint_revolutions = 1.0;  // revolutions between checkpoints while turning; 0: not by revolutions
    bool allow_unsafe_dt = false;  // accept a dt above the safe maximum (then only the blow-up check guards the run)
    int threads = 1;               // 0: every core of the machine (resolve_threads)
    double max_memory_gib = 0.0;   // refuse a run estimated to need more; 0: half the machine's (limits.hpp)
    bool large_drum = false;       // accept a wall far larger than its grains (check_drum_size)
    DrumSampleHook on_sample;      // none by default (the Python module passes its callback)
    std::vector<std::string> fields;  // KEY=VALUE: fields taken during the run (parse_fields_during_run); none if empty
};

// How a run ended: exit_code 0 (finished and analysed), exit_stopped (a
// checkpoint to resume from); whether figures were asked for; where.
struct DrumOutcome {
    int exit_code = 0;
    bool plot = false;
    std::filesystem::path directory;
};

// A new run into options.settings.output. Throws tumble::Error for bad
// settings (before any work), BlewUp if the run becomes unphysical.
DrumOutcome run_drum(const DrumRunOptions& options);

// Continues the run of `checkpoint` (the newest intact one of `directory`).
// progress_every: as DrumRunOptions's. revolutions > 0: the run's new
// length, more than it has turned (tumble::Error otherwise, before any
// work); a finished run goes on from its end (its summary is removed, and
// written anew at the new end), and one that ended on its band change
// (--until-band-change) goes on without that watch.
DrumOutcome resume_drum(io::Checkpoint checkpoint, const std::filesystem::path& directory, bool quiet,
                        double progress_every = default_progress_every, double revolutions = 0.0);

// Throws tumble::Error unless `directory` holds a drum run (drum_run.toml),
// saying what `command` (e.g. "analyze") takes instead: for a run of tumble
// run (run.json), that its files are read as they are.
void require_drum_run(const std::string& directory, const std::string& command);

// The analysis of a finished run directory again (summary.json,
// summary.txt), returned as text; options: the start-up left out of the
// fits, the band thresholds. Refuses bad band thresholds (before anything
// is read; analysis::check_band_options), a run in use or unfinished.
std::string analyze_drum(const std::string& directory, const io::AnalyzeOptions& options = {});

// The bands of a run so far (io::analyze_bands_so_far), finished, stopped
// or going on: into DIR/so_far/. Refuses bad thresholds, and a second
// --so-far on the same run at the same time.
std::string analyze_bands_so_far(const std::string& directory, const analysis::BandOptions& options = {});

}  // namespace tumble::experiments
