// SPDX-License-Identifier: MIT
// tumble resume DIR: continue an interrupted run from its newest intact
// checkpoint; a damaged newer one is reported and skipped.
#include <fmt/format.h>

#include "cli/commands.hpp"
#include "experiments/limits.hpp"
#include "io/run_lock.hpp"
#include "tumble/core/error.hpp"

namespace tumble::cli {

int resume_command(const std::string& directory, bool quiet, double progress_every) {
    const io::RunLock lock(directory);  // held until the run ends
    io::LoadedCheckpoint loaded =
        io::load_newest_checkpoint(directory, static_cast<std::uintmax_t>(memory_limit_bytes(0.0)));
    for (const std::string& why : loaded.rejected)
        fmt::print(stderr, "tumble resume: warning: {}; using the previous checkpoint\n", why);
    const io::CheckpointRecord& record = loaded.checkpoint.record;
    if (record.integer("finished")) {
        fmt::print("tumble resume: the run in {} has finished ({}); nothing to do\n", directory,
                   loaded.file.string());
        return 0;
    }
    if (!quiet) fmt::print("tumble resume: from {}\n", loaded.file.string());
    const std::string command = record.text("command");
    if (command == "run") return resume_run(std::move(loaded.checkpoint), directory, quiet, progress_every);
    if (command == "drum") return resume_drum(std::move(loaded.checkpoint), directory, quiet, progress_every);
    throw Error(loaded.file.string() + ": a checkpoint of an unknown command \"" + command + "\"");
}

}  // namespace tumble::cli
