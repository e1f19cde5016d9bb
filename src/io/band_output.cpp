// SPDX-License-Identifier: MIT
#include "io/band_output.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "io/csv_table.hpp"
#include "io/output.hpp"
#include "io/png.hpp"
#include "io/render/scene.hpp"
#include "tumble/analysis/band_crossing.hpp"
#include "tumble/analysis/edge_broadening.hpp"
#include "tumble/core/error.hpp"

namespace tumble::io {

namespace fs = std::filesystem;

namespace {

// The rows of one band sample, in this order. The radial rows are named
// for their reference: bed_core_fraction and bed_periphery_fraction are
// ranked from the bed's centre (analysis::bed_centre); a tumble before
// 2026-11-30 wrote core_fraction and wall_fraction, ranked from the drum
// axis, in their place, which are read back as NaN (BandRecord).
constexpr std::array<const char*, 5> quantities{"small_fraction", "grains", "small_grains", "bed_core_fraction",
                                                "bed_periphery_fraction"};
constexpr std::array<const char*, 2> axis_quantities{"core_fraction", "wall_fraction"};

}  // namespace

BandProfileWriter::BandProfileWriter(const fs::path& directory, int bins, bool continuing)
    : path_(directory / "band_profile.csv"), out_(continuing ? open_for_appending(path_) : open_for_writing(path_)) {
    if (continuing) return;
    out_ << "revolutions,quantity";
    for (int b = 0; b < bins; ++b) out_ << ",bin_" << b;
    out_ << '\n';
    check_written(out_, path_);
}

void BandProfileWriter::write(double revolutions, const analysis::BandSample& s) {
    const std::array<const std::vector<double>*, quantities.size()> rows{
        &s.small_fraction, &s.grains, &s.small_grains, &s.core_fraction, &s.periphery_fraction};
    for (std::size_t q = 0; q < quantities.size(); ++q) {
        out_ << fmt::format("{},{}", revolutions, quantities[q]);
        // Four digits: the noise of a bin of tens of grains is in the second.
        for (double v : *rows[q]) out_ << fmt::format(",{:.4g}", v);
        out_ << '\n';
    }
    check_written(out_, path_);
}

BandRecord read_band_profile(const fs::path& file, const DrumRunInfo& info, bool growing) {
    CsvTable csv = read_csv_table(file, growing);
    if (growing) csv.rows.resize(csv.rows.size() - csv.rows.size() % quantities.size());  // whole samples
    const auto bins = static_cast<std::size_t>(info.band_bins);
    if (csv.header.size() != bins + 2)
        throw Error(file.string() + ": " + std::to_string(csv.header.size() - 2) + " bins, drum_run.toml says " +
                    std::to_string(bins));
    const std::vector<double> N = csv.numbers("revolutions");
    std::vector<std::vector<double>> columns;
    for (std::size_t b = 0; b < bins; ++b) columns.push_back(csv.numbers("bin_" + std::to_string(b)));
    const std::size_t quantity = csv.column("quantity");
    BandRecord r;
    r.field.inner_length = info.inner_length;
    r.field.periodic = info.periodic_axis;
    if (N.size() % quantities.size() != 0)
        throw Error(file.string() + ": " + std::to_string(N.size()) + " rows, not a multiple of " +
                    std::to_string(quantities.size()) + " (one per quantity and sample)");
    bool axis = false;  // this sample's radial rows are from the drum axis
    for (std::size_t row = 0; row < N.size(); ++row) {
        const std::size_t q = row % quantities.size();
        const std::string& name = csv.rows[row][quantity];
        if (q == 3) axis = name == axis_quantities[0];
        const bool known = name == quantities[q] || (q >= 3 && axis && name == axis_quantities[q - 3]);
        if (!known)
            throw Error(fmt::format("{}: row {}: quantity {} expected, found {}", file.string(), row + 2,
                                    q == 4 && axis ? axis_quantities[1] : quantities[q], name));
        std::vector<double> values(bins);
        for (std::size_t b = 0; b < bins; ++b) values[b] = axis && q >= 3 ? std::nan("") : columns[b][row];
        if (q == 0) r.field.revolutions.push_back(N[row]);
        if (q == 3) r.axis_samples += axis;
        auto& target = q == 0 ? r.field.small_fraction
                       : q == 1 ? r.field.grains
                       : q == 2 ? r.field.small_grains
                       : q == 3 ? r.core_fraction
                                : r.periphery_fraction;
        target.push_back(std::move(values));
    }
    return r;
}

namespace {

// Grain-weighted mean over the bins of a row (NaN where none).
double pooled(const std::vector<double>& value, const std::vector<double>& grains) {
    double sum = 0.0, n = 0.0;
    for (std::size_t b = 0; b < value.size(); ++b)
        if (std::isfinite(value[b])) sum += grains[b] * value[b], n += grains[b];
    return n > 0.0 ? sum / n : std::nan("");
}

// C(z, N) as an image: z from -L/2 at the left, N growing downward; white
// at `mean`, toward the colour of the species in excess (the palette's
// species 1 above, 0 below) in proportion to the excess, full at phi = 1 or
// 0; grey for an empty bin.
void write_kymograph(const fs::path& file, const analysis::BandField& f, double mean) {
    const int bins = static_cast<int>(f.bins()), samples = static_cast<int>(f.revolutions.size());
    // Wide and tall enough to read: at least 480 by 320 pixels.
    const int sx = std::max(1, (480 + bins - 1) / bins), sy = std::max(1, (320 + samples - 1) / samples);
    render::Image image(bins * sx, samples * sy, {128, 128, 128});
    const render::Rgb rich = render::grain_colour(1), poor = render::grain_colour(0);
    const auto blend = [](render::Rgb c, double t) {
        const auto mix = [t](std::uint8_t v) { return static_cast<std::uint8_t>(std::lround(255.0 + t * (v - 255.0))); };
        return render::Rgb{mix(c.r), mix(c.g), mix(c.b)};
    };
    for (int k = 0; k < samples; ++k)
        for (int b = 0; b < bins; ++b) {
            const double phi = f.small_fraction[k][b];
            if (!std::isfinite(phi)) continue;
            const render::Rgb c = phi >= mean ? blend(rich, mean < 1.0 ? (phi - mean) / (1.0 - mean) : 0.0)
                                              : blend(poor, mean > 0.0 ? (mean - phi) / mean : 0.0);
            for (int y = k * sy; y < (k + 1) * sy; ++y)
                for (int x = b * sx; x < (b + 1) * sx; ++x) image.set(x, y, c);
        }
    write_png(file, image);
}

// The blocks of analysis::difference_blocks as JSON, the two quantities and
// their difference under the given names.
Json difference_blocks_json(const std::vector<analysis::DifferenceBlock>& blocks, const char* a, const char* b,
                            const std::string& difference) {
    Json list = Json::array();
    for (const analysis::DifferenceBlock& block : blocks)
        list.push_back(Json{{"from", block.from},
                            {"to", block.to},
                            {"revolutions", static_cast<std::int64_t>(block.revolutions)},
                            {a, block.a},
                            {b, block.b},
                            {difference, block.difference},
                            {difference + "_lo", block.interval.lo},
                            {difference + "_hi", block.interval.hi},
                            {"correlation_revolutions", block.correlation}});
    return list;
}

// bands.json's "radial_core": the reference and the blocks.
Json radial_core_json(const std::vector<double>& revolutions, const std::vector<double>& core,
                      const std::vector<double>& periphery, std::size_t axis_samples) {
    return Json{{"reference", "bed centroid"},
                {"axis_samples", static_cast<std::int64_t>(axis_samples)},
                {"blocks", difference_blocks_json(analysis::difference_blocks(revolutions, core, periphery),
                                                  "core_fraction", "periphery_fraction", "core_excess")}};
}

// The layers next to the caps: 2 cm (five bins of the default 4 mm; at
// least one bin), phi there against the row's phi0, in blocks of N.
constexpr double end_layer_width = 0.02;  // m

Json end_layers_json(const analysis::BandField& field, std::size_t bins, double width) {
    const analysis::EndLayers layers = analysis::end_layers(field, bins);
    return Json{{"width", width},
                {"bins", static_cast<std::int64_t>(bins)},
                {"left", difference_blocks_json(analysis::difference_blocks(field.revolutions, layers.left, layers.mean),
                                                "layer_fraction", "mean_fraction", "excess")},
                {"right", difference_blocks_json(analysis::difference_blocks(field.revolutions, layers.right, layers.mean),
                                                 "layer_fraction", "mean_fraction", "excess")}};
}

// The small grains' crossing of the inner bands of large grains (bands
// poor in the species counted with a band on each side), from the particle
// snapshots of the rotation: at each snapshot the bands of the nearest band
// sample; blocks of a tenth of the rotation (at least a frame spacing).
analysis::CrossingEstimate crossing_of_run(const analysis::BandHistory& h, const analysis::BandField& field,
                                           const std::vector<analysis::GrainFrame>& frames) {
    analysis::CrossingEstimate e;
    if (field.periodic) e.note = "a periodic axis: a band's two sides are one";
    else if (frames.size() < 2 || h.samples.empty()) e.note = "fewer than two particle snapshots of the rotation";
    if (!e.note.empty()) return e;
    std::vector<std::vector<analysis::BandSpan>> spans;
    bool any = false;
    for (const analysis::GrainFrame& f : frames) {
        const auto nearest = std::min_element(h.samples.begin(), h.samples.end(), [&](const auto& a, const auto& b) {
            return std::abs(a.revolutions - f.revolutions) < std::abs(b.revolutions - f.revolutions);
        });
        spans.emplace_back();
        for (std::size_t i = 1; i + 1 < nearest->bands.size(); ++i)
            if (!nearest->bands[i].rich) spans.back().push_back({nearest->bands[i].lo, nearest->bands[i].hi});
        any = any || !spans.back().empty();
    }
    if (!any) {
        e.note = "no band of the other species between two bands of this one at any snapshot";
        return e;
    }
    try {
        const analysis::AxialTracks tracks = analysis::axial_tracks(frames, 1);  // tag 1: the species of the band field
        const double spacing = frames[1].revolutions - frames[0].revolutions;
        const double span = frames.back().revolutions - frames.front().revolutions;
        return analysis::band_crossing_diffusion(tracks, spans, std::max(spacing, span / 10.0));
    } catch (const Error& error) {  // snapshots unequally spaced: the count needs equal intervals
        e.note = error.what();
        return e;
    }
}

// bands.json's "crossing": the estimate, what it rests on, and the MSD's D
// of the same grains with the ratio (when given).
Json crossing_json(const analysis::CrossingEstimate& e, const analysis::MsdEstimate* msd) {
    Json j = estimate_json(e.D, e.interval, e.determined, e.note);
    j["D_uncorrected"] = e.D_uncorrected;
    j["crossings"] = e.crossings;
    j["rate"] = e.rate;
    j["band_density"] = e.band_density;
    j["width"] = e.width;
    j["band_revolutions"] = e.revolutions;
    j["blocks"] = static_cast<std::int64_t>(e.blocks);
    if (msd) {
        j["msd"] = msd_json(*msd);
        j["ratio_to_msd"] = e.D / msd->D;
    }
    return j;
}

std::string describe_crossing(const analysis::CrossingEstimate& e, const analysis::MsdEstimate* msd,
                              const std::string& small, const std::string& large) {
    if (!(e.revolutions > 0.0))
        return fmt::format("crossing of the {} bands by {}: not measured ({})", large, small, e.note);
    std::string s = fmt::format(
        "crossing of the inner {} bands by {}: {:.1f} crossings in {:.4g} band-revolutions ({:.3g} per revolution; "
        "{:.3g} grains per m inside, {:.3g} m wide): D_eff = {:.3e} m^2/rev, 95 % interval [{:.3e}, {:.3e}]",
        large, small, e.crossings, e.revolutions, e.rate, e.band_density, e.width, e.D, e.interval.lo, e.interval.hi);
    if (!e.determined) s += " (not determined: " + e.note + ")";
    if (msd && std::isfinite(msd->D))
        s += fmt::format("; the MSD's D of {} {:.3e} m^2/rev (ratio {:.2f})", small, msd->D, e.D / msd->D);
    return s;
}

// bands.json's "edges": the blur of the start's boundaries
// (analysis/edge_broadening.hpp), per level of the normalised composition,
// with the MSD's D of the small grains.
Json edges_json(const analysis::EdgeDiffusion& e, const analysis::MsdEstimate* msd) {
    Json levels = Json::array(), boundaries = Json::array();
    for (std::size_t l = 0; l < analysis::edge_levels.size(); ++l) {
        Json level = estimate_json(e.D[l], e.interval[l], e.determined, e.note);
        level["u"] = analysis::edge_levels[l];
        if (msd) level["ratio_to_msd"] = e.D[l] / msd->D;
        levels.push_back(level);
    }
    for (std::size_t b = 0; b < e.boundaries.size(); ++b)
        boundaries.push_back(Json{{"z", e.boundaries[b]},
                                  {"species_side", e.species_left[b] ? "left" : "right"},
                                  {"D", e.boundary_D[b]}});
    Json j{{"method", "Boltzmann-Matano"},
           {"block_revolutions", analysis::edge_block_revolutions},
           {"boundaries", boundaries},
           {"levels", levels},
           {"determined", e.determined},
           {"note", e.note}};
    if (msd) j["msd"] = msd_json(*msd);
    return j;
}

std::string describe_edges(const analysis::EdgeDiffusion& e, const analysis::MsdEstimate* msd,
                           const std::string& small, const std::string& large) {
    if (e.boundaries.empty()) return "blur of the start's boundaries: not measured (" + e.note + ")";
    std::string s = fmt::format("blur of the start's {} {} (Boltzmann-Matano; band_edges.csv), D in m^2/rev at u "
                                "= {} (among {}), {}, {} (among {}):",
                                e.boundaries.size(), e.boundaries.size() == 1 ? "boundary" : "boundaries",
                                analysis::edge_levels[0], large, analysis::edge_levels[1],
                                analysis::edge_levels[2], small);
    if (std::none_of(e.D.begin(), e.D.end(), [](double D) { return std::isfinite(D); }))
        return s + " not measured (" + e.note + ")";
    for (std::size_t l = 0; l < analysis::edge_levels.size(); ++l) {
        s += std::isfinite(e.D[l]) ? fmt::format(" {:.3e}", e.D[l]) : std::string(" none");
        if (e.determined) s += fmt::format(" [{:.3e}, {:.3e}]", e.interval[l].lo, e.interval[l].hi);
    }
    if (!e.determined) s += " (no interval: " + e.note + ")";
    if (msd && std::isfinite(msd->D)) s += fmt::format("; the MSD's D of {} {:.3e} m^2/rev", small, msd->D);
    return s;
}

// band_edges.csv: per boundary of the start and block of revolutions, the
// Matano plane and D at each level.
void write_edge_blocks(const fs::path& file, const analysis::EdgeDiffusion& e) {
    std::ostringstream out;
    out << "boundary,z_start,revolutions,matano";
    for (double u : analysis::edge_levels) out << ",D_u" << std::lround(100.0 * u);  // D_u25: numpy keeps no '.' in a name
    out << '\n';
    for (const analysis::EdgeBlock& b : e.blocks)
        out << fmt::format("{},{},{},{},{}\n", b.boundary, e.boundaries[b.boundary], b.revolutions, b.matano,
                           fmt::join(b.D, ","));
    write_file_whole(file, out.str());
}

// The radial shells of each snapshot (analysis::radial_shells): radial_shells.csv,
// one row per snapshot and shell: revolutions, shell (0 innermost), radius
// (the shell's volume-weighted mean distance from the bed's centre, m),
// grains, small_fraction (phi).
void write_radial_shells(const fs::path& file, const std::vector<analysis::GrainFrame>& frames,
                         const std::vector<analysis::RadialShells>& shells) {
    std::ostringstream out;
    out << "revolutions,shell,radius,grains,small_fraction\n";
    for (std::size_t k = 0; k < shells.size(); ++k)
        for (std::size_t s = 0; s < shells[k].size(); ++s)
            out << fmt::format("{},{},{:.5g},{},{:.5g}\n", frames[k].revolutions, s, shells[k].mean_radius(s),
                               shells[k].grains[s], shells[k].small_fraction(s));
    write_file_whole(file, out.str());
}

// bands.json's "radial_shells": the shells pooled over the blocks of N.
Json radial_shells_json(const std::vector<analysis::GrainFrame>& frames,
                        const std::vector<analysis::RadialShells>& shells) {
    std::vector<double> revolutions;
    for (const analysis::GrainFrame& f : frames) revolutions.push_back(f.revolutions);
    Json blocks = Json::array();
    for (const analysis::ShellBlock& b : analysis::radial_shell_blocks(revolutions, shells)) {
        Json phi = Json::array(), radius = Json::array(), grains = Json::array();
        for (std::size_t s = 0; s < b.shells.size(); ++s) {
            phi.push_back(b.shells.small_fraction(s));
            radius.push_back(b.shells.mean_radius(s));
            grains.push_back(b.shells.grains[s] / static_cast<double>(b.snapshots));
        }
        blocks.push_back(Json{{"from", b.from},
                              {"to", b.to},
                              {"snapshots", static_cast<std::int64_t>(b.snapshots)},
                              {"small_fraction", phi},
                              {"radius", radius},
                              {"grains", grains},
                              {"core_excess", b.shells.core_excess()}});
    }
    return Json{{"reference", "bed centroid"},
                {"shells", analysis::radial_shell_count},
                {"snapshots", static_cast<std::int64_t>(frames.size())},
                {"blocks", blocks}};
}

Json band_json(const analysis::Band& b, const std::string& rich, const std::string& poor) {
    return Json{{"species", b.rich ? rich : poor}, {"rich", b.rich},       {"lo", b.lo},
                {"hi", b.hi},                      {"centre", b.centre},   {"small_fraction", b.small_fraction}};
}

}  // namespace

void analyze_band_run(const fs::path& dir, const fs::path& out, const DrumRunInfo& info, std::ostringstream& text,
                      Json& summary, const analysis::BandOptions& options,
                      const std::vector<analysis::GrainFrame>& frames, const analysis::MsdEstimate* small_msd,
                      BandReport report, bool growing) {
    if (info.band_bins <= 0 || !fs::exists(dir / "band_profile.csv")) {
        if (report == BandReport::always)
            text << "  bands: not measured (no band_profile.csv: a run of tumble before the band analysis)\n";
        return;
    }
    const BandRecord record = read_band_profile(dir / "band_profile.csv", info, growing);
    const analysis::BandField& field = record.field;
    const analysis::BandHistory h = analysis::analyze_band_field(field, options);
    const std::string small = info.components.size() > 1 ? info.components[1].name : "species 1";
    const std::string large = info.components.front().name;
    const std::size_t samples = h.samples.size();

    // bands.csv and band_positions.csv.
    std::ostringstream series, positions, spectrum;
    series << "revolutions,bands,rich_bands,mean,contrast,band_contrast,dominant_wavelength,dominant_share,"
              "core_fraction,periphery_fraction,core_excess,left_end_rich,left_end_fraction,right_end_rich,"
              "right_end_fraction\n";
    positions << "revolutions,band,rich,lo,hi,centre,small_fraction,grains\n";
    spectrum << "revolutions";
    const std::size_t modes = samples ? h.samples.front().power.size() : 0;
    for (std::size_t m = 1; m <= modes; ++m) spectrum << ",wavelength_" << m;
    spectrum << '\n';
    std::vector<double> core(samples), periphery(samples);
    for (std::size_t k = 0; k < samples; ++k) {
        const analysis::BandProfile& p = h.samples[k];
        core[k] = pooled(record.core_fraction[k], field.grains[k]);
        periphery[k] = pooled(record.periphery_fraction[k], field.grains[k]);
        const std::size_t rich =
            static_cast<std::size_t>(std::count_if(p.bands.begin(), p.bands.end(), [](const auto& b) { return b.rich; }));
        const double nan = std::nan("");
        const auto end = [&](bool right) {
            if (p.bands.empty() || field.periodic) return std::pair{nan, nan};  // a ring has no ends
            const analysis::Band& b = right ? p.bands.back() : p.bands.front();
            return std::pair{b.rich ? 1.0 : 0.0, b.small_fraction};
        };
        series << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", p.revolutions, p.bands.size(), rich,
                              p.mean, p.contrast, p.band_contrast, p.dominant_wavelength, p.dominant_share, core[k],
                              periphery[k], core[k] - periphery[k], end(false).first, end(false).second, end(true).first,
                              end(true).second);
        spectrum << fmt::format("{}", p.revolutions);
        for (double power : p.power) spectrum << fmt::format(",{:.4g}", power);
        spectrum << '\n';
        for (std::size_t i = 0; i < p.bands.size(); ++i) {
            const analysis::Band& b = p.bands[i];
            positions << fmt::format("{},{},{},{},{},{},{},{}\n", p.revolutions, i, b.rich ? 1 : 0, b.lo, b.hi,
                                     b.centre, b.small_fraction, b.grains);
        }
    }
    write_file_whole(out / "bands.csv", series.str());
    write_file_whole(out / "band_positions.csv", positions.str());
    write_file_whole(out / "band_spectrum.csv", spectrum.str());

    double mean = 0.0, total = 0.0;
    for (std::size_t k = 0; k < samples; ++k)
        for (std::size_t b = 0; b < field.bins(); ++b)
            if (std::isfinite(field.small_fraction[k][b]))
                mean += field.grains[k][b] * field.small_fraction[k][b], total += field.grains[k][b];
    if (samples > 0) write_kymograph(out / "kymograph.png", field, total > 0.0 ? mean / total : 0.5);

    const auto layer_bins = static_cast<std::size_t>(
        std::max(1L, std::lround(end_layer_width / (info.inner_length / info.band_bins))));
    const double layer_width = static_cast<double>(layer_bins) * info.inner_length / info.band_bins;

    // bands.json: the thresholds, the counts, the last sample's bands and the events.
    std::size_t most = 0;
    double onset = std::nan("");
    for (const analysis::BandProfile& p : h.samples) most = std::max(most, p.bands.size());
    for (const analysis::BandEvent& e : h.events)
        if (e.kind == "onset" && !std::isfinite(onset)) onset = e.revolutions;
    const analysis::CrossingEstimate crossing = crossing_of_run(h, field, frames);
    const analysis::EdgeDiffusion edges = analysis::edge_diffusion(field, info.band_edges);
    if (!edges.boundaries.empty()) write_edge_blocks(out / "band_edges.csv", edges);
    std::vector<analysis::RadialShells> shells;
    for (const analysis::GrainFrame& f : frames) shells.push_back(analysis::radial_shells(f, 1));  // tag 1: as the field
    if (!shells.empty()) write_radial_shells(out / "radial_shells.csv", frames, shells);
    Json events = Json::array();
    std::size_t merges = 0;
    for (const analysis::BandEvent& e : h.events) {
        merges += e.kind == "merge";
        events.push_back(Json{{"revolutions", e.revolutions}, {"kind", e.kind}, {"species", e.rich ? small : large},
                              {"z", e.z}, {"before", static_cast<std::int64_t>(e.before)},
                              {"after", static_cast<std::int64_t>(e.after)}});
    }
    // Whether the band lines go into the text: see BandReport.
    const std::size_t at_start = samples ? h.samples.front().bands.size() : 0;
    const bool banded = info.arrangement == "bands" || info.arrangement == "boundaries" ||
                        info.until_band_change > 0.0 || std::isfinite(onset) || most > at_start;
    const bool reported = report == BandReport::always || banded;
    Json bands{{"species", small},
               {"reported", reported},
               {"other", large},
               {"bins", info.band_bins},
               {"bin_width", info.inner_length / info.band_bins},
               {"samples", static_cast<std::int64_t>(samples)},
               {"thresholds", Json{{"smoothing_bins", options.smoothing},
                                   {"z_enter", options.z_enter},
                                   {"z_leave", options.z_leave},
                                   {"min_contrast", options.min_contrast},
                                   {"min_contrast_leave", options.min_contrast_leave},
                                   {"min_width_bins", options.min_width}}},
               {"spectrum", Json{{"transform", info.periodic_axis ? "fourier" : "cosine"},
                                 {"wavelengths", [&] {
                                      Json w = Json::array();
                                      for (std::size_t m = 1; m <= modes; ++m)
                                          w.push_back((info.periodic_axis ? 1.0 : 2.0) * info.inner_length /
                                                      static_cast<double>(m));
                                      return w;
                                  }()}}},
               {"radial_core", radial_core_json(field.revolutions, core, periphery, record.axis_samples)},
               {"radial_shells", shells.empty() ? Json(nullptr) : radial_shells_json(frames, shells)},
               {"end_layers", field.periodic ? Json(nullptr) : end_layers_json(field, layer_bins, layer_width)},
               {"crossing", crossing_json(crossing, small_msd)},
               {"edges", edges_json(edges, small_msd)},
               {"max_bands", static_cast<std::int64_t>(most)},
               {"onset_revolution", onset},
               {"merges", static_cast<std::int64_t>(merges)},
               {"events", events}};
    if (samples > 0) {
        const analysis::BandProfile& last = h.samples.back();
        Json list = Json::array();
        for (const analysis::Band& b : last.bands) list.push_back(band_json(b, small, large));
        Json ends = nullptr;
        if (!last.bands.empty() && !field.periodic)
            ends = Json{{"left", band_json(last.bands.front(), small, large)},
                        {"right", band_json(last.bands.back(), small, large)}};
        bands["final"] = Json{{"revolutions", last.revolutions},
                              {"bands", static_cast<std::int64_t>(last.bands.size())},
                              {"contrast", last.contrast},
                              {"band_contrast", last.band_contrast},
                              {"dominant_wavelength", last.dominant_wavelength},
                              {"dominant_share", last.dominant_share},
                              {"core_fraction", core.back()},
                              {"periphery_fraction", periphery.back()},
                              {"list", list},
                              {"ends", ends}};
        bands["initial"] = Json{{"revolutions", h.samples.front().revolutions},
                                {"bands", static_cast<std::int64_t>(h.samples.front().bands.size())},
                                {"contrast", h.samples.front().contrast},
                                {"core_fraction", core.front()},
                                {"periphery_fraction", periphery.front()}};
    }
    write_json_file(out / "bands.json", bands);
    summary["bands"] = bands;

    std::ostringstream lines;
    lines << fmt::format("  bands of {} (fraction phi by volume in {} bins of {:.3g} mm, {} samples; band_profile.csv, "
                        "bands.csv, bands.json, kymograph.png):\n",
                        small, info.band_bins, 1e3 * info.inner_length / info.band_bins, samples);
    if (samples > 0) {
        const analysis::BandProfile& first = h.samples.front();
        const analysis::BandProfile& last = h.samples.back();
        const auto describe = [&](const analysis::BandProfile& p) {
            if (p.bands.empty())
                return fmt::format("no bands (contrast, mean |phi - phi0|, {:.3f})", p.contrast);
            std::string s = fmt::format("{} bands (", p.bands.size());
            for (std::size_t i = 0; i < p.bands.size(); ++i) {
                if (i) s += ' ';
                s += p.bands[i].rich ? 'S' : 'L';
            }
            s += fmt::format("; S: rich in {}), band contrast {:.3f}", small, p.band_contrast);
            if (field.periodic) return s + " (periodic axis: no end bands)";
            return s + fmt::format(", ends {} {:.2f} / {} {:.2f}", p.bands.front().rich ? small : large,
                                   p.bands.front().small_fraction, p.bands.back().rich ? small : large,
                                   p.bands.back().small_fraction);
        };
        lines << fmt::format("    N = {:.3g}: {}\n    N = {:.3g}: {}; dominant wavelength {:.3g} m ({:.0f} % of the "
                            "power)\n",
                            first.revolutions, describe(first), last.revolutions, describe(last),
                            last.dominant_wavelength, 100.0 * last.dominant_share);
        if (most == 0)
            lines << fmt::format("    no bands at any sample (a band needs a mean deviation of {:.3g} standard errors of a "
                                "random mix and {:.3g} in phi)\n",
                                options.z_enter, options.min_contrast);
        else
            lines << fmt::format("    at most {} bands; {} events ({} merges; bands.json){}\n", most, h.events.size(), merges,
                                std::isfinite(onset) ? fmt::format("; bands appear in the mixed bed at N = {:.3g}", onset)
                                                     : std::string());
        lines << fmt::format("    radial core (phi in the inner and outer third about the bed's centre): {:.3f}, {:.3f} "
                            "at N = {:.3g} ({:.3f}, {:.3f} at N = {:.3g})\n",
                            core.back(), periphery.back(), last.revolutions, core.front(), periphery.front(),
                            first.revolutions);
        if (!shells.empty()) {
            std::vector<double> phi;  // the last snapshot's, innermost first
            for (std::size_t s = 0; s < shells.back().size(); ++s) phi.push_back(shells.back().small_fraction(s));
            lines << fmt::format("    radial shells ({} of equal grain volume about the bed's centre, {} particle "
                                "snapshots; radial_shells.csv): phi from the innermost out {:.3f} at N = {:.3g}, inner "
                                "third less outer third {:+.3f}\n",
                                analysis::radial_shell_count, shells.size(), fmt::join(phi, " "),
                                frames.back().revolutions, shells.back().core_excess());
        }
        if (record.axis_samples > 0)
            lines << fmt::format("    radial core: {} of the {} samples of band_profile.csv were measured from the drum "
                                "axis by an earlier tumble (rows core_fraction, wall_fraction) and are left out "
                                "(NaN)\n",
                                record.axis_samples, samples);
        if (!field.periodic) {  // the layers next to the caps, over the last block of N
            const analysis::EndLayers layers = analysis::end_layers(field, layer_bins);
            const auto left = analysis::difference_blocks(field.revolutions, layers.left, layers.mean);
            const auto right = analysis::difference_blocks(field.revolutions, layers.right, layers.mean);
            // A block worth fewer than 3 independent revolutions has no interval (NaN bounds).
            auto with_interval = [](const analysis::DifferenceBlock& b) {
                return std::isfinite(b.interval.lo) && std::isfinite(b.interval.hi)
                           ? fmt::format("{:+.3f} [{:+.3f}, {:+.3f}]", b.difference, b.interval.lo, b.interval.hi)
                           : fmt::format("{:+.3f} (no interval: fewer than 3 independent revolutions)", b.difference);
            };
            if (!left.empty() && !right.empty())
                lines << fmt::format("    end layers ({:.3g} cm at each cap), phi - phi0 over N = {:.3g} to {:.3g}: left "
                                    "{}, right {} (95 %, revolution means correlated over {:.2g} and {:.2g} revolutions; "
                                    "bands.json end_layers)\n",
                                    100.0 * layer_width, left.back().from, last.revolutions, with_interval(left.back()),
                                    with_interval(right.back()), left.back().correlation, right.back().correlation);
        }
        lines << "    " << describe_crossing(crossing, small_msd, small, large) << "\n";
        lines << "    " << describe_edges(edges, small_msd, small, large) << "\n";
    }
    if (reported) text << lines.str();
}


std::string analyze_bands_so_far(const fs::path& dir, const analysis::BandOptions& options, bool running) {
    const DrumRunInfo info = read_drum_run_info(dir / "drum_run.toml");
    const fs::path out = dir / "so_far";
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec) throw Error(out.string() + ": cannot create the folder: " + ec.message());
    std::ostringstream text;
    text << "tumble analyze --so-far " << dir.string() << ": the bands of the revolutions written so far, into "
         << out.string() << "\n";
    if (running)
        text << "  the run is going on: its newest snapshot and band sample, perhaps half written, are left out\n";
    Json summary = Json::object();
    std::vector<analysis::GrainFrame> frames = read_rotation_frames(dir, info, running ? 1 : 0);
    const SnapshotCoverage coverage = snapshot_coverage(frames);
    text << coverage.describe();
    summary["snapshots"] = coverage.json();
    analyze_band_run(dir, out, info, text, summary, options, frames, nullptr, BandReport::always, running);
    write_file_atomically(out / "summary.txt", text.str());
    return text.str();
}

}  // namespace tumble::io
