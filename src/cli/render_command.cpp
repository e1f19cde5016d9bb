// SPDX-License-Identifier: MIT
// tumble render DIR: a movie of a run's particle snapshots, the paper's
// "animated videos" of the drum (docs/RENDER.md). Every snapshots/NNNNNN.csv,
// with the smooth walls of NNNNNN_walls.vtp where the run has them, becomes
// a frame, frames/NNNNNN.png (two views side by side over the clock and the
// legend, drawn by src/io/render/ on -j threads), and ffmpeg joins the
// frames into DIR/NAME.mp4, NAME the run directory's.
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
#include <optional>
#include <sstream>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "experiments/progress.hpp"
#include "io/checkpoint.hpp"
#include "experiments/limits.hpp"
#include "io/drum_output.hpp"
#include "io/output.hpp"
#include "io/png.hpp"
#include "io/render/scene.hpp"
#include "io/snapshots.hpp"
#include "io/sweep.hpp"
#include "tumble/core/constants.hpp"
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

// A snapshot as a frame draws it: its particles (NNNNNN.csv) and its smooth
// walls (NNNNNN_walls.vtp, where the run has them).
io::SnapshotParticles read_snapshot(const fs::path& csv) {
    io::SnapshotParticles snapshot = io::read_snapshot_csv(csv);
    snapshot.walls = io::read_snapshot_walls(csv);
    return snapshot;
}

// What every frame shares: the box that holds every particle and wall of
// every snapshot, the wall's centre, the grain materials.
io::render::Scene gather_scene(const std::vector<fs::path>& snapshots, unsigned jobs, ProgressStyle style) {
    std::vector<io::render::Scene> parts(snapshots.size());
    Progress progress("reading", 0, static_cast<std::int64_t>(snapshots.size()), style, {.unit = "snapshots"});
    parallel_for(snapshots.size(), jobs, [&](std::size_t k) { parts[k].add(read_snapshot(snapshots[k])); },
                 progress);
    io::render::Scene scene;
    for (const io::render::Scene& part : parts) scene.add(part);
    return scene;
}

// What the frames' clock needs of a drum run: when rotation began, how fast.
struct DrumClock {
    double start = 0.0;  // s: the end of settling, revolution N = 0
    double omega = 0.0;  // rad/s
};

// "t = 0.512 s, N = 2.25 revolutions" (N for a drum run only); empty if the
// snapshot does not say its time.
std::string clock_text(const io::SnapshotParticles& snapshot, const std::optional<DrumClock>& drum) {
    const std::optional<double>& t = snapshot.time;
    if (!t) return {};
    if (!drum) return fmt::format("t = {:.4g} s", *t);
    return fmt::format("t = {:.4g} s, N = {:.2f} revolutions", *t, drum->omega * (*t - drum->start) / (2.0 * pi));
}

// frames/NNNNNN.png of snapshot NNNNNN (counted from 0 in their order).
void draw_frames(const std::vector<fs::path>& snapshots, const io::render::Scene& scene,
                 const io::render::FrameStyle& style, const std::optional<DrumClock>& drum, const fs::path& frames,
                 unsigned jobs, ProgressStyle shown) {
    Progress progress("drawing", 0, static_cast<std::int64_t>(snapshots.size()), shown, {.unit = "frames"});
    parallel_for(snapshots.size(), jobs, [&](std::size_t k) {
        const io::SnapshotParticles snapshot = read_snapshot(snapshots[k]);
        const io::render::Image image = io::render::render_frame(snapshot, scene, style, clock_text(snapshot, drum));
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
ColourBy colour_by(const std::string& option, const std::optional<io::DrumRunInfo>& drum) {
    if (option == "tag") return ColourBy::tag;
    if (option == "material") return ColourBy::material;
    return drum && drum->mode == "self" ? ColourBy::tag : ColourBy::material;
}

// The views: the drum's for a drum run; for a scenario, "up" against the
// gravity kept in the run's newest checkpoint (+z if it has none).
io::render::Orientation orientation_of(const fs::path& directory, bool drum) {
    if (drum) return io::render::drum_orientation();
    try {
        const auto max_bytes = static_cast<std::uintmax_t>(memory_limit_bytes(0.0));
        // (Any rank's file holds the scenario: a run of ranks has no file of one process.)
        const io::LoadedCheckpoint loaded =
            io::load_newest_checkpoint(directory, max_bytes, io::newest_checkpoint_kind(directory, max_bytes));
        return io::render::orientation_against(loaded.checkpoint.scenario.gravity);
    } catch (const Error&) {
        return io::render::orientation_against({0.0, 0.0, 0.0});
    }
}

// The movie's frame rate: as asked, or one that makes a movie of about 6 s
// or more, at most 25 frames/s.
int frame_rate(int asked, std::size_t frames) {
    if (asked > 0) return asked;
    return static_cast<int>(std::clamp<std::size_t>(frames / 6, 2, 25));
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
    const fs::path movie = options.out.empty() ? io::default_movie_file(directory) : fs::path(options.out);
    const fs::path ffmpeg = options.frames_only ? fs::path() : find_on_path("ffmpeg");
    if (!options.frames_only && ffmpeg.empty())
        throw Error("ffmpeg not found on PATH, and it makes the movie " + movie.string() +
                    ": install ffmpeg (Debian: apt-get install ffmpeg), or pass --frames-only");
    const fs::path run_info = directory / "drum_run.toml";
    const std::optional<io::DrumRunInfo> drum =
        fs::exists(run_info) ? std::optional(io::read_drum_run_info(run_info)) : std::nullopt;
    io::render::FrameStyle style{options.width, colour_by(options.colour, drum),
                                 orientation_of(directory, drum.has_value()), {}};
    const unsigned jobs = options.jobs > 0 ? options.jobs : std::max(1u, std::thread::hardware_concurrency());
    const bool talk = !options.quiet;
    const std::size_t count = snapshots.size();
    if (talk)
        fmt::print("tumble render: {} snapshots of {}, grains coloured by {}, {} threads\n", count,
                   directory.string(), style.colour_by == ColourBy::tag ? "tag" : "material", jobs);

    const auto start = Clock::now();
    const io::render::Scene scene = gather_scene(snapshots, jobs, progress_style(!talk));
    std::vector<std::string> tag_names;
    if (drum)
        for (const io::DrumComponent& c : drum->components) tag_names.push_back(c.name);
    style.legend = io::render::scene_legend(scene, style.colour_by, tag_names);
    const fs::path frames = fresh_frames_directory(directory);
    const std::optional<DrumClock> clock =
        drum ? std::optional(DrumClock{drum->settle_time, drum->omega}) : std::nullopt;
    draw_frames(snapshots, scene, style, clock, frames, jobs, progress_style(!talk));
    if (talk)
        fmt::print("{} frames of {} x {} pixels in {}, read and drawn in {:.1f} s\n", count, 2 * options.width,
                   io::render::frame_layout(scene, style).height, frames.string(), seconds_since(start));
    if (options.frames_only) return 0;

    const int fps = frame_rate(options.fps, count);
    const double seconds = static_cast<double>(count) / fps;
    if (seconds < 3.0)
        fmt::print(stderr,
                   "tumble render: warning: the movie lasts only {:.1f} s ({} frames at {} frames/s); more snapshots "
                   "make a longer one: tumble drum --snapshots P (per revolution), tumble run: [output] "
                   "snapshot_interval\n",
                   seconds, count, fps);
    const auto movie_start = Clock::now();
    make_movie(ffmpeg, frames, fps, movie);
    if (talk)
        fmt::print("movie {}: {:.1f} s at {} frames/s (ffmpeg, H.264) in {:.1f} s\n", movie.string(), seconds, fps,
                   seconds_since(movie_start));
    return 0;
}

}  // namespace tumble::cli
