// SPDX-License-Identifier: MIT
// Snapshots that ParaView (or any VTK reader) opens directly, as a time
// series. VTK XML formats (https://docs.vtk.org/en/latest/design_documents/
// VTKFileFormats.html), version 1.0, with the data appended in binary and
// compressed by zlib (compressor="vtkZLibDataCompressor", header_type
// UInt64; the layout is described at VtkFile in vtk_output.cpp): numbers
// read back bit for bit, and two runs with the same input give identical
// files.
//
//   NNNNNN.vtu   the particles: VTK UnstructuredGrid, one VTK_VERTEX cell per
//                sphere, points = centres X (m), rows ordered by global id.
//                Point data: id (Int64), velocity (m/s), angular_velocity
//                (rad/s), radius (m), material (Int32, index into the
//                scenario's materials, whose names are in the FieldData
//                String array "material_names"), tag (Int32), kinematic (UInt8, 1 for
//                spheres on a prescribed motion), contacts (Int32, number of
//                sphere-sphere contacts; flat walls are not counted).
//   NNNNNN.vtp   the contact network: VTK PolyData, one line per touching
//                pair from the centre of i to the centre of the image of j
//                nearest i (so lines never cross a periodic box). Cell data:
//                id_i, id_j (Int64), normal_force F_n (N, > 0 repulsive),
//                overlap h (m), normal n (j -> i). Flat-wall contacts are not
//                included (see tumble/sim/contact_network.hpp).
//   NNNNNN_walls.vtp  the smooth walls (Scenario::walls), where their motions
//                have carried them: VTK PolyData, triangles (walls/
//                wall_surface.hpp; infinite planes and cylinders cut to the
//                box). Cell data: wall (Int32, index into the scenario's walls,
//                whose names are in the FieldData String array "wall_names").
//   NAME.vti     coarse-grained fields (tumble fields): VTK ImageData, its
//                points the grid's nodes, each field a point-data array
//                (io/fields_output.hpp lists them).
//   *.pvd        a ParaView collection: one DataSet entry per (time, file).
//
// Both data files carry the simulated time in FieldData "TimeValue" (s),
// which ParaView reads as the time of a dataset opened without an index,
// and the step number in FieldData "step".
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "io/snapshot_data.hpp"
#include "tumble/analysis/coarse_grain.hpp"
#include "tumble/sim/simulation.hpp"

namespace tumble::io {

// Writes the particles of `sim` to `file` (.vtu), or tumble::Error naming it.
void write_vtu_snapshot(const std::filesystem::path& file, const SnapshotData& snapshot);
void write_vtu_snapshot(const std::filesystem::path& file, const Simulation& sim);

// Writes the contact network of `sim` to `file` (.vtp), or tumble::Error.
void write_vtp_contact_network(const std::filesystem::path& file, const SnapshotData& snapshot);
void write_vtp_contact_network(const std::filesystem::path& file, const Simulation& sim);

// Writes the walls of a snapshot to `file` (.vtp), or tumble::Error.
void write_vtp_walls(const std::filesystem::path& file, const SnapshotData& snapshot);

// Writes coarse-grained fields to `file` (.vti), or tumble::Error.
void write_vti_fields(const std::filesystem::path& file, const analysis::Fields& fields);

// A ParaView collection file (.pvd) that indexes datasets by time. The
// index is written at construction (empty) and rewritten completely at every
// add(), into a temporary file that is then renamed over it, so a crash
// leaves either the old or the new index, never a broken one, and a failed
// write leaves the old one and no temporary file. Dataset paths
// are stored as given, relative to the directory of the .pvd file.
// Keep one index per kind of dataset (e.g. particles.pvd, contacts.pvd).
class PvdIndex {
public:
    explicit PvdIndex(std::filesystem::path file);
    void add(double time, const std::filesystem::path& dataset_relative_path);

    const std::filesystem::path& file() const { return file_; }

private:
    void rewrite() const;

    std::filesystem::path file_;
    std::vector<std::pair<double, std::string>> entries_;  // time (s), dataset path
};

}  // namespace tumble::io
