// SPDX-License-Identifier: MIT
// Triangle meshes from STL files, binary or ASCII, into the engine's
// TriangleMesh (tumble/walls/mesh.hpp).
//
// Which kind: ASCII when the file begins with "solid" (after blanks) and
// the first word after that line is "facet" or "endsolid"; otherwise binary
// when its size is 84 + 50 n bytes, n the count at bytes 80-83 (some binary
// files begin with "solid" too: their header is free text); otherwise ASCII
// again when it begins with "solid" and holds text only (a malformed ASCII
// file, refused with its line); otherwise a binary file of the wrong size.
//   binary  80 bytes of header, n (uint32), then per triangle 12 float32
//           (normal, corners 1, 2, 3), 2 bytes of attribute; little-endian.
//   ASCII   solid NAME / facet normal NX NY NZ / outer loop / vertex X Y Z
//           (three times) / endloop / endfacet ... endsolid NAME; keywords in
//           any case; several solids in one file are read one after another.
// The normals in the file are not read (the engine takes N from the corner
// order, right-hand rule); nor are names and attributes.
//
// Placement: each corner x of the file becomes
//     x' = Rot(axis, angle) (scale x) + offset
// in that order: scaled about the file's origin (1e-3 for a file in mm),
// turned about an axis through that origin by the right-hand rule, then
// moved. Then the corners are welded (weld_triangles: identical coordinates
// after the placement make one vertex) and the mesh is checked (check_mesh).
//
// Refused, with ConfigError "FILE: WHERE: REASON" (WHERE a line, for ASCII,
// or a triangle counting from 1, with its line for ASCII; empty for the
// whole file), before any mesh is built: a missing or unreadable file, a
// file larger than max_stl_file_bytes, a binary file shorter than its count
// says (truncated: the triangle it ends in) or longer, an ASCII file that
// breaks the grammar, a coordinate that is not a finite number, a file
// without triangles, and what check_mesh refuses (a degenerate triangle, a
// repeated one). Open edges and edges of more than two faces are allowed.
// A placement that is not finite, a scale <= 0, or a zero axis is refused
// (WHERE: scale, rotation, offset) before the file is read.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>

#include "tumble/core/vec3.hpp"
#include "tumble/walls/mesh.hpp"

namespace tumble::io {

inline constexpr std::size_t max_stl_file_bytes = std::size_t{1} << 30;  // 1 GiB: 21 million binary triangles

struct StlRotation {
    Vec3 axis;           // any length > 0
    double angle = 0.0;  // rad, right-hand rule about the axis
};

struct StlPlacement {
    double scale = 1.0;  // file units to m
    std::optional<StlRotation> rotation;
    Vec3 offset;  // m
};

TriangleMesh read_stl(const std::filesystem::path& file, const StlPlacement& placement = {});

}  // namespace tumble::io
