// SPDX-License-Identifier: MIT
// Particles from a CSV file (format: docs/SCENARIO.md, "csv" blocks).
//
// The first non-blank, non-comment line is the header: a comma-separated
// list of column names, in any order, each at most once, from
//     x, y, z          position, m (required)
//     vx, vy, vz       velocity, m/s (default 0)
//     wx, wy, wz       angular velocity, rad/s (default 0)
//     radius           m (default: the material's radius)
//     material         material name (required unless a default is given)
//     motion           motion name; empty = free (default free)
//     tag              integer label (default 0)
// Every following line is one particle with exactly as many fields as the
// header. Fields are trimmed of spaces and tabs; there is no quoting (names
// cannot contain commas). An empty field means "the default". Blank lines
// and lines whose first non-blank character is '#' are skipped. Errors throw
// ConfigError naming the file, the line (1-based) and the column. Lines are
// at most 4096 bytes and rows at most max_scenario_particles (config.hpp), so
// a binary or endless file is refused with bounded memory.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tumble/sim/scenario.hpp"

namespace tumble::io {

// Values for columns that are absent or cells that are empty. The scenario
// reader fills them from the keys of the [[particles]] block.
struct CsvDefaults {
    std::optional<std::int32_t> material;  // index into the material list
    std::int32_t motion = free_motion;
    std::int32_t tag = 0;
    Vec3 velocity;          // m/s
    Vec3 angular_velocity;  // rad/s
    std::optional<double> radius;  // m; absent: the material's radius
};

// Material and motion names are looked up in `materials` (by Material::name)
// and `motion_names`; the returned specs hold their indices. With
// `line_numbers` non-null it receives the file line of each particle.
std::vector<ParticleSpec> read_particle_csv(const std::filesystem::path& file, const std::vector<Material>& materials,
                                            const std::vector<std::string>& motion_names,
                                            const CsvDefaults& defaults = {},
                                            std::vector<std::size_t>* line_numbers = nullptr);

}  // namespace tumble::io
