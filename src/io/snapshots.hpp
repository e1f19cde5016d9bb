// SPDX-License-Identifier: MIT
// The particle snapshots of a run, numbered from 0, each written four ways:
//   snapshots/NNNNNN.csv   per-particle state as text (output.hpp)
//   snapshots/NNNNNN.vtu   the same for ParaView (vtk_output.hpp)
//   snapshots/NNNNNN.xyz   the same as extended XYZ, for OVITO (xyz_output.hpp)
//   snapshots/NNNNNN.vtp   the contact network: a line per contact with its normal force
//   snapshots/NNNNNN_walls.vtp  the smooth walls, where a scenario has them
// and the ParaView time-series indexes in the run directory, particles.pvd,
// contacts.pvd and walls.pvd (open them in ParaView: File > Open). The CSV files are
// read back for `tumble render`. A run shared among MPI ranks writes the same
// files, gathered on rank 0 (write() is then collective).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/csv_table.hpp"
#include "io/vtk_output.hpp"
#include "tumble/sim/simulation.hpp"
#include "tumble/walls/wall_surface.hpp"

namespace tumble::io {

class SnapshotSeries {
public:
    // earlier_times: the times of the snapshots a resumed run has already
    // written (their files are kept; the indexes are rewritten to list them).
    // walls: the scenario has smooth walls (Scenario::walls), drawn too.
    explicit SnapshotSeries(const std::filesystem::path& directory, const std::vector<double>& earlier_times = {},
                            bool walls = false);
    void write(const Simulation& sim);
    const std::vector<double>& times() const { return times_; }

private:
    void add_to_indexes(double time);

    std::filesystem::path directory_;
    std::optional<PvdIndex> particles_, contacts_, walls_;  // on rank 0 only
    std::vector<double> times_;
};

// What a snapshots/NNNNNN.csv says of each particle, in the file's order
// (by global id); what `tumble render` draws.
struct SnapshotParticles {
    std::vector<Vec3> position;            // m
    std::vector<double> radius;            // m
    std::vector<std::int32_t> material;    // index into material_names
    std::vector<std::string> material_names;  // in the order they first appear
    std::vector<std::int32_t> tag;
    std::vector<std::uint8_t> kinematic;   // 1: moves by a prescribed motion (a drum wall particle)
    std::optional<double> time;            // s, when it was taken; none if the file does not say
    WallSurface walls;                     // the smooth walls: read_snapshot_walls, none until then
};
// tumble::Error naming the file if it cannot be read or lacks a column.
SnapshotParticles read_snapshot_csv(const std::filesystem::path& file);

// The walls of the snapshot whose CSV file is `csv_file`, all in one:
// NNNNNN_walls.vtp beside it (vtk_input.hpp); no triangles if it has none
// (the run has no smooth walls). tumble::Error if the file cannot be read.
WallSurface read_snapshot_walls(const std::filesystem::path& csv_file);

// The simulated time a snapshot CSV was taken at, s: its `time` column, or
// the first line "# time = T s, step = S" of snapshots written before it
// had one; none if it says neither.
std::optional<double> snapshot_time(const CsvTable& csv);

// The snapshot CSV files of a run directory (DIR/snapshots/NNNNNN.csv), in
// the order of their numbers; empty if there are none.
std::vector<std::filesystem::path> list_snapshot_csv(const std::filesystem::path& directory);

}  // namespace tumble::io
