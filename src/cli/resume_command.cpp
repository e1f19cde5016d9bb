// SPDX-License-Identifier: MIT
// tumble resume DIR: continue an interrupted run from its newest intact
// checkpoint; a damaged newer one is reported and skipped.
#include <filesystem>
#include <optional>

#include <fmt/format.h>

#include "tumble/core/mpi.hpp"

#include "cli/commands.hpp"
#include "experiments/limits.hpp"
#include "io/run_lock.hpp"
#include "tumble/core/error.hpp"

namespace tumble::cli {

namespace {
// The ranks the newest checkpoint of a run shared among ranks was written on.
std::int64_t load_newest_ranks(const std::string& directory, std::uintmax_t max_bytes) {
    return io::load_newest_checkpoint(directory, max_bytes, {0, 2}).checkpoint.record.integer("ranks");
}
}  // namespace

int resume_command(const std::string& directory, bool quiet, double progress_every, double revolutions) {
    // Under mpirun every rank reads its own checkpoint file (a run shared
    // among ranks, io/checkpoint.hpp); rank 0 holds the lock and talks.
    const io::CheckpointRank who{mpi::rank(), mpi::size()};
    std::optional<io::RunLock> lock;  // held until the run ends
    if (who.rank == 0) lock.emplace(directory);
    const bool talk = !quiet && who.rank == 0;
    // A run goes on on any number of ranks: on as many as it ran on, each
    // rank reads its own file; a run of one process, every rank reads the
    // one file and keeps its slab; a run of another number of ranks, every
    // rank reads every rank's file (the whole state) and keeps its slab.
    const auto max_bytes = static_cast<std::uintmax_t>(memory_limit_bytes(0.0));
    // (A run that went on on one process after ranks, or the reverse, has
    // files of both kinds: the newest moment's decide.)
    const bool shared_files = io::newest_checkpoint_kind(directory, max_bytes).ranks > 1;
    const bool as_many = shared_files && load_newest_ranks(directory, max_bytes) == who.ranks;
    const io::CheckpointRank files = as_many ? who : io::CheckpointRank{};
    io::LoadedCheckpoint loaded = files.ranks > 1   ? io::load_shared_checkpoint(directory, max_bytes, files)
                                  : shared_files ? io::load_whole_checkpoint(directory, max_bytes)
                                                 : io::load_newest_checkpoint(directory, max_bytes, files);
    for (const std::string& why : loaded.rejected)
        fmt::print(stderr, "tumble resume: {}warning: {}; using the previous checkpoint\n", mpi::line_prefix(), why);
    const io::CheckpointRecord& record = loaded.checkpoint.record;
    const std::string command = record.text("command");
    if (revolutions > 0.0 && command != "drum")
        throw Error("--revolutions: the run in " + directory + " is not a drum run (tumble " + command +
                    "); only a drum run is lengthened");
    // A run's results are written before the checkpoint that says it has
    // finished: without them the record is not to be trusted (forged or
    // damaged), and the run is finished again from the checkpoint's state.
    const std::filesystem::path results =
        std::filesystem::path(directory) / (command == "drum" ? "summary.json" : "run.json");
    if (record.integer("finished") && !(revolutions > 0.0)) {
        if (std::filesystem::exists(results)) {
            if (talk)
                fmt::print("tumble resume: the run in {} has finished ({}); nothing to do\n", directory,
                           loaded.file.string());
            return 0;
        }
        if (mpi::rank() == 0)
            fmt::print(stderr, "tumble resume: warning: {} says the run has finished, but {} is missing; finishing "
                               "it from there\n", loaded.file.string(), results.string());
    }
    if (talk) fmt::print("tumble resume: from {}\n", loaded.file.string());
    if (command == "run") return resume_run(std::move(loaded.checkpoint), directory, quiet, progress_every);
    if (command == "drum") return resume_drum(std::move(loaded.checkpoint), directory, quiet, progress_every, revolutions);
    throw Error(loaded.file.string() + ": a checkpoint of an unknown command \"" + command + "\"");
}

}  // namespace tumble::cli
