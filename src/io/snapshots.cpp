// SPDX-License-Identifier: MIT
#include "io/snapshots.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>

#include <fmt/format.h>

#include "io/csv_table.hpp"
#include "io/output.hpp"
#include "io/vtk_input.hpp"
#include "io/xyz_output.hpp"
#include "tumble/core/mpi.hpp"

namespace tumble::io {

namespace fs = std::filesystem;

namespace {
fs::path dataset(std::size_t number, const char* extension) {
    return fs::path("snapshots") / fmt::format("{:06d}.{}", number, extension);
}
fs::path walls_dataset(std::size_t number) { return fs::path("snapshots") / fmt::format("{:06d}_walls.vtp", number); }
}  // namespace

SnapshotSeries::SnapshotSeries(const fs::path& directory, const std::vector<double>& earlier_times, bool walls)
    : directory_(directory) {
    if (mpi::rank() == 0) {  // shared among ranks, rank 0 writes the snapshots
        particles_.emplace(directory / "particles.pvd");
        contacts_.emplace(directory / "contacts.pvd");
        if (walls) walls_.emplace(directory / "walls.pvd");
        fs::create_directories(directory / "snapshots");
    }
    for (double time : earlier_times) add_to_indexes(time);
}

void SnapshotSeries::write(const Simulation& sim) {
    const std::size_t number = times_.size();
    const SnapshotData snapshot = snapshot_of(sim);  // collective when shared among ranks
    if (particles_) {
        write_snapshot(directory_, static_cast<int>(number), snapshot);
        write_vtu_snapshot(directory_ / dataset(number, "vtu"), snapshot);
        write_xyz_snapshot(directory_ / dataset(number, "xyz"), snapshot);
        write_vtp_contact_network(directory_ / dataset(number, "vtp"), snapshot);
        if (walls_) write_vtp_walls(directory_ / walls_dataset(number), snapshot);
    }
    add_to_indexes(sim.time());
}

void SnapshotSeries::add_to_indexes(double time) {
    const std::size_t number = times_.size();
    if (particles_) particles_->add(time, dataset(number, "vtu"));
    if (contacts_) contacts_->add(time, dataset(number, "vtp"));
    if (walls_) walls_->add(time, walls_dataset(number));
    times_.push_back(time);
}

std::optional<double> snapshot_time(const CsvTable& csv) {
    if (std::find(csv.header.begin(), csv.header.end(), "time") != csv.header.end() && !csv.rows.empty())
        return csv.numbers("time").front();
    std::ifstream in(csv.file);
    std::string first;
    std::getline(in, first);
    const std::string prefix = "# time = ";
    if (!first.starts_with(prefix)) return std::nullopt;
    char* end = nullptr;
    const double t = std::strtod(first.c_str() + prefix.size(), &end);
    if (end == first.c_str() + prefix.size() || !std::isfinite(t)) return std::nullopt;
    return t;
}

SnapshotParticles read_snapshot_csv(const fs::path& file) {
    const CsvTable csv = read_csv_table(file);
    const std::vector<double> x = csv.numbers("x"), y = csv.numbers("y"), z = csv.numbers("z"),
                              radius = csv.numbers("radius"), tag = csv.numbers("tag"),
                              kinematic = csv.numbers("kinematic");
    const std::size_t material = csv.column("material");
    SnapshotParticles p;
    p.radius = radius;
    p.time = snapshot_time(csv);
    for (std::size_t i = 0; i < csv.rows.size(); ++i) {
        p.position.push_back({x[i], y[i], z[i]});
        p.tag.push_back(static_cast<std::int32_t>(tag[i]));
        p.kinematic.push_back(kinematic[i] != 0.0 ? 1 : 0);
        const std::string& name = csv.rows[i][material];
        const auto known = std::find(p.material_names.begin(), p.material_names.end(), name);
        p.material.push_back(static_cast<std::int32_t>(known - p.material_names.begin()));
        if (known == p.material_names.end()) p.material_names.push_back(name);
    }
    return p;
}

WallSurface read_snapshot_walls(const fs::path& csv_file) {
    fs::path vtp = csv_file;
    vtp.replace_filename(csv_file.stem().string() + "_walls.vtp");
    std::error_code ec;
    if (!fs::exists(vtp, ec)) return {};
    return read_vtp_walls(vtp);
}

std::vector<fs::path> list_snapshot_csv(const fs::path& directory) {
    std::vector<fs::path> files;
    std::error_code ec;
    for (const fs::directory_entry& entry : fs::directory_iterator(directory / "snapshots", ec)) {
        const std::string stem = entry.path().stem().string();
        if (entry.path().extension() == ".csv" && !stem.empty() &&
            std::all_of(stem.begin(), stem.end(), [](unsigned char c) { return std::isdigit(c); }))
            files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
        return std::stoull(a.stem().string()) < std::stoull(b.stem().string());
    });
    return files;
}

}  // namespace tumble::io
