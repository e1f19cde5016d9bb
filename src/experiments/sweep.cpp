// SPDX-License-Identifier: MIT
#include "experiments/sweep.hpp"

#include <algorithm>
#include <chrono>
#include <deque>
#include <sstream>
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
#include "tumble/core/mpi.hpp"
#include "tumble/setup/drum.hpp"
#include "tumble/sim/time_step.hpp"

namespace tumble::experiments {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// The sweep directory made, with its points/ folder, and, on rank 0, locked
// (each point's run holds its own lock) and given a copy of the sweep file.
std::optional<io::RunLock> prepare_directory(const fs::path& dir, const std::string& sweep_file) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw Error(dir.string() + ": cannot create the sweep directory: " + ec.message());
    std::optional<io::RunLock> lock;
    if (mpi::rank() == 0) lock.emplace(dir);  // before anything is written into it
    fs::create_directories(dir / "points", ec);
    if (ec) throw Error((dir / "points").string() + ": cannot create the folder: " + ec.message());
    if (mpi::rank() != 0) return lock;
    std::ofstream copy(dir / "sweep.toml", std::ios::trunc);  // what was asked, for the record
    copy << "# copy of " << sweep_file << " as last run by tumble sweep\n" << io::read_text_file(sweep_file);
    return lock;
}

// The messages of a sweep over MPI ranks (docs/SWEEP.md, "MPI"): a rank
// asks rank 0 for a point (request, empty); rank 0 answers with the point's
// index and 1 to resume it from its checkpoint or 0 to start it, or with
// "none" (assign); the rank reports each point it ran, "INDEX EXIT_CODE
// SECONDS\n" and then the text of its summary.json (result), and at the end
// that it asks no more (done).
enum Tag : int { request = 1, assign = 2, result = 3, done = 4 };

// A point to run and how: from its checkpoint or from the start.
struct Assignment {
    std::size_t point = 0;
    bool resume = false;
};

}  // namespace

SweepPlan sweep_plan(const std::string& sweep_file, const std::string& output_directory) {
    const io::SweepSettings settings = io::load_sweep_settings(sweep_file);
    SweepPlan plan;
    plan.directory = output_directory.empty() ? settings.output : fs::path(output_directory);
    plan.points = io::expand_sweep(settings, plan.directory);
    std::map<std::string, double> dt_of_mode;
    const io::DrumSettings defaults;
    for (const io::SweepPoint& p : plan.points) {
        if (!dt_of_mode.count(p.mode)) {  // every point of a sweep has the same walls and axis
            DrumGeometry g;
            g.periodic_axis = p.periodic_axis;
            g.walls = find_keyword(drum_wall_kinds, p.walls)->value;
            dt_of_mode[p.mode] = assess_time_step(build_drum_scenario(g, p.mode, p.grains, p.seed).scenario).dt;
        }
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
    const int rank = mpi::rank(), ranks = mpi::size();
    const std::string who = mpi::line_prefix();
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const unsigned jobs = o.jobs > 0 ? o.jobs : std::max(1u, cores / static_cast<unsigned>(mpi::node_size()));
    const std::optional<io::RunLock> lock = prepare_directory(dir, o.sweep_file);  // held to the end

    // Rank 0 plans: the finished points are skipped, the interrupted ones
    // that have a checkpoint resumed, the others run from the start.
    std::deque<Assignment> queue;
    std::size_t skipped = 0;
    if (rank == 0) {
        for (const io::SweepPoint& p : points) {
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
            queue.push_back({p.index, resume});
        }
        if (!o.quiet)
            fmt::print("{}tumble sweep: {} points in {} ({} finished before, {} to run, {} at once{})\n", who,
                       points.size(), dir.string(), skipped, queue.size(), jobs,
                       ranks > 1 ? fmt::format(" on each of {} ranks", ranks) : std::string());
    }
    const std::size_t to_run = queue.size();

    // The command line of an assigned point, on the rank that runs it.
    auto job_of = [&](const Assignment& a) {
        const io::SweepPoint& p = points[a.point];
        std::error_code ec;
        fs::remove(p.directory / io::point_failed_file, ec);
        std::vector<std::string> argv{o.tumble_binary.string()};
        for (std::string& arg : a.resume ? io::resume_arguments(p) : io::drum_arguments(p)) argv.push_back(std::move(arg));
        return io::PointJob{a.point, std::move(argv), p.directory / io::point_log_file};
    };

    SweepOutcome outcome{.directory = dir, .points = points.size()};
    install_stop_signals();  // SIGINT, SIGTERM: the running points checkpoint and stop
    const auto start = Clock::now();
    std::size_t finished_here = 0, reported = 0;  // points ended on this rank; on every rank (rank 0)
    std::map<std::size_t, io::PointResult> remote;  // rank 0: the results the other ranks sent
    int ranks_done = 0;                              // rank 0: ranks that ask for no more points
    // In a log, a line at the steady interval between the points' own lines
    // (a point can run for hours); on a terminal those lines are enough.
    ProgressStyle style = progress_style(o.quiet || rank != 0, o.progress_every);
    if (style.output == ProgressStyle::Output::terminal) style.output = ProgressStyle::Output::none;
    Progress progress(who + "sweep", 0, static_cast<std::int64_t>(to_run), style, {.unit = "points"});

    // Rank 0's account of a point that ended, on any rank.
    auto report = [&](const io::SweepPoint& p, bool ok, double seconds, const std::string& where) {
        ++reported;
        if (!ok) ++outcome.failed;
        if (o.quiet) return;
        const double t = seconds_since(start);
        const double eta = t / static_cast<double>(reported) * static_cast<double>(to_run - reported);
        fmt::print("{}{} {}{} in {} [{}/{}; elapsed {}, ETA {}]\n", who, ok ? "done  " : "failed", p.name, where,
                   format_duration(seconds), reported, to_run, format_duration(t), format_duration(eta));
    };
    // Rank 0 answers what the other ranks sent, without waiting.
    auto serve = [&] {
        while (std::optional<mpi::Message> m = mpi::poll()) {
            const std::string from = fmt::format(" (rank {})", m->from);
            if (m->tag == Tag::request) {
                if (queue.empty() || stop_signalled()) {
                    mpi::send(m->from, Tag::assign, "none");
                } else {
                    mpi::send(m->from, Tag::assign, fmt::format("{} {}", queue.front().point, int(queue.front().resume)));
                    queue.pop_front();
                }
            } else if (m->tag == Tag::result) {
                const std::size_t newline = m->text.find('\n');
                std::istringstream head(m->text.substr(0, newline));
                std::size_t index = 0;
                int code = 0;
                double seconds = 0.0;
                head >> index >> code >> seconds;
                if (!head || index >= points.size())
                    throw Error(fmt::format("sweep: a malformed result from rank {}: {}", m->from, m->text.substr(0, 80)));
                if (code == exit_stopped && stop_signalled()) continue;
                const io::SweepPoint& p = points[index];
                const std::string summary = newline == std::string::npos ? "" : m->text.substr(newline + 1);
                remote[index] = code == 0 ? io::point_result_from_summary(p, summary, p.name + from + ": summary.json")
                                          : io::failed_point_result(p, code, "rank " + std::to_string(m->from) + ", ");
                report(p, code == 0 && remote[index].note.empty(), seconds, from);
            } else if (m->tag == Tag::done) {
                ++ranks_done;
            }
        }
    };
    // The next point for this rank: from the queue on rank 0, from rank 0 elsewhere.
    auto next = [&]() -> std::optional<io::PointJob> {
        if (rank == 0) {
            if (queue.empty()) return std::nullopt;
            const Assignment a = queue.front();
            queue.pop_front();
            return job_of(a);
        }
        mpi::send(0, Tag::request, "");
        const std::string answer = mpi::receive(0, Tag::assign).text;
        Assignment a;
        int resume = 0;
        std::istringstream in(answer);
        if (!(in >> a.point >> resume) || a.point >= points.size()) return std::nullopt;  // "none"
        a.resume = resume != 0;
        return job_of(a);
    };

    io::run_jobs(
        next, jobs,
        [&](const io::PointJob& job) {
            if (!o.quiet)
                fmt::print("{}start  {} ({})\n", who, points[job.point].name, format_duration(seconds_since(start)));
        },
        [&](const io::PointJob& job, const io::PointOutcome& out) {
            ++finished_here;
            const io::SweepPoint& p = points[job.point];
            const bool stopped = out.exit_code == exit_stopped && stop_signalled();
            const bool ok = out.exit_code == 0 && io::point_state(p.directory) == io::PointState::finished;
            if (stopped) fmt::print(stderr, "{}stopped {} with a checkpoint (resumed by the next sweep)\n", who, p.name);
            if (!ok && !stopped) {
                io::write_failure_marker(p.directory, out.exit_code);
                fmt::print(stderr, "{}FAILED {} (exit code {}{}); log: {}\n", who, p.name, out.exit_code,
                           out.exit_code == 0 ? ", but no summary.json" : "", job.log.string());
            }
            if (rank == 0) {
                if (!stopped) report(p, ok, out.seconds, "");
                return;
            }
            // Another rank: the result goes to rank 0, which tells the table.
            const int code = ok || stopped ? out.exit_code : (out.exit_code == 0 ? 1 : out.exit_code);
            mpi::send(0, Tag::result, fmt::format("{} {} {:.3f}\n", job.point, code, out.seconds) +
                                          (ok ? io::read_text_file(p.directory / io::point_summary_file) : ""));
            if (!ok && !stopped) ++outcome.failed;
            if (!o.quiet && !stopped)
                fmt::print("{}{} {} in {} [{} on this rank]\n", who, ok ? "done  " : "failed", p.name,
                           format_duration(out.seconds), finished_here);
        },
        [&] {  // polled while the points run
            if (rank == 0) serve();
            progress.update(static_cast<std::int64_t>(reported));
            return stop_signalled();
        });
    if (rank != 0) {
        mpi::send(0, Tag::done, "");
    } else {
        while (ranks_done < ranks - 1) {  // the other ranks' last points
            serve();
            progress.update(static_cast<std::int64_t>(reported));
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
    }
    if (stop_signalled()) {
        fmt::print(stderr, "{}tumble sweep: stopped by a signal; the running points wrote checkpoints. Continue "
                           "with the same command: {} sweep {} -o {}\n",
                   who, program_name(), o.sweep_file, dir.string());
        outcome.stopped = true;
        outcome.exit_code = exit_stopped;
        return outcome;
    }
    if (rank != 0) return outcome;  // exit code 0: rank 0 counts the failures

    std::vector<io::PointResult> results;
    for (const io::SweepPoint& p : points) {
        const auto it = remote.find(p.index);
        results.push_back(it != remote.end() ? it->second : io::read_point_result(p));
    }
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
