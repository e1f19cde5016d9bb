// SPDX-License-Identifier: MIT
// Coarse-grained fields of a run (tumble fields, tumble.fields in Python):
// the settings as a user gives them, checked and turned into a grid, and the
// time average over states taken from the run's checkpoint
// (docs/FIELDS.md).
//
// Where the states come from: a run's snapshots hold the grains and the
// normal force of each grain-grain contact, but not the tangential forces
// nor the contacts with smooth walls, which the contact stress needs. The
// fields are therefore taken from the run's newest checkpoint (or a chosen
// one): its state is restored into the engine and continued in memory, and
// each sample is one step taken with the contacts recorded, so every
// contact force is the one the contact law gave (docs/FIELDS.md, "States").
// Nothing is written into the run directory but the output folder.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tumble/analysis/coarse_grain.hpp"
#include "tumble/analysis/flowing_layer.hpp"
#include "tumble/analysis/simulation_fields.hpp"
#include "io/checkpoint.hpp"
#include "tumble/core/domain.hpp"

namespace tumble::experiments {

// The grid and kernel as given; an unset value takes its default from the
// grains (grid_settings).
struct FieldSettings {
    std::optional<Vec3> lo, hi;   // m; default: the grains' extent, centres +- radius
    std::optional<double> cell;   // m, cell size along every resolved axis (default: the width)
    std::optional<std::array<double, 3>> cells;  // cells per axis (instead of cell); 1 on an averaged axis
    std::string average;          // the averaged axes: "", "x", "yz", ...
    analysis::CgKernel kernel = analysis::CgKernel::gaussian;
    std::optional<double> width;  // m; default: the grains' mean radius
    double max_memory_gib = 0.0;  // the limit (0: half the machine's memory)
    bool vti = false;             // the fields will be written as .vti: its buffer counts too
};

// What is wrong with the settings on their own (before any grain is seen),
// naming the key: "width: ...", "cell: ...", "cells: ...", "average: ...",
// "hi: ..."; "" if nothing.
std::string field_settings_problem(const FieldSettings& s);

// The settings with their defaults from the grains, checked
// (analysis::cg_settings_problem) and the memory of the grid against the
// limit (limits.hpp, check_memory, naming `memory_option`): tumble::Error
// with the reason otherwise. With `cell`, hi moves up to a whole number of
// cells from lo. An averaged axis along which `domain` is periodic takes the
// domain's extent by default, and is periodic (analysis::CgGrid) where its
// lo and hi are the domain's.
analysis::CgSettings grid_settings(const FieldSettings& s, const analysis::CgGrains& grains,
                                   const std::string& memory_option, const Domain* domain = nullptr);
// The same when nothing needs the grains (lo, hi, width and the cells all
// given); none otherwise.
std::optional<analysis::CgSettings> grid_settings(const FieldSettings& s, const std::string& memory_option);

// The samples of a run directory: `samples` states `every` seconds of
// simulated time apart, from the checkpoint (empty: the run's newest).
//
// frame "drum" (a run of tumble drum): `fields` is the drum's cross-section
// (the settings' grid, averaged along z), the free surface is found on it
// (analysis::find_drum_surface, fitted over the middle `span` of its length),
// and the samples are taken again from the checkpoint (the same states: no
// state is kept) and coarse-grained in the drum's coordinates (s, d, z)
// into the depth profile: resolved along d at the cross-section's cell size
// from 3 widths above the surface to the deepest a grain can reach under it,
// averaged along s over the span and along z over the cross-section's
// extent (docs/FIELDS.md, "The drum's frame").
struct RunFieldsOptions {
    std::filesystem::path run_directory;
    std::filesystem::path checkpoint;
    int samples = 1;
    double every = 0.01;  // s
    FieldSettings settings;
    std::string frame = "lab";  // "lab" or "drum"
    double span = 0.5;          // the drum frame: the middle part of the surface averaged, in (0, 1]
    // The drum frame: cells along s (across the span) and z (along the
    // cross-section's extent) of a second grid in the drum's coordinates,
    // resolved along d as the profile is (DrumLayer::resolved); (1, 1): none.
    std::array<double, 2> frame_cells{1.0, 1.0};
    std::string memory_option = "--max-memory GIB";
};
struct DrumLayer {
    analysis::DrumSurface surface;
    analysis::Fields profile;  // in the drum's coordinates: x = s, y = d, z
    analysis::FlowingLayer layer;
    // The fields resolved along s and z too (RunFieldsOptions::frame_cells),
    // on the profile's extent and its nodes along d.
    std::optional<analysis::Fields> resolved;
};
struct RunFields {
    analysis::Fields fields;
    std::filesystem::path checkpoint;  // the file the states came from
    std::vector<double> times;         // s, of the samples
    double seconds = 0.0;              // the coarse-graining's own time (wall clock), s
    std::optional<DrumLayer> drum;     // frame "drum"
};

// What is wrong with the frame, span and frame cells on their own (and the
// averaged axes the drum frame needs), naming the key; "" if nothing.
std::string frame_problem(const RunFieldsOptions& o);
// `say` hears what is about to happen (the checkpoint, the grid and its
// memory before it is allocated). tumble::Error naming the option or the
// file for bad settings, a missing directory or checkpoint, before any step.
RunFields run_fields(const RunFieldsOptions& options, const std::function<void(const std::string&)>& say);

// The files of the fields in `out` (created if missing): fields.vti and
// fields.csv, or the one `format` ("vti", "csv", "both") names.
void write_fields_files(const std::filesystem::path& out, const analysis::Fields& fields, const std::string& format);
// The drum frame's files in `out` (created if missing), beside the
// cross-section's: profile.csv, frame.csv where resolved, drum_frame.json
// (io::drum_frame_json); and the line that says what it found.
void write_drum_layer_files(const std::filesystem::path& out, const DrumLayer& layer, double span);
std::string drum_layer_summary(const DrumLayer& layer);

// Fields taken while a run goes (tumble run --fields, tumble drum --fields,
// tumble.run_drum(fields=...); docs/FIELDS.md, "During a run"): the state at
// the end of every `every` seconds of simulated time from `from` on, each a
// step taken with its contacts recorded, as tumble fields takes them from a
// checkpoint, averaged into one grid and written when the run ends.
//
// frame "drum" (a run of tumble drum): the grid is the drum's cross-section
// (averaged along z); at the run's end the free surface is found on it as
// tumble fields --frame drum finds it, and the depth profile is carried
// from it (analysis::drum_profile_of: the states are gone, so they cannot
// be taken again in the surface's coordinates).
struct FieldsDuringRun {
    FieldSettings settings;  // lo, hi default: the simulation's domain
    double every = 0.01;     // s between the states
    double from = 0.0;       // s of simulated time: the first state is the first step's end at or after it
    int samples = 0;         // the most states taken (0: until the run ends)
    std::string format = "both";
    std::string frame = "lab";  // or "drum"
    double span = 0.5;          // the drum frame: the middle part of the surface averaged, in (0, 1]
};
// The settings from KEY=VALUE items (an item may hold several, separated by
// spaces; a later one replaces an earlier one of the same key): the keys
// io::field_keys, lo and hi as X,Y,Z, cells as NX,NY,NZ. tumble::Error
// "fields: KEY: reason" for an unknown key or a value that is not one.
FieldsDuringRun parse_fields_during_run(const std::vector<std::string>& items);

// The plan of the fields of `items` (parse_fields_during_run) for one
// simulation, made and checked before its first step: the grid (its lo and
// hi the domain's unless given, its width the grains' mean radius at the
// start unless given) and its memory against the run's limit
// (`max_memory_gib`, --max-memory; 0: half the machine's), the steps of the
// states. `last_step`: the run's last step where it is known (0
// otherwise), which `from` must not pass. tumble::Error naming the key
// otherwise, and for a simulation shared among MPI ranks.
//
// A checkpoint of the run keeps the recorder (save): its items, grid and
// steps, the states' times, reach and the sums, 24 numbers a node; a resumed run
// goes on from them (resumed) and writes at its end the fields an
// uninterrupted run would have written, bit for bit.
class FieldRecorder {
public:
    // `drum`: the simulation is a drum's (frame drum is refused otherwise).
    FieldRecorder(const std::vector<std::string>& items, const Simulation& sim, std::int64_t last_step,
                  double max_memory_gib, bool drum);
    // Into a checkpoint's record (keys "fields.*"); nothing once written.
    void save(io::CheckpointRecord& record) const;
    // The recorder a checkpoint's record saved, for the simulation restored
    // from it; none if the run took no fields. tumble::Error naming the
    // checkpoint if the record's fields do not fit together, or the grid's
    // memory is more than half the machine's.
    static std::optional<FieldRecorder> resumed(const io::CheckpointRecord& record, const Simulation& sim);
    // `steps` steps of `sim`, the states due among them taken (Simulation::advance otherwise).
    void advance(Simulation& sim, std::int64_t steps);
    // The fields of the states taken so far into RUN/fields
    // (write_fields_files), or with frame drum into RUN/flowing_layer with
    // the drum frame's files (write_drum_layer_files; where no surface is
    // found, the cross-section alone and a line saying why); lines that say
    // what was written.
    std::string write(const std::filesystem::path& run_directory);
    const analysis::CgGrid& grid() const { return settings_.grid; }
    std::string summary() const;  // the grid and its memory, and the states' steps

private:
    FieldRecorder() = default;

    std::vector<std::string> items_;
    FieldsDuringRun options_;
    analysis::CgSettings settings_;
    std::int64_t first_ = 0, between_ = 0;  // the steps of the states: first_ + k between_
    double dt_ = 0.0;
    std::vector<double> times_;  // s, of the states taken
    // m: the largest distance of a grain centre from the z axis in the
    // states taken, and the largest radius (the drum frame's profile grid)
    double reach_ = 0.0, largest_ = 0.0;
    std::optional<analysis::FieldAccumulator> sum_;
};

// The memory the fields of grid g need (analysis::cg_memory_bytes, and the
// .vti file's buffer where s.vti), and the grid's size as said before it
// is allocated: "NX x NY x NZ nodes (N), MEMORY".
double field_memory_bytes(const FieldSettings& s, const analysis::CgGrid& g);
std::string grid_summary(const FieldSettings& s, const analysis::CgGrid& g);

}  // namespace tumble::experiments
