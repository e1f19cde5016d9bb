// SPDX-License-Identifier: MIT
// Axial bands of a two-species drum (docs/BAND-ANALYSIS.md): the
// composition along the axis sampled over the rotation, C(z, N) (the
// "kymograph" of band studies), and what is read from it: the bands, their
// number, edges, contrast and the species at the ends, the dominant
// wavelength, and the merging of bands over N. Frame as in drum_measure.hpp:
// drum axis = z, centre at the origin; the species counted is the grains of
// one tag (tag 1: material 2, the small grains, in the two-component mode).
//
// Segmentation of one sample (analyze_band_field, in this order):
//  1. phi0, the row's mean: phi per bin weighted by the bin's grain count.
//  2. A running mean of phi - phi0 over `smoothing` bins (truncated at end
//     caps, wrapped on a periodic axis; empty bins left out) decides only the
//     sign of each bin: runs are maximal stretches of one sign, their ends the
//     zero crossings of the smoothed deviation, interpolated between bin
//     centres (the first and last run reach the caps).
//  3. A run is significant when, from the raw phi of its bins, its mean
//     deviation d (grain-weighted) is large against the noise of a uniform
//     bed, |d| >= z * se, and |d| >= min_contrast, and it spans at least
//     min_width bins. Noise: a bed mixed at random puts each grain of the
//     bin in the counted species with the row's number fraction x0, so phi
//     has the variance c / n with c = phi0^2 (1 - phi0)^2 / (x0 (1 - x0))
//     (the binomial variance carried to the volume fraction; x0 = phi0 for
//     equal sizes), and a run of n grains se = sqrt(c / n).
//  4. Hysteresis in time: a run that overlaps a band of its sign in the
//     previous sample needs only z_leave and min_contrast_leave to stay; a
//     new one needs z_enter and min_contrast. A band whose amplitude hovers about
//     the entry threshold does not flicker.
//  5. Bands: consecutive significant runs of one sign join into one band;
//     insignificant runs between them belong to it; an edge between bands of
//     opposite sign lies midway between the end of the one's last significant
//     run and the start of the other's first. The end bands reach the caps.
//     On a periodic axis the first and last band join if of one sign.
//     Fewer than two bands is no banding: the count is 0.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "tumble/analysis/bootstrap.hpp"
#include "tumble/analysis/depth_mobility.hpp"
#include "tumble/particles/particle_store.hpp"

namespace tumble::analysis {

// Where and how a drum run samples the bands.
struct BandFrame {
    double inner_length = 0.12;  // m, the bed length L
    int bins = 30;               // axial bins (default_band_bins)
    int species_tag = 1;         // the species whose fraction phi is (tag 1: material 2, the small grains)
};

// The default axial bins of the band profile: L / 4 mm, at least 2 (4 mm:
// about half the large grains' diameter, 7.2 mm, and most of the small
// grains', 4.8 mm; the paper's radii are 3.6 and 2.4 mm).
int default_band_bins(double inner_length);

// One sample of the composition along the axis, per bin (NaN where a bin,
// or its core or periphery, holds no grains).
struct BandSample {
    std::vector<double> small_fraction;  // phi = V_species / V_all in the bin
    std::vector<double> grains;          // grains in the bin
    std::vector<double> small_grains;    // grains of the species in the bin
    // The radial core: in each bin the grains are ranked by their distance
    // in the cross-section from the bed's centre (bed_centre); the inner
    // third of the bin's grain volume is the core, the outer third the
    // periphery (the wall and the free surface); phi of each.
    std::vector<double> core_fraction, periphery_fraction;
};

// The centre of the bed's cross-section from which the radial core is
// measured: the volume-weighted centroid (x, y) of all free grains of the
// drum (z ignored). Why this point: a radial core of small grains forms
// around the bed's centre of circulation (Khakhar, McCarthy & Ottino 1997),
// the point about which the grains circulate, carried up in solid rotation
// and back down the flowing layer, not around the drum axis. A bed of
// fill f, its surface flat at the dynamic angle of repose, is a circular
// segment of half angle a (f = (2a - sin 2a) / 2 pi), symmetric about the
// line through the axis perpendicular to the free surface. On that line lie
// the centre of circulation, where the flowing layer meets the bed in solid
// rotation (the velocity changes sign there), R cos a + delta from the axis
// (delta the layer's depth), and the segment's centroid, at
// 4 R sin^3(a) / (3 (2a - sin 2a)). At the paper's fill of 0.3 (a = 71
// degrees) the surface is 0.32 R from the axis and the centroid 0.60 R, so
// the two points coincide when the layer is 0.28 R deep (11 mm in the 8 cm
// drum, two or three grains) and lie a grain apart otherwise; the axis is
// 0.6 R (24 mm, three large grains) from the centroid, and the grains
// nearest it are those of the free surface, the periphery of the flow
// (docs/BAND-ANALYSIS.md). The centroid needs no velocities and no surface fit.
// It is pooled over the whole drum, not taken per bin: the ~40 grains of a
// bin would place it only to about 2.5 mm (the bed's spread over
// sqrt(40)), half a small grain; the price is the bed's tilt within a grain
// diameter or two of an end cap. x, y in m; (0, 0) without free grains.
std::pair<double, double> bed_centre(const ParticleStore& p);
// The same of a particle snapshot's grains.
std::pair<double, double> bed_centre(const GrainFrame& f);

BandSample measure_bands(const ParticleStore& p, const BandFrame& frame);

// The radial core seen a second way (docs/BAND-ANALYSIS.md, "Radial
// shells"): the whole drum's grains of one snapshot ranked by their
// distance in the cross-section from the bed's centre (bed_centre; ties by
// id) and cut into `shells` shells of equal grain volume, a grain in the
// shell in which the middle of its volume falls, as the thirds of
// BandSample are cut per bin. Equal volumes, not equal widths: a shell then
// holds the same share of any bed, whatever its grains' size, so beds of
// other grains compare shell by shell (a null of grains of one size
// against the paper's two), and with 6 shells the
// inner two are the core and the outer two the periphery of a ranking over
// the whole drum rather than per axial bin. Sums per shell, so snapshots
// pool by adding (operator+=).
struct RadialShells {
    std::vector<double> volume;          // grain volume, m^3
    std::vector<double> species_volume;  // of the species counted, m^3
    std::vector<double> moment;          // sum of volume x distance from the centre, m^4
    std::vector<double> grains;          // grain count
    RadialShells& operator+=(const RadialShells& other);
    std::size_t size() const { return volume.size(); }
    double small_fraction(std::size_t shell) const;  // phi = V_species / V; NaN when empty
    double mean_radius(std::size_t shell) const;     // moment / V, the volume-weighted mean distance, m
    // phi of the inner third of the shells less phi of the outer third
    // (pooled by volume; the shell count a multiple of 3).
    double core_excess() const;
};
inline constexpr int radial_shell_count = 6;
// species_tag: the species counted (1: the small grains); shells >= 3, a
// multiple of 3. Empty shells when the frame has fewer grains than shells.
RadialShells radial_shells(const GrainFrame& f, int species_tag, int shells = radial_shell_count);

// The shells of snapshots taken at `revolutions` (in time order) pooled
// over the blocks of N that the radial core uses (difference_blocks: [0, 1),
// [1, 2), [2, 4), ...), a block only where it holds a snapshot.
struct ShellBlock {
    double from = 0.0, to = 0.0;  // revolutions, [from, to)
    std::size_t snapshots = 0;
    RadialShells shells;          // summed over the block's snapshots
};
std::vector<ShellBlock> radial_shell_blocks(const std::vector<double>& revolutions,
                                            const std::vector<RadialShells>& shells);

// C(z, N): the samples of a run, in time order.
struct BandField {
    double inner_length = 0.0;  // m
    bool periodic = false;      // periodic axis (no end caps)
    std::vector<double> revolutions;                 // N per sample
    std::vector<std::vector<double>> small_fraction; // [sample][bin], NaN: empty
    std::vector<std::vector<double>> grains;         // [sample][bin]
    std::vector<std::vector<double>> small_grains;   // [sample][bin]; empty: equal grain sizes (x0 = phi0)
    std::size_t bins() const { return small_fraction.empty() ? 0 : small_fraction.front().size(); }
    double bin_centre(std::size_t b) const;          // z, m
};

struct BandOptions {
    // A running mean over 3 bins (12 mm at the default bins, about 1.7 large
    // grain diameters) decides the sign of the deviation: one stray grain
    // does not split a band.
    int smoothing = 3;
    // Significance of a new band: a run's mean deviation at least 4 standard
    // errors of a random mix (a two-sided normal tail of 6e-5 per run); no
    // band in 4000 samples of a random mix of 30 or 160 bins
    // (tests/unit/test_bands.cpp), where z_enter = 3 gives 7 % at 160 bins.
    // 2 to stay.
    double z_enter = 4.0, z_leave = 2.0;
    // And at least 0.05 in volume fraction (0.025 to stay): in a long bed of
    // many grains a weak but certain modulation is not a band.
    double min_contrast = 0.05, min_contrast_leave = 0.025;
    int min_width = 2;  // bins: a band is at least about one large grain diameter wide (8 mm at the default bins)
};

// Throws tumble::Error unless smoothing and min_width >= 1, z_enter > 0,
// 0 <= z_leave <= z_enter, 0 <= min_contrast <= 1 and 0 <= min_contrast_leave
// <= min_contrast (all finite); the message names the setting by
// name(field), field as in BandOptions ("z_enter"): a command line passes
// its option's name.
void check_band_options(const BandOptions& options,
                        const std::function<std::string(const std::string& field)>& name =
                            [](const std::string& field) { return field; });

struct Band {
    bool rich = false;          // rich in the species counted (phi above phi0)
    double lo = 0.0, hi = 0.0;  // edges, m (lo > hi: the band wraps around a periodic axis)
    double centre = 0.0;        // m
    double small_fraction = 0.0;  // grain-weighted mean phi of its bins
    double grains = 0.0;        // grains in its bins
};

struct BandProfile {
    double revolutions = 0.0;
    double mean = 0.0;            // phi0
    std::vector<Band> bands;      // along z; empty: no banding (fewer than two bands)
    // Contrast: the grain-weighted mean |phi - phi0| over the bins (defined
    // without bands too), and between bands the mean phi of the rich bands
    // minus that of the poor ones (NaN without bands).
    double contrast = 0.0;
    double band_contrast = 0.0;
    // Spectrum of phi - phi0 (empty bins: 0): with end caps a cosine
    // transform (DCT-II, the mirror image of the bed at each cap: mode k has
    // wavelength 2 L / k), on a periodic axis the Fourier series (L / k);
    // the dominant mode and its share of the power (NaN for a flat row).
    std::vector<double> power;  // by mode k = 1, 2, ...
    double dominant_wavelength = 0.0;  // m
    double dominant_share = 0.0;
};

// Changes of the bands between two samples.
struct BandEvent {
    double revolutions = 0.0;  // N of the later sample
    // "merge": an inner band vanished and its two neighbours joined;
    // "end": an end band vanished, its neighbour reaching the cap;
    // "vanish": any other band gone; "appear": a band with no forerunner;
    // "onset": banding begins (from no bands); "dissolve": it ends.
    std::string kind;
    bool rich = false;  // of the band that vanished or appeared
    double z = 0.0;     // its centre, m (onset, dissolve: 0)
    std::size_t before = 0, after = 0;  // band counts
};

struct BandHistory {
    std::vector<BandProfile> samples;
    std::vector<BandEvent> events;
};

BandHistory analyze_band_field(const BandField& field, const BandOptions& options = {});

// When the band count left its start value for good: the revolution N of
// the first sample of the run of samples, reaching to the last one, whose
// counts all differ from the first sample's, if that run spans at least
// `hold` revolutions; NaN otherwise (hold <= 0 or not finite, fewer than two
// samples, the last sample back at the start's count, or a change younger
// than `hold`). A merge, an end band lost, bands dissolving or (from a mixed
// start) banding beginning all count. What `tumble drum --until-band-change
// HOLD` ends a run on (docs/BAND-ANALYSIS.md); the counts are those of
// analyze_band_field, whose hysteresis makes each sample's count depend on
// the earlier samples only, so the run sees the counts its analysis reports.
double band_count_changed(const BandHistory& history, double hold);

// Two quantities a and b sampled over the run (the radial core: phi_core
// and phi_periphery pooled over the bins; an end layer: phi next to a cap
// and the row's phi0), in blocks of revolutions doubling in length, [0, 1),
// [1, 2), [2, 4), [4, 8), ... (log N, as banding is read), the last ending
// past the last sample. The samples of each whole revolution are averaged
// first; difference = a - b is the mean of the block's revolution means,
// with the 95 % interval of a correlated series (series.hpp): revolution
// means are not independent when the quantity drifts or wanders over many
// revolutions, as the end layers do. NaN bounds when the block is worth
// fewer than 3 independent revolutions.
struct DifferenceBlock {
    double from = 0.0, to = 0.0;        // revolutions, [from, to)
    std::size_t revolutions = 0;        // whole revolutions with a finite sample
    double a = 0.0, b = 0.0, difference = 0.0;  // means of the revolution means
    double correlation = 1.0;           // integrated autocorrelation time of the differences, revolutions
    Interval interval;
};
std::vector<DifferenceBlock> difference_blocks(const std::vector<double>& revolutions, const std::vector<double>& a,
                                               const std::vector<double>& b);

// phi in the layer of `bins` bins next to each cap (grain-weighted; NaN
// where the layer holds no grains), and the row's phi0, per sample: the
// end layers, where end-wall friction segregates first in experiments.
struct EndLayers {
    std::vector<double> left, right, mean;
};
EndLayers end_layers(const BandField& field, std::size_t bins);

}  // namespace tumble::analysis
