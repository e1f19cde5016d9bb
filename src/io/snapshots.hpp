// SPDX-License-Identifier: MIT
// The particle snapshots of a run, numbered from 0, each written three ways:
//   snapshots/NNNNNN.csv   per-particle state as text (output.hpp)
//   snapshots/NNNNNN.vtu   the same for ParaView (vtk_output.hpp)
//   snapshots/NNNNNN.vtp   the contact network: a line per contact with its normal force
// and two ParaView time-series indexes in the run directory, particles.pvd
// and contacts.pvd (open them in ParaView: File > Open).
#pragma once

#include <filesystem>
#include <vector>

#include "io/vtk_output.hpp"
#include "tumble/sim/simulation.hpp"

namespace tumble::io {

class SnapshotSeries {
public:
    // earlier_times: the times of the snapshots a resumed run has already
    // written (their files are kept; the indexes are rewritten to list them).
    explicit SnapshotSeries(const std::filesystem::path& directory, const std::vector<double>& earlier_times = {});
    void write(const Simulation& sim);
    const std::vector<double>& times() const { return times_; }

private:
    void add_to_indexes(double time);

    std::filesystem::path directory_;
    PvdIndex particles_, contacts_;
    std::vector<double> times_;
};

}  // namespace tumble::io
