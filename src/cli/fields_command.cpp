// SPDX-License-Identifier: MIT
// tumble fields RUN_DIR: coarse-grained fields of a run (docs/FIELDS.md).
#include <cmath>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "io/fields_output.hpp"
#include "tumble/core/constants.hpp"

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
        const analysis::DrumSurface& s = run.drum->surface;
        const analysis::FlowingLayer& l = run.drum->layer;
        io::write_fields_csv(out / "profile.csv", run.drum->profile, "sdz");
        if (run.drum->resolved) io::write_fields_csv(out / "frame.csv", *run.drum->resolved, "sdz");
        io::write_json_file(out / "drum_frame.json", io::drum_frame_json(s, l, options.run.span));
        const std::string layer =
            std::isfinite(l.thickness)
                ? fmt::format("flowing layer {:.3g} m ({:.2f} grain diameters) deep", l.thickness, l.thickness / l.diameter)
                : std::string("no flowing layer (the velocity along the surface does not turn below it)");
        say(fmt::format("free surface at {:.2f} degrees, {:.4g} m from the axis; surface velocity {:.3g} m/s, {}",
                        s.angle * 180.0 / pi, s.level, l.surface_velocity, layer));
    }
    say(fmt::format("{} sample{} from t = {:.6g} s to {:.6g} s (coarse-grained in {:.3g} s) into {}", run.times.size(),
                    run.times.size() == 1 ? "" : "s", run.times.front(), run.times.back(), run.seconds, out.string()));
    return 0;
}

}  // namespace tumble::cli
