// SPDX-License-Identifier: MIT
// The files of a drum run directory (docs/DRUM.md):
//   drum_run.toml      what was run: settings, geometry, components
//   drum_series.csv    one row per sample: revolutions N, time, angle of
//                      repose, bed centre, and per component <z>, its standard
//                      error, kinetic energy (total and per grain)
//   profiles.csv       the axial concentration profiles C(z, N)
//   depth_mobility.csv  axial mean squared displacement per revolution by
//                      depth below the free surface (from the snapshots)
//   summary.json, summary.txt   the analysis (`tumble analyze DIR`)
//   band_profile.csv and the band analysis: io/band_output.hpp
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/json.hpp"
#include "tumble/analysis/axial_msd.hpp"
#include "tumble/analysis/bands.hpp"
#include "tumble/analysis/depth_mobility.hpp"
#include "tumble/analysis/drum_measure.hpp"
#include "tumble/setup/paper_materials.hpp"

namespace tumble::io {

struct DrumComponent {
    std::string name;         // "material-1", "material-2", or "left", "right"
    std::size_t grains = 0;
    double mass = 0.0;        // kg, all its grains
    double start_side = 0.0;  // -1: started at z < 0, +1: at z > 0
};

struct DrumRunInfo {
    std::string mode;
    double omega = 0.0;            // rad/s
    double froude = 0.0;           // omega^2 R / g
    double revolutions = 0.0;      // asked for
    std::uint64_t seed = 0;
    std::size_t wall_particles = 0;
    double inner_radius = 0.0;     // m
    double inner_length = 0.0;     // m: the bed length L of the Hogg solution
    double solid_fraction = 0.0;   // grain volume / drum volume
    double fill_fraction = 0.0;    // bed cross-section / drum cross-section, measured after settling
    double dt = 0.0;               // s
    double skin = 0.0;             // m, the neighbour list's as used (0: not recorded, a run before 2026-12-02)
    int samples_per_revolution = 0;
    int profile_bins = 0;
    int band_bins = 0;             // axial bins of band_profile.csv (0: none, a run from before the band analysis)
    double settle_time = 0.0;      // s of simulated settling
    bool settled = false;          // reached the settling criterion
    double wall_seconds = 0.0;     // of the rotating phase
    double grain_updates_per_second = 0.0;
    int threads = 1;               // of the time step (tumble drum --threads)
    std::string isa;               // instruction set of the hot loops (tumble/core/isa.hpp), of the last part run
    std::string shear_model = "paper";    // keyword of the shear model (contact_law.hpp)
    std::string friction_normal = "net";  // keyword of the normal force that limits friction
    std::string tangential_stiffness = "paper";  // keyword of the shear and twisting springs' stiffness
    // J/m^2, every pair's W (the attraction); < 0: the pairs' W differ
    // (the drum's own materials' [[pair]] tables)
    double surface_energy = paper::surface_energy;
    std::string walls = "particles";     // the walls' kind (keyword of drum_wall_kinds; setup/drum.hpp)
    std::string mesh;                    // a mesh mantle's STL file and its unit in m (none: the smooth
    double mesh_scale = 1.0;             // cylinder in triangles)
    // The drum's materials as the scenario holds them (empty: the paper's,
    // a run from before they were recorded), whether they are the paper's,
    // and the names of those of the large and small grains, the wall and
    // the caps.
    std::vector<Material> materials;
    bool paper_materials = true;
    std::string large_material = "material-1", small_material = "material-2", wall_material = "wall",
                cap_material = "wall";
    bool periodic_axis = false;    // no end caps: the axis is periodic with period inner_length
    double spin_up_time = 0.0;     // s: linear ramp from rest to omega (0: none)
    std::string arrangement = "halves";  // the start's axial arrangement (keyword; setup/drum.hpp)
    std::vector<double> band_edges;      // z (m) of the start's band edges, -L/2 to L/2 (empty: not recorded)
    double cap_friction = -1.0;          // mu between grains and caps (< 0: the wall's)
    // tumble drum --until-band-change: revolutions the band count must
    // differ from the start's before the run ends (0: off); if it ended so,
    // the N since which it differed and the counts at the start and end
    // (band_change_since < 0: the run turned every revolution asked).
    double until_band_change = 0.0;
    double band_change_since = -1.0;
    int bands_at_start = 0, bands_at_end = 0;
    std::vector<DrumComponent> components;
};

void write_drum_run_info(const std::filesystem::path& file, const DrumRunInfo& info);
DrumRunInfo read_drum_run_info(const std::filesystem::path& file);
// The same as TOML text (kept in checkpoints); `name` is used in messages.
std::string drum_run_info_text(const DrumRunInfo& info);
DrumRunInfo parse_drum_run_info(std::string_view text, const std::filesystem::path& name);
// Why the Hogg solution does not describe <z> of this run, or "" if it
// does: it needs the halves start between end caps (the mean of a wrapped
// coordinate follows no Hogg law; a mixed or banded start has no step to
// relax).
std::string hogg_not_applicable(const DrumRunInfo& info);

class DrumSeriesWriter {
public:
    // continuing: append to the files as they stand (a resumed run), no header.
    DrumSeriesWriter(const std::filesystem::path& directory, const DrumRunInfo& info, bool continuing = false);
    void write(double revolutions, double time, const analysis::DrumState& state);

private:
    std::filesystem::path series_path_, profiles_path_;
    std::ofstream series_, profiles_;
    double inner_length_;
};

// The drum_series.csv columns, read back.
struct DrumSeries {
    std::vector<double> revolutions, time, angle_of_repose;
    std::vector<std::vector<double>> mean_z, mean_z_stderr, kinetic_energy, kinetic_per_grain;  // [component][sample]
};
DrumSeries read_drum_series(const std::filesystem::path& file, std::size_t components);

// profiles.csv read back: for each sample N, C[component][bin].
struct DrumProfiles {
    std::vector<double> revolutions;
    std::vector<double> bin_centre;  // z, m
    std::vector<std::vector<std::vector<double>>> concentration;  // [sample][component][bin]
};
DrumProfiles read_drum_profiles(const std::filesystem::path& file, std::size_t components, std::size_t bins);

// A particle snapshot (snapshots/NNNNNN.csv) of a drum run: its free grains,
// sorted by id, at N = omega (t - rotation_start) / 2 pi revolutions.
// The grains' masses come from their materials' densities (by name):
// `materials`, those of the run (DrumRunInfo::materials).
analysis::GrainFrame read_snapshot_grains(const std::filesystem::path& file, double rotation_start, double omega,
                                          const std::vector<Material>& materials = paper::materials());

// The particle snapshots taken during the rotation (N >= 0), in time order,
// but the `leave_newest` newest files (a run going on may be writing one).
std::vector<analysis::GrainFrame> read_rotation_frames(const std::filesystem::path& directory, const DrumRunInfo& info,
                                                       std::size_t leave_newest = 0);

// What the particle snapshots of a rotation cover. A run continued from a
// kept checkpoint on another machine has its series but not its earlier
// snapshots, and every measurement made from the snapshots then covers the
// later revolutions only. summary.txt says so (describe()), and
// summary.json has it under "snapshots" (json()).
struct SnapshotCoverage {
    std::size_t count = 0;
    double first = 0.0, last = 0.0, spacing = 0.0;  // revolutions
    bool from_start = false;                        // the first at N = 0 (within half a spacing)
    std::string describe() const;
    Json json() const;
};
SnapshotCoverage snapshot_coverage(const std::vector<analysis::GrainFrame>& frames);

struct AnalyzeOptions {
    // The start-up left out of the fits: revolutions N >= this (the bed
    // spins up and reaches its steady flow within the first revolution at
    // the default speed; more at high speed).
    double first_revolution = 1.0;
    // The thresholds of the band segmentation (docs/BAND-ANALYSIS.md; tumble analyze
    // --band-z-enter ...), checked by analysis::check_band_options.
    analysis::BandOptions bands;
    // The band analysis in the text even for a run without bands (tumble
    // analyze --band-report); otherwise only for one with bands (BandReport).
    bool band_report = false;
};

// Fits D per component (grains' axial MSD, free-amplitude Hogg, drift), the
// kinetic-energy ratios and the profile comparison; writes summary.json,
// summary.txt, axial_msd.csv and the other analysis files into `directory`
// and returns the text.
std::string analyze_drum_run(const std::filesystem::path& directory, const AnalyzeOptions& options = {});

// The grains' axial MSD D of one component of a drum run, the one estimator
// behind summary.json's "msd" and summary.txt's headline D (and Python's
// Run.msd): the particle snapshots from options.first_revolution on, in
// blocks of a fifth of that span, 2 to 4 revolutions in whole snapshot
// spacings; block > 0 asks for blocks of that many revolutions instead.
// `frames` are the run's rotation frames (read_rotation_frames).
analysis::MsdEstimate drum_msd(const std::vector<analysis::GrainFrame>& frames, const DrumRunInfo& info,
                               std::size_t component, const AnalyzeOptions& options = {}, double block = 0.0);
// The block length drum_msd uses by default, revolutions (0: too few frames).
double drum_msd_block(const std::vector<analysis::GrainFrame>& frames, const DrumRunInfo& info,
                      const AnalyzeOptions& options = {});

// A D in summary.json: the number when determined, else null; and the best
// estimate of one not determined (null when determined or when there is none).
Json determined_value(double D, bool determined);
Json best_estimate(double D, bool determined);

// An estimate of D (m^2/rev) in summary.json and bands.json: D (null when not
// determined), D_best_estimate (the estimator's value when not determined),
// D_lo and D_hi (its 95 % interval), determined, note.
Json estimate_json(double D, const analysis::Interval& interval, bool determined, const std::string& note);

// The grains' axial MSD estimate: estimate_json and the lags fitted, the blocks.
Json msd_json(const analysis::MsdEstimate& m);

}  // namespace tumble::io
