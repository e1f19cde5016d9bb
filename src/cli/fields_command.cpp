// SPDX-License-Identifier: MIT
// tumble fields RUN_DIR: coarse-grained fields of a run (docs/FIELDS.md).
#include <fmt/format.h>

#include "cli/commands.hpp"

namespace tumble::cli {

int fields_command(const FieldsOptions& options) {
    const auto say = [&](const std::string& line) {
        if (!options.quiet) fmt::print("tumble fields: {}\n", line);
    };
    const RunFields run = run_fields(options.run, say);
    const std::filesystem::path out =
        options.out.empty() ? options.run.run_directory / (options.run.frame == "drum" ? "flowing_layer" : "fields")
                            : std::filesystem::path(options.out);
    write_fields_files(out, run.fields, options.format);
    if (run.drum) {
        write_drum_layer_files(out, *run.drum, options.run.span);
        say(drum_layer_summary(*run.drum));
    }
    say(fmt::format("{} sample{} from t = {:.6g} s to {:.6g} s (coarse-grained in {:.3g} s) into {}", run.times.size(),
                    run.times.size() == 1 ? "" : "s", run.times.front(), run.times.back(), run.seconds, out.string()));
    return 0;
}

}  // namespace tumble::cli
