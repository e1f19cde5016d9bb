// SPDX-License-Identifier: MIT
// tumble render DIR: a movie of a run's particle snapshots, the paper's
// "animated videos" of the drum (docs/RENDER.md). Every snapshots/NNNNNN.csv
// becomes a frame, frames/NNNNNN.png (two views side by side, drawn by
// src/io/render/ on -j threads), and ffmpeg joins the frames into an MP4.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <sstream>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "experiments/progress.hpp"
#include "io/drum_output.hpp"
#include "io/png.hpp"
#include "io/render/scene.hpp"
#include "io/snapshots.hpp"
#include "io/sweep.hpp"
#include "tumble/core/error.hpp"

namespace tumble::cli {

namespace {

namespace fs = std::filesystem;
using io::render::ColourBy;

// Calls work(k) for every k in [0, count) on `jobs` threads, reporting the
// number done to `progress` from this thread. After all threads have
// stopped, rethrows the first exception a call threw (the others then stop
// taking work).
void parallel_for(std::size_t count, unsigned jobs, const std::function<void(std::size_t)>& work, Progress& progress) {
    std::atomic<std::size_t> next{0}, done{0};
    std::atomic<bool> failed{false};
    std::exception_ptr error;
    std::mutex error_mutex;
    auto worker = [&] {
        for (std::size_t k = next++; k < count && !failed; k = next++) {
            try {
                work(k);
                ++done;
            } catch (...) {
                const std::lock_guard lock(error_mutex);
                if (!error) error = std::current_exception();
                failed = true;
            }
        }
    };
    std::vector<std::thread> threads;
    for (unsigned t = 0; t < std::max(1u, jobs); ++t) threads.emplace_back(worker);
    while (done < count && !failed) {
        progress.update(static_cast<std::int64_t>(done));
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    for (std::thread& t : threads) t.join();
    progress.finish();
    if (error) std::rethrow_exception(error);
}

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// What every frame shares: the box that holds every particle of every
// snapshot, the wall's centre, the grain materials.
io::render::Scene gather_scene(const std::vector<fs::path>& snapshots, unsigned jobs, bool show_progress) {
    std::vector<io::render::Scene> parts(snapshots.size());
    Progress progress(static_cast<std::int64_t>(snapshots.size()), 1, show_progress, "snapshots read/s");
    parallel_for(snapshots.size(), jobs, [&](std::size_t k) { parts[k].add(io::read_snapshot_csv(snapshots[k])); },
                 progress);
    io::render::Scene scene;
    for (const io::render::Scene& part : parts) scene.add(part);
    return scene;
}

// frames/NNNNNN.png of snapshot NNNNNN (counted from 0 in their order).
void draw_frames(const std::vector<fs::path>& snapshots, const io::render::Scene& scene, ColourBy colours,
                 int view_width, const fs::path& frames, unsigned jobs, bool show_progress) {
    Progress progress(static_cast<std::int64_t>(snapshots.size()), 1, show_progress, "frames/s");
    parallel_for(snapshots.size(), jobs, [&](std::size_t k) {
        const io::render::Image image =
            io::render::render_frame(io::read_snapshot_csv(snapshots[k]), scene, colours, view_width);
        io::write_png(frames / fmt::format("{:06d}.png", k), image, true);
    }, progress);
}

// The executable `program` in a directory of PATH, or an empty path.
fs::path find_on_path(const std::string& program) {
    const char* path = std::getenv("PATH");
    std::stringstream directories(path ? path : "");
    for (std::string directory; std::getline(directories, directory, ':');) {
        const fs::path candidate = fs::path(directory.empty() ? "." : directory) / program;
        std::error_code ec;
        if (fs::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0) return candidate;
    }
    return {};
}

// --color, or by default: the starting half (tag) for a self-diffusion drum
// run, where all grains are of one material; the material otherwise.
ColourBy colour_by(const std::string& option, const fs::path& directory) {
    if (option == "tag") return ColourBy::tag;
    if (option == "material") return ColourBy::material;
    const fs::path run_info = directory / "drum_run.toml";
    if (fs::exists(run_info) && io::read_drum_run_info(run_info).mode == "self") return ColourBy::tag;
    return ColourBy::material;
}

// The frames directory, emptied of an earlier render's frames.
fs::path fresh_frames_directory(const fs::path& directory) {
    const fs::path frames = directory / "frames";
    std::error_code ec;
    fs::remove_all(frames, ec);
    if (!ec) fs::create_directories(frames, ec);
    if (ec) throw Error(frames.string() + ": cannot make the frames directory: " + ec.message());
    return frames;
}

// ffmpeg: frames/%06d.png at `fps` -> H.264 in yuv420p (plays everywhere;
// needs even width and height, which the frames have). Its messages go to
// frames/ffmpeg.log and, if it fails, into the error.
void make_movie(const fs::path& ffmpeg, const fs::path& frames, int fps, const fs::path& movie) {
    if (movie.has_parent_path()) fs::create_directories(movie.parent_path());
    const fs::path log = frames / "ffmpeg.log";
    const int pid = io::spawn_process({ffmpeg.string(), "-y", "-loglevel", "error", "-framerate", std::to_string(fps),
                                       "-i", (frames / "%06d.png").string(), "-c:v", "libx264", "-pix_fmt", "yuv420p",
                                       "-crf", "20", movie.string()},
                                      log);
    int status = 0;
    if (waitpid(pid, &status, 0) < 0) throw Error("ffmpeg: cannot wait for the child process");
    const int code = io::decode_wait_status(status);
    if (code != 0) {
        std::ifstream in(log);
        std::stringstream messages;
        messages << in.rdbuf();
        throw Error(fmt::format("ffmpeg failed (exit code {}) making {}; its messages ({}):\n{}", code,
                                movie.string(), log.string(), messages.str()));
    }
}

}  // namespace

int render_command(const RenderOptions& options) {
    const fs::path directory = options.directory;
    if (!fs::is_directory(directory)) throw Error(directory.string() + ": no such run directory");
    const std::vector<fs::path> snapshots = io::list_snapshot_csv(directory);
    if (snapshots.empty())
        throw Error((directory / "snapshots").string() +
                    ": no particle snapshots (NNNNNN.csv) to render; tumble drum writes them with --snapshots P "
                    "(per revolution), tumble run at the scenario's [output] snapshot_interval");
    const fs::path movie = options.out.empty() ? directory / "drum.mp4" : fs::path(options.out);
    const fs::path ffmpeg = options.frames_only ? fs::path() : find_on_path("ffmpeg");
    if (!options.frames_only && ffmpeg.empty())
        throw Error("ffmpeg not found on PATH, and it makes the movie " + movie.string() +
                    ": install ffmpeg (Debian: apt-get install ffmpeg), or pass --frames-only");
    const ColourBy colours = colour_by(options.colour, directory);
    const unsigned jobs = options.jobs > 0 ? options.jobs : std::max(1u, std::thread::hardware_concurrency());
    const bool talk = !options.quiet;
    const std::size_t count = snapshots.size();
    if (talk)
        fmt::print("tumble render: {} snapshots of {}, grains coloured by {}, {} threads\n", count,
                   directory.string(), colours == ColourBy::tag ? "tag" : "material", jobs);

    const auto start = Clock::now();
    const io::render::Scene scene = gather_scene(snapshots, jobs, talk && progress_wanted());
    const fs::path frames = fresh_frames_directory(directory);
    draw_frames(snapshots, scene, colours, options.width, frames, jobs, talk && progress_wanted());
    if (talk)
        fmt::print("{} frames of {} x {} pixels in {}, read and drawn in {:.1f} s\n", count, 2 * options.width,
                   io::render::scene_views(scene, options.width).first.height, frames.string(), seconds_since(start));
    if (options.frames_only) return 0;

    const auto movie_start = Clock::now();
    make_movie(ffmpeg, frames, options.fps, movie);
    if (talk)
        fmt::print("movie {}: {:.1f} s at {} frames/s (ffmpeg, H.264) in {:.1f} s\n", movie.string(),
                   static_cast<double>(count) / options.fps, options.fps, seconds_since(movie_start));
    return 0;
}

}  // namespace tumble::cli
