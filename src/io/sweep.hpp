// SPDX-License-Identifier: MIT
// tumble sweep (docs/SWEEP.md): the drum experiment over a list of rotation
// speeds, modes and seeds. This header holds the parts that the sweep's run
// (experiments/sweep.hpp) is built of: the sweep file, the expansion into
// points and their run directories, the state of a point on disk (resume),
// the running of child processes,
// the reading of the points' summary.json, and the aggregation into
// sweep.csv and sweep_summary.csv.
#pragma once

#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/drum_config.hpp"

namespace tumble::io {

// ---------------------------------------------------------------- sweep file

struct SweepSettings {
    std::vector<double> speeds;                  // in speed_unit, file order
    SpeedUnit speed_unit = SpeedUnit::rad_per_s;  // [sweep] omega / rpm / froude
    std::vector<std::string> modes{"self", "two-component"};
    std::vector<std::uint64_t> seeds{1};
    double revolutions = 5.0;
    std::size_t grains_two_component = 1000;
    std::size_t grains_self = 458;
    int samples_per_revolution = 20;
    int snapshots_per_revolution = 8;  // per point (the grains' axial MSD needs them; about 1.5 MB each); 0: none
    double diameter = 0.08;            // m: only to turn froude into omega (the drum's default diameter)
    std::string shear = "paper";            // shear model of every point (tumble drum --shear)
    std::string friction_normal = "net";    // tumble drum --friction-normal
    std::string tangential_stiffness = "paper";  // tumble drum --tangential-stiffness
    bool periodic_axis = false;             // tumble drum --periodic-axis: no end caps
    std::string walls = "particles";        // tumble drum --walls (keyword of drum_wall_kinds)
    std::filesystem::path output = "sweep-out";
};

// Reads a sweep TOML file; ConfigError names file, key and reason.
SweepSettings load_sweep_settings(const std::filesystem::path& file);

// ---------------------------------------------------------------- points

struct SweepPoint {
    std::size_t index = 0;     // position in the plan (deterministic order)
    std::string mode;          // "self" or "two-component"
    double omega = 0.0;        // rad/s
    double froude = 0.0;       // omega^2 R / g, R = diameter / 2
    std::uint64_t seed = 0;
    double revolutions = 0.0;
    std::size_t grains = 0;
    int samples_per_revolution = 20;
    int snapshots_per_revolution = 0;
    std::string shear = "paper", friction_normal = "net", tangential_stiffness = "paper";
    bool periodic_axis = false;
    std::string walls = "particles";
    std::string name;          // e.g. "two-component_omega5.000_seed1"
    std::filesystem::path directory;  // DIR/points/NAME
};

// "MODE_omegaW.WWW_seedS".
std::string sweep_point_name(const std::string& mode, double omega, std::uint64_t seed);

// All points, in the order: modes (file order), speeds (file order), seeds
// (file order). Throws tumble::Error if two points would share a directory.
std::vector<SweepPoint> expand_sweep(const SweepSettings& s, const std::filesystem::path& directory);

// The arguments after the program name of the child run:
// drum -q --mode M --omega W --seed S --revolutions R --grains G --samples K
//      --snapshots P --shear H --friction-normal F --tangential-stiffness T --out DIR --force
//      --threads 1 [--periodic-axis] [--walls smooth]
std::vector<std::string> drum_arguments(const SweepPoint& p);
// The arguments that continue an interrupted point from its checkpoint:
// resume -q DIR
std::vector<std::string> resume_arguments(const SweepPoint& p);

// ---------------------------------------------------------------- state on disk

// Files in a point's directory.
inline constexpr const char* point_summary_file = "summary.json";
inline constexpr const char* point_log_file = "log.txt";
inline constexpr const char* point_failed_file = "failed.txt";  // written by the sweep when the child failed

enum class PointState {
    pending,     // no directory yet
    unfinished,  // a directory without summary.json (interrupted): resumed from its checkpoint, else rerun
    failed,      // failed.txt (and no summary.json): as unfinished
    finished,    // summary.json: skipped
};
const char* to_string(PointState s);
PointState point_state(const std::filesystem::path& point_directory);

// The failure marker: "exit code N\n".
void write_failure_marker(const std::filesystem::path& point_directory, int exit_code);

// ---------------------------------------------------------------- child processes

// Starts `argv` (argv[0] the program path) with stdout and stderr appended
// to `log`, stdin from /dev/null and this process's environment less an MPI
// launcher's variables (mpi::is_launcher_variable: a child of a rank is not
// one of the ranks); returns the pid. Throws tumble::Error if the process
// cannot be started.
int spawn_process(const std::vector<std::string>& argv, const std::filesystem::path& log);

// Exit code of a finished child: its exit status, or 128 + signal.
int decode_wait_status(int status);

// The path of the running executable (/proc/self/exe).
std::filesystem::path self_executable();

struct PointJob {
    std::size_t point;              // index into the plan
    std::vector<std::string> argv;  // the full command line
    std::filesystem::path log;      // stdout + stderr of the child
};

struct PointOutcome {
    std::size_t point;
    int exit_code;
    double seconds;
};

// Runs the jobs that `next()` hands out, up to `parallel` at once, until it
// returns nullopt (it is not asked again) and the running ones have ended.
// `on_start(job)` and `on_finish(job, outcome)` are called from the calling
// thread; `stop()` is polled every 20 ms or so while jobs run (it may do
// other work, as answering other MPI ranks). Once it returns true, no job is
// started and each running one is sent SIGTERM (a drum writes a checkpoint
// and stops) and waited for. Returns the outcomes in the order the jobs
// finished.
using NextJob = std::function<std::optional<PointJob>()>;
std::vector<PointOutcome> run_jobs(const NextJob& next, unsigned parallel,
                                   const std::function<void(const PointJob&)>& on_start,
                                   const std::function<void(const PointJob&, const PointOutcome&)>& on_finish,
                                   const std::function<bool()>& stop = {});
// The same for a list of jobs, in order.
std::vector<PointOutcome> run_jobs(const std::vector<PointJob>& jobs, unsigned parallel,
                                   const std::function<void(const PointJob&)>& on_start,
                                   const std::function<void(const PointJob&, const PointOutcome&)>& on_finish,
                                   const std::function<bool()>& stop = {});

// ---------------------------------------------------------------- aggregation

// The components of a mode, in column order.
std::vector<std::string> components_of_mode(const std::string& mode);

struct PointResult {
    SweepPoint point;
    PointState state = PointState::pending;
    std::string note;  // why there are no numbers (failed, unreadable summary.json)
    // Per component name: D, D_stderr, D_one_term, determined (the pinned
    // Hogg fit of earlier versions of tumble), and the share of its axial <dz^2>
    // in the top grain layer, less than a mean grain diameter below the free
    // surface; the grains' MSD D with its 95 % interval and the
    // free-amplitude Hogg D with its interval, NaN where not determined
    // (NaN: null / absent).
    struct Component {
        double D, D_stderr, D_one_term;
        bool determined;
        double surface_share;
        double msd_D = NAN, msd_lo = NAN, msd_hi = NAN;
        double hogg_D = NAN, hogg_lo = NAN, hogg_hi = NAN;
    };
    std::map<std::string, Component> components;
    double ke_ratio_total, ke_ratio_total_ref, ke_ratio_per_grain, ke_ratio_per_grain_ref;
    double angle_of_repose;  // degrees
    double grain_updates_per_second;
};

// Reads the point's summary.json if it is finished (state and note otherwise).
PointResult read_point_result(const SweepPoint& p);
// The result of a finished point from the text of its summary.json (an MPI
// rank sends it to rank 0); `source` names it in a note. Or of a point whose
// run ended with a non-zero exit code (where: the rank's line prefix).
PointResult point_result_from_summary(const SweepPoint& p, const std::string& summary_json, const std::string& source);
PointResult failed_point_result(const SweepPoint& p, int exit_code, const std::string& where);

// Writes DIR/sweep.csv (one row per point, plan order) and
// DIR/sweep_summary.csv (mean, standard deviation, count, and the 95 %
// bootstrap interval of the mean with the seed as the unit, from 3 seeds
// on, over seeds per mode and omega). Returns the number of points without results.
std::size_t write_sweep_tables(const std::filesystem::path& directory, const std::vector<PointResult>& results);

}  // namespace tumble::io
