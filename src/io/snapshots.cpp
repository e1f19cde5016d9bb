// SPDX-License-Identifier: MIT
#include "io/snapshots.hpp"

#include <fmt/format.h>

#include "io/output.hpp"

namespace tumble::io {

namespace fs = std::filesystem;

SnapshotSeries::SnapshotSeries(const fs::path& directory)
    : directory_(directory), particles_(directory / "particles.pvd"), contacts_(directory / "contacts.pvd") {
    fs::create_directories(directory / "snapshots");
}

void SnapshotSeries::write(const Simulation& sim) {
    const int number = next_++;
    const std::string name = fmt::format("{:06d}", number);
    write_snapshot(directory_, number, sim);
    const fs::path particles = fs::path("snapshots") / (name + ".vtu");
    const fs::path contacts = fs::path("snapshots") / (name + ".vtp");
    write_vtu_snapshot(directory_ / particles, sim);
    write_vtp_contact_network(directory_ / contacts, sim);
    particles_.add(sim.time(), particles);
    contacts_.add(sim.time(), contacts);
}

}  // namespace tumble::io
