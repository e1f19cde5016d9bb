// SPDX-License-Identifier: MIT
// tumble drum, and the drum's side of resume and analyze: the experiment
// (experiments/drum.hpp), then the figures (tools/plot_drum.py).
#include <fmt/format.h>

#include "cli/commands.hpp"
#include "experiments/drum.hpp"
#include "tumble/core/mpi.hpp"

namespace tumble::cli {

namespace {

// The figures are a convenience: a machine without matplotlib still has
// every number in the run directory.
int with_figures(const experiments::DrumOutcome& outcome, bool quiet) {
    if (outcome.exit_code == 0 && outcome.plot && mpi::rank() == 0 &&
        plot_command("run", {outcome.directory.string()}, "", quiet) != 0)
        fmt::print(stderr, "tumble drum: warning: the figures could not be drawn ({} plot {})\n",
                   experiments::program_name(), outcome.directory.string());
    return outcome.exit_code;
}

}  // namespace

int drum_command(const DrumOptions& options) { return with_figures(experiments::run_drum(options), options.quiet); }

int resume_drum(io::Checkpoint checkpoint, const std::filesystem::path& directory, bool quiet, double progress_every,
                double revolutions) {
    return with_figures(experiments::resume_drum(std::move(checkpoint), directory, quiet, progress_every, revolutions),
                        quiet);
}

int analyze_command(const std::string& directory, const io::AnalyzeOptions& options, bool so_far) {
    fmt::print("{}", so_far ? experiments::analyze_bands_so_far(directory, options.bands)
                            : experiments::analyze_drum(directory, options));
    return 0;
}

}  // namespace tumble::cli
