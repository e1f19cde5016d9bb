// SPDX-License-Identifier: MIT
#include "io/snapshots.hpp"

#include <fmt/format.h>

#include "io/output.hpp"

namespace tumble::io {

namespace fs = std::filesystem;

namespace {
fs::path dataset(std::size_t number, const char* extension) {
    return fs::path("snapshots") / fmt::format("{:06d}.{}", number, extension);
}
}  // namespace

SnapshotSeries::SnapshotSeries(const fs::path& directory, const std::vector<double>& earlier_times)
    : directory_(directory), particles_(directory / "particles.pvd"), contacts_(directory / "contacts.pvd") {
    fs::create_directories(directory / "snapshots");
    for (double time : earlier_times) add_to_indexes(time);
}

void SnapshotSeries::write(const Simulation& sim) {
    const std::size_t number = times_.size();
    write_snapshot(directory_, static_cast<int>(number), sim);
    write_vtu_snapshot(directory_ / dataset(number, "vtu"), sim);
    write_vtp_contact_network(directory_ / dataset(number, "vtp"), sim);
    add_to_indexes(sim.time());
}

void SnapshotSeries::add_to_indexes(double time) {
    const std::size_t number = times_.size();
    particles_.add(time, dataset(number, "vtu"));
    contacts_.add(time, dataset(number, "vtp"));
    times_.push_back(time);
}

}  // namespace tumble::io
