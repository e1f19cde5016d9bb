// SPDX-License-Identifier: MIT
// Reads back what vtk_output.hpp writes, for `tumble render`: the walls of a
// snapshot (NNNNNN_walls.vtp). Only the layout tumble writes is read (VTK
// XML 1.0, UInt64 headers, data appended raw and compressed by
// vtkZLibDataCompressor, described at VtkFile in vtk_output.cpp), not VTK
// files in general.
#pragma once

#include <filesystem>

#include "tumble/walls/wall_surface.hpp"

namespace tumble::io {

// The triangles of every wall of a snapshot together (points m, the
// "position" array; triangles from "connectivity" and "offsets" of the
// Polys), or tumble::Error naming the file if it cannot be read or is not
// such a file.
WallSurface read_vtp_walls(const std::filesystem::path& file);

}  // namespace tumble::io
