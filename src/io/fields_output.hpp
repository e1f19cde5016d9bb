// SPDX-License-Identifier: MIT
// Coarse-grained fields (tumble/analysis/coarse_grain.hpp) as files:
//   NAME.csv   one row per node of the grid, x fastest, then y, then z:
//              the node's x, y, z (m; the middle of [lo, hi] along an
//              averaged axis), then every field, a column per component
//              (velocity_x ..., stress_xy = sigma_xy: the force's x, the
//              branch's y). Loads with numpy.genfromtxt(names=True) and
//              pandas.read_csv as it is. (In the drum's coordinates the
//              axes are s, d, z: velocity_s, stress_sd.)
//   NAME.vti   the same for ParaView: VTK ImageData (vtk_output.hpp's
//              compressed binary), its points the nodes, every field a
//              point-data array (tensors of 9 components, row by row).
// Both say the number of samples averaged (FieldData "samples", CSV column
// "samples").
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "io/json.hpp"
#include "tumble/analysis/coarse_grain.hpp"
#include "tumble/analysis/flowing_layer.hpp"

namespace tumble::io {

// One field as the writers list it: its name, components per node (1, 3 or
// 9) and the component names' suffixes, its values node by node (a view of
// the Fields' own memory).
struct FieldColumn {
    std::string name;
    std::vector<std::string> components;  // {""} for a scalar, {"x", "y", "z"}, {"xx", "xy", ...}
    std::span<const double> values;       // components.size() per node
};
// The fields in the order the files give them (views: `f` must outlive them).
// `axes` names the grid's three axes in the components' names: "xyz"
// (velocity_x, stress_xy), or "sdz" for fields in the drum's coordinates
// (velocity_s, stress_sd; analysis/flowing_layer.hpp).
std::vector<FieldColumn> field_columns(const analysis::Fields& f, const std::string& axes = "xyz");

// The bytes the files' writers hold besides the fields for a grid of
// `nodes` nodes: the .vti file's compressed arrays at most (doubles barely
// compress), built in memory before it is written; the CSV file is written
// a block of rows at a time.
double fields_file_bytes(std::size_t nodes);

// tumble::Error naming the file if it cannot be written. The node's
// coordinates are the columns named by `axes` (field_columns).
void write_fields_csv(const std::filesystem::path& file, const analysis::Fields& f, const std::string& axes = "xyz");

// The drum frame's numbers, as drum_frame.json gives them (docs/FIELDS.md,
// "The drum's frame"): the surface's angle (degrees) and line, the bed's
// solid fraction, the surface velocity and the flowing layer's thickness.
Json drum_frame_json(const analysis::DrumSurface& surface, const analysis::FlowingLayer& layer, double span);

}  // namespace tumble::io
