// SPDX-License-Identifier: MIT
#include "experiments/sweep.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>
#include <optional>
#include <thread>

#include <fmt/format.h>

#include "experiments/limits.hpp"
#include "experiments/run_control.hpp"
#include "io/checkpoint.hpp"
#include "io/run_lock.hpp"
#include "io/toml_reader.hpp"
#include "tumble/core/error.hpp"
#include "tumble/setup/drum.hpp"
#include "tumble/sim/time_step.hpp"

namespace tumble::experiments {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// True when a point is settled for rank 0's wait: a readable summary.json,
// or a failure marker of this job (or of any job when the job is unknown).
bool point_done(const io::SweepPoint& p, const std::string& job) {
    const io::PointState s = io::point_state(p.directory);
    if (s == io::PointState::finished) return io::read_point_result(p).note.empty();  // not half-written
    if (s == io::PointState::failed) {
        const auto marker_job = io::failure_marker_job(p.directory);
        return job.empty() || (marker_job && *marker_job == job);
    }
    return false;
}

// Rank 0 waits until every point is done (point_done), at most `timeout` seconds.
void wait_for_other_ranks(const std::vector<io::SweepPoint>& points, const io::RankInfo& rank, double timeout,
                          bool quiet) {
    const std::string who = rank.line_prefix();
    const auto wait_start = Clock::now();
    auto last_report = wait_start;
    while (true) {
        const auto waiting = static_cast<std::size_t>(
            std::count_if(points.begin(), points.end(), [&](const io::SweepPoint& p) { return !point_done(p, rank.job); }));
        if (waiting == 0) return;
        const double waited = seconds_since(wait_start);
        if (waited > timeout) {
            fmt::print(stderr, "{}gave up waiting after {} for {} points of the other ranks\n", who,
                       format_duration(waited), waiting);
            return;
        }
        if (!quiet && Clock::now() - last_report > std::chrono::minutes(1)) {
            fmt::print("{}waiting for {} points of the other ranks\n", who, waiting);
            last_report = Clock::now();
        }
        std::this_thread::sleep_for(std::chrono::seconds(1));
    }
}

// The sweep directory made, with its points/ folder, and, on rank 0, locked
// (each point's run holds its own lock) and given a copy of the sweep file.
std::optional<io::RunLock> prepare_directory(const fs::path& dir, const std::string& sweep_file,
                                             const io::RankInfo& rank) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw Error(dir.string() + ": cannot create the sweep directory: " + ec.message());
    std::optional<io::RunLock> lock;
    if (rank.rank == 0) lock.emplace(dir);
    fs::create_directories(dir / "points", ec);
    if (ec) throw Error((dir / "points").string() + ": cannot create the folder: " + ec.message());
    if (rank.rank == 0) {
        std::ofstream copy(dir / "sweep.toml", std::ios::trunc);  // what was asked, for the record
        copy << "# copy of " << sweep_file << " as last run by tumble sweep\n" << io::read_text_file(sweep_file);
    }
    return lock;
}

}  // namespace

SweepPlan sweep_plan(const std::string& sweep_file, const std::string& output_directory) {
    const io::SweepSettings settings = io::load_sweep_settings(sweep_file);
    SweepPlan plan;
    plan.directory = output_directory.empty() ? settings.output : fs::path(output_directory);
    plan.points = io::expand_sweep(settings, plan.directory);
    std::map<std::string, double> dt_of_mode;
    const io::DrumSettings defaults;
    for (const io::SweepPoint& p : plan.points) {
        if (!dt_of_mode.count(p.mode))
            dt_of_mode[p.mode] = assess_time_step(build_drum_scenario({}, p.mode, p.grains, p.seed).scenario).dt;
        try {
            check_drum_durations(p.revolutions, p.omega, p.samples_per_revolution, defaults.settle_max_time,
                                 dt_of_mode[p.mode]);
        } catch (const Error& e) {
            throw Error(sweep_file + ": point " + p.name + " (sweep.revolutions, and the speeds): " + e.what());
        }
    }
    return plan;
}

SweepOutcome run_sweep(const SweepRunOptions& o) {
    const SweepPlan plan = sweep_plan(o.sweep_file, o.output_directory);
    const std::vector<io::SweepPoint>& points = plan.points;
    const fs::path& dir = plan.directory;
    const io::RankInfo rank = io::detect_rank();
    const std::string who = rank.line_prefix();
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const unsigned jobs = o.jobs > 0 ? o.jobs : std::max(1u, cores / static_cast<unsigned>(rank.local_size));
    const std::vector<std::size_t> mine = io::points_of_rank(points.size(), rank.rank, rank.size);
    const std::optional<io::RunLock> lock = prepare_directory(dir, o.sweep_file, rank);  // held to the end

    // This rank's points: skip the finished ones, resume the interrupted ones
    // that have a checkpoint, run the others from the start.
    std::vector<io::PointJob> todo;
    std::size_t skipped = 0;
    for (std::size_t i : mine) {
        const io::SweepPoint& p = points[i];
        const io::PointState s = io::point_state(p.directory);
        if (s == io::PointState::finished) {
            ++skipped;
            continue;
        }
        const bool resume = s != io::PointState::pending &&
                            io::resumable(p.directory, static_cast<std::uintmax_t>(memory_limit_bytes(0.0)));
        if (s != io::PointState::pending && !o.quiet)
            fmt::print("{}{}: {} before; {}\n", who, p.name, io::to_string(s),
                       resume ? "resuming it from its newest checkpoint" : "running it again from the start");
        std::error_code ec;
        fs::remove(p.directory / io::point_failed_file, ec);
        std::vector<std::string> argv{o.tumble_binary.string()};
        for (std::string& a : resume ? io::resume_arguments(p) : io::drum_arguments(p)) argv.push_back(std::move(a));
        todo.push_back({i, std::move(argv), p.directory / io::point_log_file});
    }
    if (!o.quiet)
        fmt::print("{}tumble sweep: {} points in {} ({} for this rank: {} finished before, {} to run, {} at once)\n",
                   who, points.size(), dir.string(), mine.size(), skipped, todo.size(), jobs);

    SweepOutcome outcome{.directory = dir, .points = points.size()};
    install_stop_signals();  // SIGINT, SIGTERM: the running points checkpoint and stop
    const auto start = Clock::now();
    std::size_t done = 0;
    // In a log, a line at the steady interval between the points' own lines
    // (a point can run for hours); on a terminal those lines are enough.
    ProgressStyle style = progress_style(o.quiet, o.progress_every);
    if (style.output == ProgressStyle::Output::terminal) style.output = ProgressStyle::Output::none;
    Progress progress(who + "sweep", 0, static_cast<std::int64_t>(todo.size()), style, {.unit = "points"});
    io::run_jobs(
        todo, jobs,
        [&](const io::PointJob& job) {
            if (!o.quiet)
                fmt::print("{}start  {} ({})\n", who, points[job.point].name, format_duration(seconds_since(start)));
        },
        [&](const io::PointJob& job, const io::PointOutcome& out) {
            ++done;
            const io::SweepPoint& p = points[job.point];
            const bool ok = out.exit_code == 0 && io::point_state(p.directory) == io::PointState::finished;
            if (out.exit_code == exit_stopped && stop_signalled()) {
                fmt::print(stderr, "{}stopped {} with a checkpoint (resumed by the next sweep)\n", who, p.name);
                return;
            }
            if (!ok) {
                ++outcome.failed;
                io::write_failure_marker(p.directory, out.exit_code, rank.job);
                fmt::print(stderr, "{}FAILED {} (exit code {}{}); log: {}\n", who, p.name, out.exit_code,
                           out.exit_code == 0 ? ", but no summary.json" : "", job.log.string());
            }
            if (!o.quiet) {
                const double t = seconds_since(start);
                const double eta = t / static_cast<double>(done) * static_cast<double>(todo.size() - done);
                fmt::print("{}{} {} in {} [{}/{}; elapsed {}, ETA {}]\n", who, ok ? "done  " : "failed", p.name,
                           format_duration(out.seconds), done, todo.size(), format_duration(t), format_duration(eta));
            }
        },
        [&] {  // polled while the points run
            progress.update(static_cast<std::int64_t>(done));
            return stop_signalled();
        });
    if (stop_signalled()) {
        fmt::print(stderr, "{}tumble sweep: stopped by a signal; the running points wrote checkpoints. Continue "
                           "with the same command: tumble sweep {} -o {}\n",
                   who, o.sweep_file, dir.string());
        outcome.stopped = true;
        outcome.exit_code = exit_stopped;
        return outcome;
    }

    if (rank.rank != 0) {
        // Exit code 0 even if points failed: mpirun would kill rank 0 before
        // it aggregates. Rank 0 reports the failures (failure markers) and
        // its exit code counts them.
        if (!o.quiet) fmt::print("{}finished: {} of {} points failed\n", who, outcome.failed, todo.size());
        return outcome;
    }

    if (rank.under_mpi()) wait_for_other_ranks(points, rank, o.wait_timeout, o.quiet);
    std::vector<io::PointResult> results;
    for (const io::SweepPoint& p : points) results.push_back(io::read_point_result(p));
    const std::size_t missing = io::write_sweep_tables(dir, results);
    outcome.tables_written = true;
    outcome.with_results = points.size() - missing;
    for (const io::PointResult& r : results)
        if (!r.note.empty()) fmt::print(stderr, "{}no result for {}: {}\n", who, r.point.name, r.note);
    if (!o.quiet)
        fmt::print("{}sweep: {} of {} points with results; written {} and {} ({})\n", who, outcome.with_results,
                   points.size(), (dir / "sweep.csv").string(), (dir / "sweep_summary.csv").string(),
                   format_duration(seconds_since(start)));
    outcome.exit_code = missing || outcome.failed ? 1 : 0;
    return outcome;
}

}  // namespace tumble::experiments
