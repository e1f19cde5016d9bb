// SPDX-License-Identifier: MIT
// tumble plot DIR: the paper's figures from a drum run, drawn by the
// project's matplotlib script tools/plot_drum.py (tools/README.md), and
// first, if the run has none, the flowing layer's fields they draw.
#include <sys/wait.h>
#include <cstdio>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "io/drum_output.hpp"
#include "tumble/core/error.hpp"

namespace tumble::cli {

namespace {

// The script beside an installed tumble (cmake --install puts it in
// PREFIX/share/tumble/tools, the program in PREFIX/bin), else the source
// tree's, for tumble run from its build directory.
std::string plot_script() {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path installed = fs::read_symlink("/proc/self/exe", ec).parent_path() / "../share/tumble/tools/plot_drum.py";
    if (!ec && fs::exists(installed, ec)) return installed.lexically_normal().string();
    return std::string(TUMBLE_TOOLS_DIR) + "/plot_drum.py";
}

// The flowing layer's fields that fig_flowing_layer draws, where the run
// has none yet: tumble fields DIR --frame drum --samples 20 --every 0.01
// --kernel lucy --cell R/40 (R the drum's inner radius) --format csv, into
// DIR/flowing_layer (docs/FIELDS.md, "The drum's frame"). A run whose
// surface cannot be found (too few grains) or that has no checkpoint gets
// a note, and the figure is skipped; so does a run whose 0.4 s of stepping
// (the samples' 0.2 s, taken twice) would take more than a minute at its
// own speed on one core (its grain updates per second over its threads).
void flowing_layer_fields(const std::string& directory, bool quiet) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::exists(fs::path(directory) / "flowing_layer" / "drum_frame.json", ec)) return;
    try {
        const io::DrumRunInfo info = io::read_drum_run_info(fs::path(directory) / "drum_run.toml");
        constexpr int samples = 20;
        constexpr double every = 0.01;  // s
        double grains = 0.0;
        for (const io::DrumComponent& c : info.components) grains += static_cast<double>(c.grains);
        const double seconds = info.dt > 0.0 && info.grain_updates_per_second > 0.0
                                   ? 2.0 * samples * every / info.dt * grains /
                                         (info.grain_updates_per_second / std::max(info.threads, 1))
                                   : 0.0;
        if (seconds > 60.0)
            throw Error(fmt::format("they would take about {:.0f} s here (tumble fields {} --frame drum computes them)",
                                    seconds, directory));
        FieldsOptions o;
        o.run.run_directory = directory;
        o.run.frame = "drum";
        o.run.samples = samples;
        o.run.every = every;
        o.run.settings.kernel = analysis::CgKernel::lucy;
        o.run.settings.cell = info.inner_radius / 40.0;
        o.format = "csv";
        o.quiet = true;  // one line here; drum_frame.json has the numbers
        fields_command(o);
        if (!quiet)
            fmt::print("tumble plot: the flowing layer's fields ({} states after the run's end) into {}\n", samples,
                       (fs::path(directory) / "flowing_layer").string());
    } catch (const Error& e) {
        fmt::print(stderr, "tumble plot: note: no flowing layer's fields for fig_flowing_layer: {}\n", e.what());
    }
}

}  // namespace

int plot_command(const std::string& mode, const std::vector<std::string>& inputs, const std::string& out, bool quiet,
                 bool band_report) {
    if (mode == "run" || mode == "compare")
        for (const std::string& directory : inputs) experiments::require_drum_run(directory, "plot");
    if (mode == "run")
        for (const std::string& directory : inputs) flowing_layer_fields(directory, quiet);
    std::vector<std::string> arguments{"python3", plot_script(), mode};
    arguments.insert(arguments.end(), inputs.begin(), inputs.end());
    if (band_report && mode == "run") arguments.push_back("--band-report");
    if (!out.empty()) {
        arguments.push_back("--out");
        arguments.push_back(out);
    }
    std::vector<char*> argv;
    for (std::string& a : arguments) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t child = fork();
    if (child == 0) {
        if (quiet) freopen("/dev/null", "w", stdout);  // errors still reach stderr
        execvp(argv[0], argv.data());
        fmt::print(stderr, "tumble plot: cannot start python3\n");
        _exit(127);
    }
    int status = 0;
    if (child < 0 || waitpid(child, &status, 0) < 0) return 3;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 3;
}

}  // namespace tumble::cli
