// SPDX-License-Identifier: MIT
// The band files of a drum run directory (docs/BAND-ANALYSIS.md):
//   band_profile.csv    written during the rotation: per band sample (4 per
//                       revolution and the last), five rows, one per
//                       quantity, each with one column per axial bin
//                       (bin_0 at z = -L/2): small_fraction (phi), grains,
//                       small_grains, bed_core_fraction,
//                       bed_periphery_fraction (the radial core about the
//                       bed's centre; core_fraction and wall_fraction, about
//                       the drum axis, in files of a tumble before 2026-11-30)
//   bands.csv           per band sample: the band count, contrast,
//                       dominant wavelength, radial core, end bands
//   band_positions.csv  per band sample, one row per band: species, edges, phi
//   band_spectrum.csv   per band sample, the power of phi - phi0 per mode
//                       (column wavelength_k: mode k, of wavelength 2 L / k
//                       with end caps, L / k on a periodic axis)
//   bands.json          the thresholds, the final bands, the events (merges),
//                       also the "bands" section of summary.json
//   kymograph.png       C(z, N) as an image: z from -L/2 at the left, N from 0
//                       at the top, white at the run's mean phi, the colour
//                       of the species in excess elsewhere
// "small" is the species counted: component 1 (material-2, the small grains
// of the two-component mode; the right half's grains in the self mode).
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/drum_output.hpp"
#include "io/json.hpp"
#include "tumble/analysis/bands.hpp"

namespace tumble::io {

class BandProfileWriter {
public:
    // continuing: append to the file as it stands (a resumed run), no header.
    BandProfileWriter(const std::filesystem::path& directory, int bins, bool continuing = false);
    void write(double revolutions, const analysis::BandSample& sample);

private:
    std::filesystem::path path_;
    std::ofstream out_;
};

// band_profile.csv read back: the field C(z, N) with its grain counts, and
// the core and periphery fractions [sample][bin]. A sample whose radial
// rows were measured from the drum axis (core_fraction, wall_fraction: a
// tumble before 2026-11-30, or a run begun with it and resumed with a later
// one) has NaN core and periphery fractions: the two references differ
// (analysis::bed_centre), and are not mixed in one series.
struct BandRecord {
    analysis::BandField field;
    std::vector<std::vector<double>> core_fraction, periphery_fraction;
    std::size_t axis_samples = 0;  // samples measured from the drum axis
};
// growing: the file of a run going on, whose last sample may be half
// written: it is left out.
BandRecord read_band_profile(const std::filesystem::path& file, const DrumRunInfo& info, bool growing = false);

// The band analysis of a run directory: reads its band_profile.csv, writes
// bands.csv, band_positions.csv, band_spectrum.csv, bands.json and
// kymograph.png into `out` (the run directory itself, or its so_far/), adds
// its lines to `text` and its section to `summary`. A run without
// band_profile.csv (one from before it, info.band_bins == 0) gets a line
// saying so. frames: the particle snapshots of the rotation
// (read_rotation_frames), from which the small grains' crossing of the
// inner bands of large grains is counted (analysis/band_crossing.hpp);
// small_msd: the small grains' D from their MSD, to compare it with
// (nullptr: not compared).
// report: when its lines go into `text` (the files are written either way).
// bands.json and summary.json's "bands" say whether they did ("reported"),
// which tumble plot follows for the band figure.
enum class BandReport {
    always,       // tumble analyze --bands, --so-far
    when_banded,  // a run with bands: a banded start (bands, boundaries), a watch
                  // on the band count (--until-band-change), bands that formed
                  // in the bed (an onset), or more bands than at the start
};
void analyze_band_run(const std::filesystem::path& directory, const std::filesystem::path& out,
                      const DrumRunInfo& info, std::ostringstream& text, Json& summary,
                      const analysis::BandOptions& options, const std::vector<analysis::GrainFrame>& frames,
                      const analysis::MsdEstimate* small_msd, BandReport report = BandReport::always,
                      bool growing = false);

// The band analysis of the revolutions written so far, of a run stopped or
// still going on (a long band study looked at while it is stopped, or while
// it runs): the files of analyze_band_run and summary.txt in DIR/so_far/,
// the run's own files untouched (no summary.json: a sweep does not take the
// run for finished). running: another process is writing the run, so its
// newest snapshot and last band sample, perhaps half written, are left out.
// Returns the text.
std::string analyze_bands_so_far(const std::filesystem::path& directory, const analysis::BandOptions& options,
                                 bool running);

}  // namespace tumble::io
