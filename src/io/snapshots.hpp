// SPDX-License-Identifier: MIT
// The particle snapshots of a run, numbered from 0, each written three ways:
//   snapshots/NNNNNN.csv   per-particle state as text (output.hpp)
//   snapshots/NNNNNN.vtu   the same for ParaView (vtk_output.hpp)
//   snapshots/NNNNNN.vtp   the contact network: a line per contact with its normal force
// and two ParaView time-series indexes in the run directory, particles.pvd
// and contacts.pvd (open them in ParaView: File > Open).
#pragma once

#include <filesystem>

#include "io/vtk_output.hpp"
#include "tumble/sim/simulation.hpp"

namespace tumble::io {

class SnapshotSeries {
public:
    explicit SnapshotSeries(const std::filesystem::path& directory);
    void write(const Simulation& sim);

private:
    std::filesystem::path directory_;
    PvdIndex particles_, contacts_;
    int next_ = 0;
};

}  // namespace tumble::io
