// SPDX-License-Identifier: MIT
// tumble sweep (docs/SWEEP.md): the points and their state (--list), or the
// sweep of experiments/sweep.hpp with this executable as each point's
// program, then the figures over speeds from its sweep.csv.
#include "cli/sweep_command.hpp"
#include "cli/commands.hpp"

#include <fmt/format.h>

#include "io/sweep.hpp"
#include "tumble/core/mpi.hpp"

namespace tumble::cli {

int sweep_command(const SweepOptions& o) {
    if (o.list) {
        const SweepPlan plan = sweep_plan(o.sweep_file, o.output_directory);
        if (tumble::mpi::rank() != 0) return 0;
        fmt::print("tumble sweep {}: {} points in {}\n", o.sweep_file, plan.points.size(), plan.directory.string());
        for (const io::SweepPoint& p : plan.points)
            fmt::print("  {:4} {:<40} {}\n", p.index, p.name, io::to_string(io::point_state(p.directory)));
        return 0;
    }
    SweepRunOptions options = o;
    options.tumble_binary = io::self_executable();
    const SweepOutcome outcome = run_sweep(options);
    // The figures over speeds (figs. 3, 5, 6): a convenience, so a machine
    // without matplotlib only gets a warning.
    const std::string table = (outcome.directory / "sweep.csv").string();
    if (outcome.tables_written && plot_command("sweep", {table}, "", o.quiet) != 0)
        fmt::print(stderr, "{}sweep: warning: the figures could not be drawn (tools/plot_drum.py sweep {})\n",
                   tumble::mpi::line_prefix(), table);
    return outcome.exit_code;
}

}  // namespace tumble::cli
