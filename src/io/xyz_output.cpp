// SPDX-License-Identifier: MIT
#include "io/xyz_output.hpp"

#include <cctype>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "io/output.hpp"

namespace tumble::io {

namespace {

// A material name as one word of a line: blanks and quotes become '_'.
std::string word(std::string name) {
    for (char& c : name)
        if (std::isspace(static_cast<unsigned char>(c)) || c == '"') c = '_';
    return name;
}

// Lattice, Origin and pbc of the domain; no Lattice if an axis has no finite length.
std::string cell(const Domain& d) {
    const Vec3 L = d.length();
    const auto flag = [](bool b) { return b ? 'T' : 'F'; };
    const std::string pbc =
        fmt::format("pbc=\"{} {} {}\"", flag(d.periodic[0]), flag(d.periodic[1]), flag(d.periodic[2]));
    for (int k = 0; k < 3; ++k)
        if (!std::isfinite(L[k]) || L[k] <= 0.0) return pbc;
    return fmt::format("Lattice=\"{} 0 0 0 {} 0 0 0 {}\" Origin=\"{} {} {}\" {}", L.x, L.y, L.z, d.lo.x, d.lo.y, d.lo.z,
                       pbc);
}

}  // namespace

void write_xyz_snapshot(const std::filesystem::path& file, const Simulation& sim) {
    write_xyz_snapshot(file, snapshot_of(sim));
}

void write_xyz_snapshot(const std::filesystem::path& file, const SnapshotData& snapshot) {
    const ParticleStore& p = snapshot.particles;
    std::vector<std::string> species;
    for (const std::string& name : snapshot.material_names) species.push_back(word(name));

    fmt::memory_buffer b;
    fmt::format_to(fmt::appender(b),
                   "{}\n{} Time={} step={} "
                   "Properties=species:S:1:pos:R:3:radius:R:1:id:I:1:velo:R:3:omega:R:3:tag:I:1:kinematic:I:1\n",
                   p.size(), cell(snapshot.domain), snapshot.time, snapshot.step);
    for (std::size_t i : order_by_id(p)) {
        const Vec3 &x = p.position[i], &v = p.velocity[i], &w = p.angular_velocity[i];
        fmt::format_to(fmt::appender(b), "{} {} {} {} {} {} {} {} {} {} {} {} {} {}\n",
                       species[static_cast<std::size_t>(p.material[i])], x.x, x.y, x.z, p.radius[i], p.id[i], v.x,
                       v.y, v.z, w.x, w.y, w.z, p.tag[i], p.is_kinematic(i) ? 1 : 0);
    }
    write_file_whole(file, {b.data(), b.size()});
}

}  // namespace tumble::io
