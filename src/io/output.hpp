// SPDX-License-Identifier: MIT
// What a run writes into its output directory:
//   time_series.csv       one row per sample: time, energies (total and per
//                         material), contacts, largest overlap, list builds,
//                         the load on each smooth wall
//   snapshots/NNNNNN.csv  per-particle state, rows ordered by global id, each
//                         with the time and step of the snapshot
//   run.json              the settings in force, the time step and its limits,
//                         the speed of the run
// Numbers are written in the shortest form that reads back to the same
// double, so two runs with the same input and seed give identical files.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "io/run_lock.hpp"
#include "io/snapshot_data.hpp"
#include "io/step_times.hpp"
#include "tumble/sim/simulation.hpp"

namespace tumble::io {

// Opens a file for writing (truncating it), or tumble::Error naming it.
std::ofstream open_for_writing(const std::filesystem::path& file);
// Opens a file for appending (after a resume), or tumble::Error naming it.
std::ofstream open_for_appending(const std::filesystem::path& file);
// Writes `bytes` to `file` so that no crash, kill or full disk leaves a
// partial file under that name: into file.tmp, flushed to the disk (fsync),
// renamed over `file`, the directory flushed. On failure the temporary file
// is removed and tumble::Error names it and the reason (e.g. "File too large").
void write_file_atomically(const std::filesystem::path& file, std::string_view bytes);
// The same without flushing to the disk, for the files written in one piece
// that a run writes often or that are large (snapshots, tables, images): a
// failed write or a kill leaves no cut file under `file`'s name, only the
// cost of the fsync is saved (a power cut may still lose the newest of them).
void write_file_whole(const std::filesystem::path& file, std::string_view bytes);
// The same of parts written one after the other (no copy of them joined).
void write_file_whole(const std::filesystem::path& file, std::span<const std::string_view> parts);
// Flushes and reports a failed write (disk full, ...) as tumble::Error naming the file.
void check_written(std::ofstream& out, const std::filesystem::path& file);

class TimeSeriesWriter {
public:
    // continuing: append to the file as it stands (a resumed run), no header.
    // The columns: those of Observables, per material of the scenario, and
    // per wall of it the load (wall_NAME_fx, _fy, _fz in N; _tx, _ty, _tz
    // in N m, about where the wall's point is).
    TimeSeriesWriter(const std::filesystem::path& file, const Scenario& scenario, bool continuing = false);
    void write(const Observables& o);

private:
    std::filesystem::path path_;
    std::ofstream out_;
};

// Array indices of the particles in the order of their global ids (the
// order of the rows of every snapshot format).
std::vector<std::size_t> order_by_id(const ParticleStore& p);

// Writes snapshots/NNNNNN.csv (NNNNNN = the sample number) and returns its path.
std::filesystem::path write_snapshot(const std::filesystem::path& directory, int number, const SnapshotData& snapshot);
std::filesystem::path write_snapshot(const std::filesystem::path& directory, int number, const Simulation& sim);

// Every file and folder that tumble writes into a run directory: tumble run,
// drum, resume, analyze (with --so-far), fields, plot and render (with the movie
// DIR/NAME.mp4, NAME the directory's, which has no fixed name and is removed
// beside these). What --force clears, so it holds them all: a test runs each
// command and checks every file it wrote against this list
// (tests/unit/test_force.cpp). summary.json comes first: it marks a finished
// drum run (tumble sweep), so it goes before anything else. Not the lock
// file, and not a sweep's log.txt and failed.txt in its points' directories,
// which the sweep keeps itself.
inline constexpr std::string_view run_files[] = {
    "summary.json",  "summary.txt",     "run.json",          "drum_run.toml",      "time_series.csv",
    "drum_series.csv", "profiles.csv",  "band_profile.csv",  "profile_comparison.csv", "depth_mobility.csv",
    "depth_mobility_long.csv", "axial_msd.csv", "bed_structure.csv", "flow_profile.csv", "bands.json",
    "bands.csv",     "band_positions.csv", "band_spectrum.csv", "band_edges.csv",   "radial_shells.csv", "kymograph.png",
    "particles.pvd", "contacts.pvd",    "walls.pvd",         "snapshots",         "checkpoints",        "figures",
    "so_far",        "frames",          "fields",            "flowing_layer"};

// tumble render's movie by default: DIR/NAME.mp4, NAME the directory's.
std::filesystem::path default_movie_file(const std::filesystem::path& directory);

// Creates the output directory and locks it for this process (RunLock).
// Refuses (tumble::Error) one that already holds a run, unless `overwrite`:
// then the earlier run's files (run_files, their temporary files FILE.tmp
// and the movie) are removed before anything new is written. Only a
// directory that tumble wrote before (it holds the lock file) is cleared;
// one with its own snapshots/ or checkpoints/ is refused.
RunLock prepare_output_directory(const std::filesystem::path& directory, bool overwrite);

struct RunSummary {
    std::string scenario_file;
    std::uint64_t seed = 0;
    double duration = 0.0;
    std::int64_t steps = 0;
    double wall_seconds = 0.0;
    std::size_t particles = 0;
    std::size_t free_particles = 0;
    StepTimesSpread time_by_phase;  // of this process's steps (since the start, or the resume)
};
void write_run_json(const std::filesystem::path& file, const Simulation& sim, const RunSummary& summary);

}  // namespace tumble::io
