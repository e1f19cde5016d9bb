// SPDX-License-Identifier: MIT
#include "io/drum_output.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "io/band_output.hpp"
#include "io/csv_table.hpp"
#include "io/json.hpp"
#include "io/output.hpp"
#include "io/snapshots.hpp"
#include "io/toml_reader.hpp"
#include "tumble/analysis/bed_structure.hpp"
#include "tumble/analysis/hogg.hpp"
#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"
#include "tumble/setup/paper_materials.hpp"

namespace tumble::io {

namespace fs = std::filesystem;

std::string drum_run_info_text(const DrumRunInfo& info) {
    toml::array components;
    for (const DrumComponent& c : info.components)
        components.push_back(toml::table{{"name", c.name},
                                         {"grains", static_cast<std::int64_t>(c.grains)},
                                         {"mass", c.mass},
                                         {"start_side", c.start_side}});
    toml::array edges;
    for (double z : info.band_edges) edges.push_back(z);
    toml::array materials;
    for (const Material& m : info.materials)
        materials.push_back(toml::table{{"name", m.name},
                                        {"E", m.E},
                                        {"G", m.G},
                                        {"nu", m.nu},
                                        {"xi", m.xi},
                                        {"eta", m.eta},
                                        {"rho", m.rho},
                                        {"radius", m.radius}});
    toml::table t{{"mode", info.mode},
                        {"omega", info.omega},
                        {"froude", info.froude},
                        {"revolutions", info.revolutions},
                        {"seed", static_cast<std::int64_t>(info.seed)},
                        {"wall_particles", static_cast<std::int64_t>(info.wall_particles)},
                        {"inner_radius", info.inner_radius},
                        {"inner_length", info.inner_length},
                        {"solid_fraction", info.solid_fraction},
                        {"fill_fraction", info.fill_fraction},
                        {"dt", info.dt},
                        {"skin", info.skin},
                        {"samples_per_revolution", info.samples_per_revolution},
                        {"profile_bins", info.profile_bins},
                        {"band_bins", info.band_bins},
                        {"settle_time", info.settle_time},
                        {"settled", info.settled},
                        {"wall_seconds", info.wall_seconds},
                        {"grain_updates_per_second", info.grain_updates_per_second},
                        {"threads", info.threads},
                        {"isa", info.isa},
                        {"shear_model", info.shear_model},
                        {"friction_normal", info.friction_normal},
                        {"tangential_stiffness", info.tangential_stiffness},
                        {"surface_energy", info.surface_energy},
                        {"periodic_axis", info.periodic_axis},
                        {"spin_up_time", info.spin_up_time},
                        {"arrangement", info.arrangement},
                        {"band_edges", edges},
                        {"cap_friction", info.cap_friction},
                        {"until_band_change", info.until_band_change},
                        {"band_change_since", info.band_change_since},
                        {"bands_at_start", info.bands_at_start},
                        {"bands_at_end", info.bands_at_end},
                        {"walls", info.walls},
                        {"mesh", info.mesh},
                        {"mesh_scale", info.mesh_scale},
                        {"paper_materials", info.paper_materials},
                        {"large_material", info.large_material},
                        {"small_material", info.small_material},
                        {"wall_material", info.wall_material},
                        {"cap_material", info.cap_material},
                        {"component", components}};
    if (!materials.empty()) t.insert("material", materials);
    std::ostringstream text;
    text << "# tumble drum run: what was run (read by `tumble analyze`)\n" << t << '\n';
    return text.str();
}

void write_drum_run_info(const fs::path& file, const DrumRunInfo& info) {
    write_file_atomically(file, drum_run_info_text(info));
}

DrumRunInfo read_drum_run_info(const fs::path& file) { return parse_drum_run_info(read_text_file(file), file); }

DrumRunInfo parse_drum_run_info(std::string_view text, const fs::path& file) {
    const toml::table t = parse_toml(text, file);
    const Reader r(file);
    DrumRunInfo info;
    info.mode = r.string(r.required(t, "", "mode"), "mode");
    auto num = [&](const char* key) { return r.required_number(t, "", key, Bound::any); };
    info.omega = num("omega");
    info.froude = num("froude");
    info.revolutions = num("revolutions");
    info.seed = static_cast<std::uint64_t>(r.integer(r.required(t, "", "seed"), "seed", 0, INT64_MAX));
    info.wall_particles = static_cast<std::size_t>(num("wall_particles"));
    info.inner_radius = num("inner_radius");
    info.inner_length = r.required_number(t, "", "inner_length", Bound::positive);
    info.solid_fraction = num("solid_fraction");
    info.fill_fraction = num("fill_fraction");
    info.dt = num("dt");
    info.skin = t["skin"].value_or(0.0);  // absent before 2026-12-02
    info.samples_per_revolution = static_cast<int>(num("samples_per_revolution"));
    info.profile_bins = static_cast<int>(r.integer(r.required(t, "", "profile_bins"), "profile_bins", 1, 1 << 20));
    info.band_bins = t["band_bins"].value_or(0);  // absent before the band analysis
    if (info.band_bins < 0 || info.band_bins > 100000) r.fail("band_bins", "must lie in 0 .. 100000");
    info.settle_time = num("settle_time");
    info.settled = r.boolean(r.required(t, "", "settled"), "settled");
    info.wall_seconds = num("wall_seconds");
    info.grain_updates_per_second = num("grain_updates_per_second");
    info.threads = t["threads"].value_or(1);  // absent in runs of tumble before threads
    info.isa = t["isa"].value_or(std::string());  // absent before the portable build (2026-11-30)
    // Absent in runs before the shear models (2026-11-30): the paper's rule,
    // then with the slip reset to zero at the limit.
    info.shear_model = t["shear_model"].value_or(std::string("paper"));
    info.friction_normal = t["friction_normal"].value_or(std::string("net"));
    info.tangential_stiffness = t["tangential_stiffness"].value_or(std::string("paper"));  // absent before Mindlin's
    info.surface_energy = t["surface_energy"].value_or(paper::surface_energy);  // absent before 2026-12-02: the paper's
    info.periodic_axis = t["periodic_axis"].value_or(false);  // absent before the periodic drum
    info.spin_up_time = t["spin_up_time"].value_or(0.0);       // absent before the spin-up ramp
    // Absent before the arrangements (2026-11-30): halves, the wall's friction.
    info.arrangement = t["arrangement"].value_or(std::string("halves"));
    if (const toml::node* n = t.get("band_edges")) info.band_edges = r.numbers(*n, "band_edges");
    info.cap_friction = t["cap_friction"].value_or(-1.0);
    // Absent before --until-band-change (2026-11-30): every revolution.
    info.until_band_change = t["until_band_change"].value_or(0.0);
    info.band_change_since = t["band_change_since"].value_or(-1.0);
    info.bands_at_start = t["bands_at_start"].value_or(0);
    info.bands_at_end = t["bands_at_end"].value_or(0);
    // Absent before smooth walls and the drum's own materials: the paper's drum.
    info.walls = t["walls"].value_or(std::string("particles"));
    if (!find_keyword(drum_wall_kinds, info.walls))
        r.fail("walls", "unknown walls \"" + info.walls + "\"; known: " + detail::quoted_list(keywords(drum_wall_kinds)));
    info.mesh = t["mesh"].value_or(std::string());
    info.mesh_scale = t["mesh_scale"].value_or(1.0);
    info.paper_materials = t["paper_materials"].value_or(true);
    info.large_material = t["large_material"].value_or(std::string("material-1"));
    info.small_material = t["small_material"].value_or(std::string("material-2"));
    info.wall_material = t["wall_material"].value_or(std::string("wall"));
    info.cap_material = t["cap_material"].value_or(info.cap_friction >= 0.0 ? std::string(drum_cap_material_name) : info.wall_material);
    const auto material_entries = r.tables(t, "", "material");
    for (std::size_t i = 0; i < material_entries.size(); ++i) {
        const std::string p = at("material", i);
        const toml::table& e = *material_entries[i];
        Material m;
        m.name = r.string(r.required(e, p, "name"), join(p, "name"));
        m.E = r.required_number(e, p, "E", Bound::positive);
        m.G = r.required_number(e, p, "G", Bound::positive);
        m.nu = r.required_number(e, p, "nu", Bound::any);
        m.xi = r.required_number(e, p, "xi", Bound::non_negative);
        m.eta = r.required_number(e, p, "eta", Bound::non_negative);
        m.rho = r.required_number(e, p, "rho", Bound::positive);
        m.radius = r.required_number(e, p, "radius", Bound::positive);
        info.materials.push_back(m);
    }
    const auto entries = r.tables(t, "", "component");
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const std::string p = at("component", i);
        DrumComponent c;
        c.name = r.string(r.required(*entries[i], p, "name"), join(p, "name"));
        c.grains = static_cast<std::size_t>(r.required_number(*entries[i], p, "grains", Bound::non_negative));
        c.mass = r.required_number(*entries[i], p, "mass", Bound::non_negative);
        c.start_side = r.required_number(*entries[i], p, "start_side", Bound::any);
        info.components.push_back(c);
    }
    if (info.components.empty()) r.fail("component", "no components");
    return info;
}

DrumSeriesWriter::DrumSeriesWriter(const fs::path& directory, const DrumRunInfo& info, bool continuing)
    : series_path_(directory / "drum_series.csv"), profiles_path_(directory / "profiles.csv"),
      series_(continuing ? open_for_appending(series_path_) : open_for_writing(series_path_)),
      profiles_(continuing ? open_for_appending(profiles_path_) : open_for_writing(profiles_path_)),
      inner_length_(info.inner_length) {
    if (continuing) return;
    series_ << "revolutions,time,angle_of_repose,fill_fraction,bed_centre_x,bed_centre_y";
    for (const DrumComponent& c : info.components)
        series_ << fmt::format(",grains_{0},mean_z_{0},mean_z_stderr_{0},kinetic_energy_{0},kinetic_per_grain_{0}",
                               column_name(c.name));
    series_ << '\n';
    profiles_ << "revolutions,component,bin,z,concentration\n";
    check_written(series_, series_path_);
    check_written(profiles_, profiles_path_);
}

void DrumSeriesWriter::write(double revolutions, double time, const analysis::DrumState& s) {
    series_ << fmt::format("{},{},{},{},{},{}", revolutions, time, s.angle_of_repose, s.fill_fraction,
                           s.bed_centre.x, s.bed_centre.y);
    for (const analysis::ComponentState& c : s.components)
        series_ << fmt::format(",{},{},{},{},{}", c.grains, c.mean_z, c.mean_z_stderr, c.kinetic_energy,
                               c.kinetic_per_grain);
    series_ << '\n';
    for (std::size_t c = 0; c < s.components.size(); ++c) {
        const auto& C = s.components[c].concentration;
        for (std::size_t b = 0; b < C.size(); ++b)
            profiles_ << fmt::format("{},{},{},{},{}\n", revolutions, c, b,
                                     -0.5 * inner_length_ + (b + 0.5) * inner_length_ / static_cast<double>(C.size()),
                                     C[b]);
    }
    check_written(series_, series_path_);
    check_written(profiles_, profiles_path_);
}

DrumSeries read_drum_series(const fs::path& file, std::size_t components) {
    const CsvTable csv = read_csv_table(file);
    DrumSeries s;
    s.revolutions = csv.numbers("revolutions");
    s.time = csv.numbers("time");
    s.angle_of_repose = csv.numbers("angle_of_repose");
    // Component columns are named after the components, in order after the
    // six fixed columns, five each.
    for (std::size_t c = 0; c < components; ++c) {
        const std::size_t first = 6 + 5 * c;
        if (first + 5 > csv.header.size()) throw Error(file.string() + ": fewer component columns than components");
        for (auto [target, offset] : {std::pair{&s.mean_z, 1}, std::pair{&s.mean_z_stderr, 2},
                                      std::pair{&s.kinetic_energy, 3}, std::pair{&s.kinetic_per_grain, 4}}) {
            target->push_back(csv.numbers(csv.header[first + offset]));
        }
    }
    return s;
}

DrumProfiles read_drum_profiles(const fs::path& file, std::size_t components, std::size_t bins) {
    const CsvTable csv = read_csv_table(file);
    const auto N = csv.numbers("revolutions"), c = csv.numbers("component"), b = csv.numbers("bin"),
               z = csv.numbers("z"), C = csv.numbers("concentration");
    DrumProfiles p;
    p.bin_centre.resize(bins);
    for (std::size_t row = 0; row < N.size(); ++row) {
        if (c[row] == 0 && b[row] == 0) {
            p.revolutions.push_back(N[row]);
            p.concentration.emplace_back(components, std::vector<double>(bins, -1.0));
        }
        if (p.concentration.empty()) throw Error(file.string() + ": rows out of order");
        const auto ci = static_cast<std::size_t>(c[row]), bi = static_cast<std::size_t>(b[row]);
        if (ci >= components || bi >= bins) throw Error(file.string() + ": component or bin out of range");
        p.concentration.back()[ci][bi] = C[row];
        p.bin_centre[bi] = z[row];
    }
    return p;
}

namespace {

// Time average over the rotating phase of a / b.
double mean_ratio(const std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& N) {
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t k = 0; k < N.size(); ++k)
        if (N[k] > 0.0 && b[k] > 0.0) {
            sum += a[k] / b[k];
            ++n;
        }
    return n ? sum / static_cast<double>(n) : std::numeric_limits<double>::quiet_NaN();
}

std::size_t nearest_sample(const std::vector<double>& N, double target) {
    std::size_t best = 0;
    for (std::size_t k = 1; k < N.size(); ++k)
        if (std::abs(N[k] - target) < std::abs(N[best] - target)) best = k;
    return best;
}

}  // namespace

analysis::GrainFrame read_snapshot_grains(const fs::path& file, double rotation_start, double omega,
                                          const std::vector<Material>& materials) {
    const CsvTable csv = read_csv_table(file);
    const std::optional<double> time = snapshot_time(csv);
    if (!time)
        throw Error(file.string() + ": not a particle snapshot (no time column, and no first line \"# time = T s, ...\")");
    const std::vector<double> id = csv.numbers("id"), x = csv.numbers("x"), y = csv.numbers("y"),
                              z = csv.numbers("z"), radius = csv.numbers("radius"), tag = csv.numbers("tag"),
                              kinematic = csv.numbers("kinematic"), vx = csv.numbers("vx"), vy = csv.numbers("vy"),
                              vz = csv.numbers("vz"), wx = csv.numbers("wx"), wy = csv.numbers("wy"),
                              wz = csv.numbers("wz");
    // Masses from the drum's materials, by name.
    const std::size_t material_column = csv.column("material");
    auto density = [&](const std::string& name) {
        for (const Material& m : materials)
            if (m.name == name) return m.rho;
        throw Error(file.string() + ": unknown material \"" + name + "\" (not one of the drum's materials)");
    };
    std::vector<std::size_t> order(id.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return id[a] < id[b]; });
    analysis::GrainFrame frame;
    frame.revolutions = omega * (*time - rotation_start) / (2.0 * tumble::pi);
    for (std::size_t k : order) {
        if (kinematic[k] != 0.0) continue;
        frame.id.push_back(static_cast<std::int64_t>(id[k]));
        frame.position.push_back({x[k], y[k], z[k]});
        frame.radius.push_back(radius[k]);
        frame.tag.push_back(static_cast<std::int32_t>(tag[k]));
        frame.velocity.push_back({vx[k], vy[k], vz[k]});
        frame.angular_velocity.push_back({wx[k], wy[k], wz[k]});
        frame.mass.push_back(4.0 / 3.0 * tumble::pi * std::pow(radius[k], 3) * density(csv.rows[k][material_column]));
    }
    return frame;
}

std::vector<analysis::GrainFrame> read_rotation_frames(const fs::path& dir, const DrumRunInfo& info,
                                                       std::size_t leave_newest) {
    std::vector<analysis::GrainFrame> frames;
    std::vector<fs::path> files = list_snapshot_csv(dir);
    files.resize(files.size() - std::min(leave_newest, files.size()));
    for (const fs::path& file : files) {
        analysis::GrainFrame frame = read_snapshot_grains(file, info.settle_time, info.omega,
                                                          info.materials.empty() ? paper::materials() : info.materials);
        if (frame.revolutions >= -1e-9) frames.push_back(std::move(frame));  // from the start of rotation
    }
    return frames;
}

SnapshotCoverage snapshot_coverage(const std::vector<analysis::GrainFrame>& frames) {
    SnapshotCoverage c;
    c.count = frames.size();
    if (frames.empty()) return c;
    c.first = frames.front().revolutions;
    c.last = frames.back().revolutions;
    c.spacing = frames.size() > 1 ? frames[1].revolutions - frames[0].revolutions : 0.0;
    c.from_start = c.first <= 0.5 * c.spacing + 1e-9;
    return c;
}

std::string SnapshotCoverage::describe() const {
    if (count == 0) return "  particle snapshots of the rotation: none (tumble drum --snapshots)\n";
    std::string s = fmt::format("  particle snapshots of the rotation: {}, N = {:.4g} to {:.4g}", count, first, last);
    if (count > 1) s += fmt::format(" (every {:.3g} revolutions)", spacing);
    if (!from_start)
        s += fmt::format("; those before N = {:.4g} are missing (a run continued elsewhere from a kept checkpoint "
                         "keeps its series, not its snapshots), so everything below measured from the snapshots "
                         "(the grains' axial MSD, the axial motion by depth, the bed structure and energetics, the "
                         "crossing of bands) covers N >= {:.4g} only",
                         first, first);
    return s + "\n";
}

Json SnapshotCoverage::json() const {
    return Json{{"count", count}, {"first_revolution", first}, {"last_revolution", last}, {"spacing", spacing},
                {"from_start", from_start}};
}

namespace {

// Depth layers of one grain diameter; the last holds everything deeper (a
// bed of 1000 grains in the paper's drum is about 6 diameters deep).
constexpr int depth_layers = 8;

// The axial displacements by depth between consecutive particle snapshots
// taken during the rotation; none without two such snapshots.
std::optional<analysis::DepthMobility> depth_mobility_of_run(const std::vector<analysis::GrainFrame>& frames,
                                                             const DrumRunInfo& info) {
    if (frames.size() < 2) return std::nullopt;
    analysis::DepthMobility mobility(static_cast<int>(info.components.size()), depth_layers,
                                     info.periodic_axis ? info.inner_length : 0.0);
    for (std::size_t k = 1; k < frames.size(); ++k) mobility.add(frames[k - 1], frames[k], info.inner_radius);
    return mobility;
}

void write_depth_mobility(const fs::path& file, const analysis::DepthMobility& m, const DrumRunInfo& info) {
    std::ostringstream out;
    out << "layer,depth_lo,depth_hi";
    for (const DrumComponent& c : info.components)
        for (const char* what : {"samples", "msd_per_rev", "share", "occupancy"})
            out << ',' << what << '_' << column_name(c.name);
    out << '\n';
    for (int layer = 0; layer < m.layers(); ++layer) {
        out << fmt::format("{},{},{}", layer, layer == 0 ? -INFINITY : layer,
                           layer + 1 == m.layers() ? INFINITY : layer + 1.0);
        for (int c = 0; c < m.components(); ++c)
            out << fmt::format(",{},{},{},{}", m.samples(c, layer), m.msd_per_revolution(c, layer), m.share(c, layer),
                               m.occupancy(c, layer));
        out << '\n';
    }
    write_file_whole(file, out.str());
}


// The MSD's blocks: a fifth of the rotation after the start-up (so 5
// blocks), at least 2 revolutions (the lags fitted run from 1 revolution to
// the block's length), at most 4, in whole frame spacings.
analysis::MsdOptions msd_options_of_run(const std::vector<analysis::GrainFrame>& frames, const DrumRunInfo& info,
                                        const AnalyzeOptions& options) {
    analysis::MsdOptions o;
    o.half_length = info.periodic_axis ? INFINITY : 0.5 * info.inner_length;
    if (frames.size() < 2) return o;
    const double h = frames[1].revolutions - frames[0].revolutions;
    const double span = frames.back().revolutions - std::max(options.first_revolution, frames.front().revolutions);
    o.block = std::floor(std::clamp(span / 5.0, 2.0, 4.0) / h + 0.01) * h;
    return o;
}

// The frames after the start-up.
std::vector<analysis::GrainFrame> steady_frames(const std::vector<analysis::GrainFrame>& frames, double first) {
    std::vector<analysis::GrainFrame> out;
    for (const analysis::GrainFrame& f : frames)
        if (f.revolutions >= first - 1e-9) out.push_back(f);
    return out;
}

// axial_msd.csv: the MSD against lag from one snapshot spacing to 4
// revolutions (or the rotation after the start-up), every window pooled.
void write_axial_msd(const fs::path& file, const std::vector<analysis::GrainFrame>& frames, const DrumRunInfo& info,
                     const AnalyzeOptions& options) {
    const std::vector<analysis::GrainFrame> steady = steady_frames(frames, options.first_revolution);
    if (steady.size() < 3) return;
    analysis::MsdOptions o = msd_options_of_run(frames, info, options);
    o.block = std::min(4.0, steady.back().revolutions - steady.front().revolutions);
    std::vector<std::vector<double>> msd;
    std::vector<double> lag;
    for (std::size_t c = 0; c < info.components.size(); ++c) {
        const analysis::MsdBlocks b = analysis::axial_msd_blocks(
            analysis::axial_tracks(steady, static_cast<std::int32_t>(c), info.periodic_axis ? info.inner_length : 0.0),
            o);
        lag = b.lag;
        msd.push_back(analysis::weighted_msd(b, std::vector<double>(b.blocks(), 1.0)));
    }
    std::ostringstream out;
    out << "lag";
    for (const DrumComponent& c : info.components) out << ",msd_" << column_name(c.name);
    out << '\n';
    for (std::size_t l = 0; l < lag.size(); ++l) {
        out << lag[l];
        for (const auto& m : msd) out << ',' << m[l];
        out << '\n';
    }
    write_file_whole(file, out.str());
}

// A Hogg fit, or an undetermined one with the reason: no samples, or not
// applicable (hogg_not_applicable).
analysis::HoggFit fit_hogg_or_note(const std::vector<double>& N, const std::vector<double>& z, double L,
                                   const analysis::HoggFitOptions& o, const std::string& not_applicable) {
    if (N.empty() || !not_applicable.empty()) {
        analysis::HoggFit none;
        none.D = none.D_stderr = none.amplitude = std::nan("");
        none.note = N.empty() ? "no samples" : not_applicable;
        return none;
    }
    return analysis::fit_hogg(N, z, L, o);
}

std::string describe_hogg(const analysis::HoggFit& f) {
    if (!f.determined)
        return fmt::format("D not determined: {}{}", f.note,
                           std::isfinite(f.D) ? fmt::format(" (best estimate {:.3e} m^2/rev)", f.D) : "");
    return fmt::format("D = {:.3e} +- {:.1e} m^2/rev (95 %: [{:.3e}, {:.3e}]), fitted <z>(0) = {:.4g} m", f.D,
                       f.D_stderr, f.D - 1.96 * f.D_stderr, f.D + 1.96 * f.D_stderr, f.amplitude);
}

// The 95 % interval of a Hogg fit: +-1.96 standard errors.
Json hogg_json(const analysis::HoggFit& f, double first_revolution) {
    return Json{{"D", determined_value(f.D, f.determined)},
                {"D_best_estimate", best_estimate(f.D, f.determined)},
                {"D_stderr", f.D_stderr},
                {"D_lo", f.D - 1.96 * f.D_stderr},
                {"D_hi", f.D + 1.96 * f.D_stderr},
                {"amplitude", f.amplitude},
                {"first_revolution", first_revolution},
                {"determined", f.determined},
                {"note", f.note},
                {"points", static_cast<std::int64_t>(f.points)}};
}

// Segregation, energetics, the free surface per slice and the flowing layer
// from the snapshots after the start-up (bed_structure.hpp):
// bed_structure.csv, flow_profile.csv, and their summary in `text` and
// `summary`.
void analyze_bed_structure(const fs::path& dir, const std::vector<analysis::GrainFrame>& frames,
                           const DrumRunInfo& info, const AnalyzeOptions& options, std::ostringstream& text,
                           Json& summary) {
    const std::vector<analysis::GrainFrame> steady = steady_frames(frames, options.first_revolution);
    if (steady.empty()) return;
    std::vector<analysis::SpeciesEnergetics> energetics(info.components.size());
    double mean_diameter = 0.0;
    for (double r : steady.front().radius) mean_diameter += 2.0 * r / static_cast<double>(steady.front().radius.size());
    std::ostringstream out;
    out << "revolutions,slice,z,relative_volume,surface_angle";
    for (const DrumComponent& c : info.components) out << ",mean_distance_" << column_name(c.name);
    out << '\n';
    std::vector<double> distance_sum(info.components.size(), 0.0), distance_count(info.components.size(), 0.0);
    double first_rms = 0.0, last_rms = 0.0;
    // Depth bins of half a mean grain diameter down to 12 diameters.
    analysis::FlowProfile flow(0.5 * mean_diameter, 12.0 * mean_diameter);
    std::vector<double> angle_sum(static_cast<std::size_t>(info.profile_bins), 0.0),
        angle_count(angle_sum.size(), 0.0);
    for (std::size_t f = 0; f < steady.size(); ++f) {
        flow.add(steady[f], info.inner_radius);
        const std::vector<double> angle =
            analysis::surface_angle_by_slice(steady[f], info.inner_radius, info.inner_length, info.profile_bins);
        // Cells of two mean grain diameters: a few grains of each kind.
        analysis::add_energetics(steady[f], 2.0 * mean_diameter, energetics);
        const analysis::AxialStructure a =
            analysis::axial_structure(steady[f], static_cast<int>(info.components.size()), info.inner_length,
                                      info.profile_bins);
        double rms = 0.0;
        for (std::size_t s = 0; s < a.z.size(); ++s) {
            out << fmt::format("{},{},{},{},{}", steady[f].revolutions, s, a.z[s], a.relative_volume[s], angle[s]);
            if (std::isfinite(angle[s])) angle_sum[s] += angle[s], angle_count[s] += 1.0;
            bool all_present = true;
            for (std::size_t c = 0; c < info.components.size(); ++c) {
                out << ',' << a.mean_distance[c][s];
                all_present = all_present && std::isfinite(a.mean_distance[c][s]);
            }
            out << '\n';
            for (std::size_t c = 0; all_present && c < info.components.size(); ++c)
                distance_sum[c] += a.mean_distance[c][s], distance_count[c] += 1.0;
            rms += (a.relative_volume[s] - 1.0) * (a.relative_volume[s] - 1.0) / static_cast<double>(a.z.size());
        }
        (f == 0 ? first_rms : last_rms) = std::sqrt(rms);
    }
    write_file_whole(dir / "bed_structure.csv", out.str());
    {
        std::ostringstream profile;
        profile << "depth,depth_diameters,downhill_velocity\n";
        for (std::size_t k = 0; k < flow.bins(); ++k)
            profile << fmt::format("{},{},{}\n", flow.depth(k), flow.depth(k) / mean_diameter, flow.velocity(k));
        write_file_whole(dir / "flow_profile.csv", profile.str());
    }
    Json angles_json = Json::array();
    std::string angles_text;
    for (std::size_t k = 0; k < angle_sum.size(); ++k) {
        const double mean = angle_count[k] > 0.0 ? angle_sum[k] / angle_count[k] : std::nan("");
        angles_json.push_back(mean);
        angles_text += fmt::format("{}{:.1f}", k ? " " : "", mean);
    }
    text << fmt::format("  free surface per axial slice (mean over the snapshots, degrees, from z = -L/2): {}\n",
                        angles_text);
    text << fmt::format("  flowing layer (mean downhill velocity along the surface changes sign; flow_profile.csv): "
                        "{:.3g} m = {:.2g} mean grain diameters deep\n",
                        flow.thickness(), flow.thickness() / mean_diameter);
    text << fmt::format("  bed volume along the axis (bed_structure.csv): rms deviation from uniform {:.3f} at N = "
                        "{:.3g}, {:.3f} at N = {:.3g}\n",
                        first_rms, steady.front().revolutions, last_rms, steady.back().revolutions);
    Json species_json = Json::array();
    text << "  where both kinds are present (cells of 2 grain diameters), per grain: fluctuation energy about the "
            "local mean flow, granular temperature, rotational energy, mean distance from the slice's centroid\n";
    for (std::size_t c = 0; c < info.components.size(); ++c) {
        const double distance = distance_count[c] > 0.0 ? distance_sum[c] / distance_count[c] : std::nan("");
        text << fmt::format("    {}: {:.3g} J, {:.3g} m^2/s^2, {:.3g} J, {:.4g} m ({} grain-frames)\n",
                            info.components[c].name, energetics[c].fluctuation(), energetics[c].temperature(),
                            energetics[c].rotation(), distance, energetics[c].grains);
        species_json.push_back(Json{{"name", info.components[c].name},
                                    {"fluctuation_energy_per_grain", energetics[c].fluctuation()},
                                    {"granular_temperature", energetics[c].temperature()},
                                    {"rotational_energy_per_grain", energetics[c].rotation()},
                                    {"mean_distance_from_centroid", distance},
                                    {"grain_frames", static_cast<std::int64_t>(energetics[c].grains)}});
    }
    summary["bed_structure"] = Json{{"volume_rms_first", first_rms},
                                    {"surface_angle_by_slice", angles_json},
                                    {"flowing_layer_thickness", flow.thickness()},
                                    {"flowing_layer_thickness_diameters", flow.thickness() / mean_diameter},
                                    {"volume_rms_last", last_rms},
                                    {"species", species_json}};
}

}  // namespace

double drum_msd_block(const std::vector<analysis::GrainFrame>& frames, const DrumRunInfo& info,
                      const AnalyzeOptions& options) {
    return msd_options_of_run(frames, info, options).block;
}

analysis::MsdEstimate drum_msd(const std::vector<analysis::GrainFrame>& frames, const DrumRunInfo& info,
                               std::size_t component, const AnalyzeOptions& options, double block) {
    if (component >= info.components.size())
        throw Error("component " + std::to_string(component) + ": the run has " +
                    std::to_string(info.components.size()) + " components");
    const std::vector<analysis::GrainFrame> steady = steady_frames(frames, options.first_revolution);
    if (steady.size() < 3) {
        analysis::MsdEstimate none;
        none.note = "fewer than three particle snapshots after the start-up (N >= " +
                    fmt::format("{:.3g}", options.first_revolution) + "; tumble drum --snapshots, --revolutions)";
        return none;
    }
    analysis::MsdOptions o = msd_options_of_run(frames, info, options);
    if (block > 0.0) o.block = block;
    const analysis::MsdBlocks blocks = analysis::axial_msd_blocks(
        analysis::axial_tracks(steady, static_cast<std::int32_t>(component),
                               info.periodic_axis ? info.inner_length : 0.0),
        o);
    return analysis::estimate_axial_diffusion({blocks}, o);
}

std::string hogg_not_applicable(const DrumRunInfo& info) {
    if (info.periodic_axis) return "not applicable on a periodic axis";
    if (info.arrangement != "halves") return "not applicable to a start other than halves (" + info.arrangement + ")";
    return "";
}

std::string analyze_drum_run(const fs::path& dir, const AnalyzeOptions& options) {
    const DrumRunInfo info = read_drum_run_info(dir / "drum_run.toml");
    const std::size_t n_components = info.components.size();
    const DrumSeries series = read_drum_series(dir / "drum_series.csv", n_components);
    const DrumProfiles profiles =
        read_drum_profiles(dir / "profiles.csv", n_components, static_cast<std::size_t>(info.profile_bins));
    const double L = info.inner_length;

    std::ostringstream text;
    text << fmt::format("tumble drum run in {}\n", dir.string());
    text << fmt::format("  mode {}, omega {:.4g} rad/s ({:.3g} rpm, Froude {:.3g}), {:.4g} revolutions\n", info.mode,
                        info.omega, info.omega * 60.0 / (2.0 * tumble::pi), info.froude,
                        series.revolutions.empty() ? 0.0 : series.revolutions.back());
    // The headline D of each component goes here, after the first two lines;
    // the details of every estimator under a heading after the set-up.
    const std::size_t headline_at = static_cast<std::size_t>(text.tellp());
    std::ostringstream headline;
    if (info.band_change_since >= 0.0)
        text << fmt::format("  ended early (--until-band-change {:.3g}): {} bands at the start, another count from "
                            "N = {:.4g} on, {} at the end ({:.4g} revolutions asked)\n",
                            info.until_band_change, info.bands_at_start, info.band_change_since, info.bands_at_end,
                            info.revolutions);
    text << fmt::format("  shear model {} ({} stiffness), friction limited by the {} normal force; surface energy {}\n",
                        info.shear_model, info.tangential_stiffness, info.friction_normal,
                        info.surface_energy < 0.0 ? std::string("W per pair (the materials' [[pair]] tables)")
                        : info.surface_energy == 0.0
                            ? std::string("W = 0 J/m^2 (no attraction)")
                            : fmt::format("W = {:.3g} J/m^2", info.surface_energy));
    if (!info.paper_materials) {
        auto radius = [&](const std::string& name) {
            for (const Material& m : info.materials)
                if (m.name == name) return fmt::format(" (R = {:.4g} m)", m.radius);
            return std::string();
        };
        text << fmt::format("  materials: large grains {}{}{}, wall {}, caps {}\n", info.large_material,
                            radius(info.large_material),
                            info.mode == "self" ? std::string()
                                                : fmt::format(", small grains {}{}", info.small_material,
                                                              radius(info.small_material)),
                            info.wall_material, info.periodic_axis ? std::string("none") : info.cap_material);
    }
    const std::string edges =
        info.band_edges.size() > 2 ? fmt::format(", band edges z = {:.4g} m", fmt::join(info.band_edges, " ")) : "";
    text << fmt::format("  start {}{}; end caps: {}\n", info.arrangement, edges,
                        info.periodic_axis          ? "none (periodic axis)"
                        : info.cap_friction >= 0.0 ? fmt::format("friction {:.3g}", info.cap_friction)
                                                   : std::string("the wall's friction"));
    text << fmt::format("  {}; inner radius {:.4g} m, bed length L = {:.4g} m\n",
                        info.walls == "smooth"   ? std::string(info.periodic_axis ? "smooth wall (an infinite cylinder)"
                                                                                  : "smooth walls (a cylinder and two discs)")
                        : info.walls == "mesh"
                            ? (info.mesh.empty() ? std::string("a mantle of triangles and two smooth discs")
                                                 : "the mantle of " + info.mesh + " and two smooth discs")
                                               : fmt::format("{} wall particles", info.wall_particles),
                        info.inner_radius, L);
    text << fmt::format("  solid fraction {:.3f} of the drum volume; fill fraction {:.3f} (bed cross-section after "
                        "settling, {})\n",
                        info.solid_fraction, info.fill_fraction,
                        info.settled ? fmt::format("settled in {:.3g} s", info.settle_time)
                                     : fmt::format("NOT settled after {:.3g} s", info.settle_time));

    const std::vector<analysis::GrainFrame> frames = read_rotation_frames(dir, info);
    const SnapshotCoverage coverage = snapshot_coverage(frames);
    text << coverage.describe();
    const std::size_t details_at = static_cast<std::size_t>(text.tellp());
    write_axial_msd(dir / "axial_msd.csv", frames, info, options);

    Json components_json = Json::array();
    std::vector<analysis::DiffusionFit> fits;
    std::vector<analysis::MsdEstimate> msd;
    for (std::size_t c = 0; c < n_components; ++c) {
        const DrumComponent& comp = info.components[c];
        // The Hogg solution describes the component that starts at z > 0;
        // mirror the other.
        std::vector<double> N, z;
        for (std::size_t k = 0; k < series.revolutions.size(); ++k)
            if (series.revolutions[k] >= 0.0) {
                N.push_back(series.revolutions[k]);
                z.push_back(comp.start_side * series.mean_z[c][k]);
            }
        if (info.arrangement == "halves")
            text << fmt::format("  {} ({} grains, started at z {} 0): <z>(0) = {:.4g} m (L/4 = {:.4g} m)\n",
                                comp.name, comp.grains, comp.start_side > 0 ? ">" : "<", z.empty() ? 0.0 : z.front(),
                                L / 4.0);
        else  // bands, boundaries or mixed: no side to mirror
            text << fmt::format("  {} ({} grains, {} start): <z>(0) = {:.4g} m\n", comp.name, comp.grains,
                                info.arrangement, z.empty() ? 0.0 : comp.start_side * z.front());  // unmirrored

        // The grains' axial MSD: the headline D.
        msd.push_back(drum_msd(frames, info, c, options));
        analysis::MsdEstimate& m = msd.back();
        if (m.determined) {
            headline << fmt::format("    {}: D = {:.3e} m^2/rev, 95 % interval [{:.3e}, {:.3e}]", comp.name, m.D,
                                    m.interval.lo, m.interval.hi);
            text << fmt::format("    grains' axial MSD (the D above): lags {:.3g}-{:.3g} rev, {} blocks of {:.3g} "
                                "rev\n",
                                m.fit_lo, m.fit_hi, m.blocks, drum_msd_block(frames, info, options));
        } else {
            headline << fmt::format("    {}: D not determined: {}{}", comp.name, m.note,
                                    std::isfinite(m.D) ? fmt::format(" (best estimate {:.3e} m^2/rev)", m.D) : "");
            text << "    grains' axial MSD: D not determined (above)\n";
        }

        // Hogg with the amplitude free and the start-up left out.
        const analysis::HoggFit hogg =
            fit_hogg_or_note(N, z, L, {options.first_revolution, false, -1.0}, hogg_not_applicable(info));
        text << "    Hogg, amplitude free, N >= " << fmt::format("{:.3g}", options.first_revolution) << ": "
             << describe_hogg(hogg) << "\n";

        // Drift: with D held at the grains' MSD value, what is left of the
        // motion of <z> is a drift of the component's centre.
        analysis::HoggFit drift;
        std::string verdict = "undetermined";
        if (m.determined && hogg_not_applicable(info).empty()) {
            drift = fit_hogg_or_note(N, z, L, {options.first_revolution, true, m.D}, "");
            // In the mirrored frame <z> starts at L/4 and mixing lowers it: a
            // drift v > 0 carries the component back toward its own end
            // (segregation), v < 0 mixes it faster than its grains' diffusion
            // (axial convection, e.g. recirculation driven by the end caps).
            if (drift.points >= 10) {
                const bool significant = std::abs(drift.drift) > 3.0 * drift.drift_stderr;
                verdict = !significant ? "diffusing" : drift.drift > 0.0 ? "segregating" : "convecting";
                const char* meaning =
                    verdict == "diffusing"     ? "consistent with diffusion alone"
                    : verdict == "segregating" ? "segregating: its <z> moves back toward its own end"
                                               : "convecting: its <z> falls faster than its grains' diffusion explains";
                text << fmt::format("    drift of <z> beyond diffusion at the MSD's D: {:.2e} +- {:.1e} m/rev ({:.1f} "
                                    "standard errors): {}\n",
                                    drift.drift, drift.drift_stderr, std::abs(drift.drift) / drift.drift_stderr,
                                    meaning);
            }
        }
        // What the headline D does not cover: a component's centre moving by
        // more than its grains' diffusion (then its Hogg D below is no
        // diffusion coefficient).
        if (verdict == "convecting")
            headline << "; its <z> falls faster than this D explains (convecting: the Hogg D below is no diffusion "
                        "coefficient)";
        else if (verdict == "segregating")
            headline << "; its <z> moves back toward its own end (segregating)";
        headline << "\n";

        const analysis::DiffusionFit fit = analysis::fit_diffusion(N.empty() ? std::vector<double>{0.0} : N,
                                                                   z.empty() ? std::vector<double>{0.0} : z, L);
        fits.push_back(fit);
        if (hogg_not_applicable(info).empty()) {
            text << "    old estimator, Hogg pinned at L/4 from N = 0: ";
            if (fit.determined)
                text << fmt::format("D = {:.3e} +- {:.1e} m^2/rev; one-term: {:.3e} +- {:.1e}\n", fit.D,
                                    fit.D_stderr, fit.one_term_D, fit.one_term_D_stderr);
            else  // said, as the other estimators say it (summary.json has the best estimate and the note)
                text << "D not determined: " << fit.note << "\n";
        }
        // In summary.json a D (or drift) that is not determined is null; the
        // old estimator's only where the Hogg solution applies.
        const bool drifted = verdict != "undetermined";
        const bool pinned = fit.determined && hogg_not_applicable(info).empty();
        components_json.push_back(Json{{"name", comp.name},
                                       {"grains", static_cast<std::int64_t>(comp.grains)},
                                       {"mass", comp.mass},
                                       {"start_side", comp.start_side},
                                       {"msd",
                                        [&] {
                                            Json j = msd_json(m);
                                            j["first_revolution"] = options.first_revolution;
                                            j["block"] = drum_msd_block(frames, info, options);
                                            return j;
                                        }()},
                                       {"hogg_free", hogg_json(hogg, options.first_revolution)},
                                       {"drift", Json{{"velocity", determined_value(drift.drift, drifted)},
                                                      {"velocity_stderr", determined_value(drift.drift_stderr, drifted)},
                                                      {"D_held", determined_value(m.D, drifted)},
                                                      {"verdict", verdict}}},
                                       {"D", determined_value(fit.D, pinned)},
                                       {"D_best_estimate", best_estimate(fit.D, pinned)},
                                       {"D_stderr", fit.D_stderr},
                                       {"D_one_term", fit.one_term_D},
                                       {"D_one_term_stderr", fit.one_term_D_stderr},
                                       {"determined", pinned},
                                       {"note", hogg_not_applicable(info).empty() ? fit.note : hogg_not_applicable(info)},
                                       {"residual_rms", fit.residual_rms},
                                       {"points", static_cast<std::int64_t>(fit.points)}});
    }

    // The dynamic angle of repose, mean over the rotation after the first
    // revolution (the bed takes a fraction of one to reach its steady slope);
    // a run shorter than two revolutions uses its second half.
    double angle_sum = 0.0;
    std::size_t angles = 0;
    const double last_N = series.revolutions.empty() ? 0.0 : series.revolutions.back();
    for (std::size_t k = 0; k < series.revolutions.size(); ++k)
        if (series.revolutions[k] > 0.0 && series.revolutions[k] >= std::min(1.0, 0.5 * last_N) &&
            std::isfinite(series.angle_of_repose[k])) {
            angle_sum += series.angle_of_repose[k];
            ++angles;
        }
    const double angle_of_repose = angles ? angle_sum / static_cast<double>(angles) : std::nan("");
    text << fmt::format("  dynamic angle of repose {:.1f} degrees (mean over the rotation after N = {:.2g})\n",
                        angle_of_repose, std::min(1.0, 0.5 * last_N));

    // --until-band-change: whether the watch ended the run (then since and the counts it saw are known).
    const bool ended_on_band_change = info.band_change_since >= 0.0;
    Json summary{{"mode", info.mode},
                 {"shear_model", info.shear_model},
                 {"friction_normal", info.friction_normal},
                 {"tangential_stiffness", info.tangential_stiffness},
                 {"surface_energy", info.surface_energy},
                 {"arrangement", info.arrangement},
                 {"cap_friction", info.cap_friction},
                 {"walls", info.walls},
                 {"mesh", info.mesh.empty() ? Json() : Json(info.mesh)},
                 {"materials", Json{{"paper", info.paper_materials},
                                    {"large", info.large_material},
                                    {"small", info.mode == "self" ? Json() : Json(info.small_material)},
                                    {"wall", info.wall_material},
                                    {"cap", info.periodic_axis ? Json() : Json(info.cap_material)}}},
                 {"omega", info.omega},
                 {"froude", info.froude},
                 {"revolutions", series.revolutions.empty() ? 0.0 : series.revolutions.back()},
                 {"revolutions_asked", info.revolutions},
                 {"snapshots", coverage.json()},
                 {"until_band_change",
                  info.until_band_change > 0.0
                      ? Json{{"hold", info.until_band_change},
                             {"ended", ended_on_band_change},
                             // null when the watch did not end the run (its own counts: bands.initial, .final)
                             {"since", ended_on_band_change ? Json(info.band_change_since) : Json()},
                             {"bands_at_start", ended_on_band_change ? Json(info.bands_at_start) : Json()},
                             {"bands_at_end", ended_on_band_change ? Json(info.bands_at_end) : Json()}}
                      : Json()},
                 {"grains", static_cast<std::int64_t>([&] {
                      std::size_t n = 0;
                      for (const auto& c : info.components) n += c.grains;
                      return n;
                  }())},
                 {"wall_particles", static_cast<std::int64_t>(info.wall_particles)},
                 {"bed_length", L},
                 {"solid_fraction", info.solid_fraction},
                 {"fill_fraction", info.fill_fraction},
                 {"angle_of_repose", angle_of_repose},
                 {"grain_updates_per_second", info.grain_updates_per_second},
                 {"isa", info.isa},
                 {"components", components_json}};

    // Kinetic energy of species 2 over species 1 (component 1 over 0), with
    // the ratio expected if both had the same mean square velocity.
    if (n_components == 2) {
        const DrumComponent &one = info.components[0], &two = info.components[1];
        const double total = mean_ratio(series.kinetic_energy[1], series.kinetic_energy[0], series.revolutions);
        const double per_grain =
            mean_ratio(series.kinetic_per_grain[1], series.kinetic_per_grain[0], series.revolutions);
        const double total_reference = two.mass / one.mass;
        const double per_grain_reference = (two.mass / two.grains) / (one.mass / one.grains);
        text << fmt::format("  kinetic energy {} / {} (mean over the rotation): total {:.3g} (equal velocities: {:.3g}), "
                            "per grain {:.3g} (equal velocities: {:.3g})\n",
                            two.name, one.name, total, total_reference, per_grain, per_grain_reference);
        summary["kinetic_energy_ratio_total"] = total;
        summary["kinetic_energy_ratio_total_equal_velocity"] = total_reference;
        summary["kinetic_energy_ratio_per_grain"] = per_grain;
        summary["kinetic_energy_ratio_per_grain_equal_velocity"] = per_grain_reference;
    }

    // Concentration profiles of the component that started at z > 0 against
    // the Hogg solution with the grains' MSD D (the pinned Hogg D where the
    // MSD has none), at a quarter, half and all of the run; and the profile
    // collapse: while the mixing front is far from the caps, C(z, N) depends
    // on z / sqrt(D N) alone, so the rms of C - C_Hogg over every sample
    // after the start-up is one number for how well single-grain diffusion
    // accounts for the spreading of the profile.
    std::size_t right = 0;
    for (std::size_t c = 0; c < n_components; ++c)
        if (info.components[c].start_side > 0) right = c;
    if (!profiles.revolutions.empty() && hogg_not_applicable(info).empty()) {
        const bool from_msd = msd[right].determined;
        const double D_profile = from_msd ? msd[right].D : fits[right].D;
        const std::string D_name = from_msd ? "the grains' MSD D" : "the pinned Hogg D";
        std::ostringstream out;
        out << "revolutions,z,measured,hogg\n";
        Json rms_json = Json::array();
        auto rms_at = [&](std::size_t k, bool write) {
            double sum = 0.0;
            std::size_t n = 0;
            for (std::size_t b = 0; b < profiles.bin_centre.size(); ++b) {
                const double measured = profiles.concentration[k][right][b];
                if (measured < 0.0 || !std::isfinite(D_profile)) continue;  // empty bin
                const double hogg =
                    analysis::hogg_concentration(profiles.bin_centre[b], D_profile, profiles.revolutions[k], L);
                if (write)
                    out << fmt::format("{},{},{},{}\n", profiles.revolutions[k], profiles.bin_centre[b], measured, hogg);
                sum += (measured - hogg) * (measured - hogg);
                ++n;
            }
            return std::pair{sum, n};
        };
        // Without a finite D or a filled bin there is nothing to compare:
        // said so (null in the JSON), not an rms of 0 or NaN.
        const std::string none = std::isfinite(D_profile) ? "no comparison: every bin is empty"
                                                          : "no comparison: no finite D";
        const auto rms_of = [](double sum, std::size_t n) {
            return n ? Json(std::sqrt(sum / static_cast<double>(n))) : Json(nullptr);
        };
        const auto rms_text = [&](const Json& rms, const std::string& what) {
            return rms.is_null() ? none : fmt::format("{} {:.3f}", what, rms.get<double>());
        };
        const double last = profiles.revolutions.back();
        for (double fraction : {0.25, 0.5, 1.0}) {
            const std::size_t k = nearest_sample(profiles.revolutions, fraction * last);
            const auto [sum, n] = rms_at(k, true);
            const Json rms = rms_of(sum, n);
            rms_json.push_back(Json{{"revolutions", profiles.revolutions[k]}, {"rms_difference", rms}});
            text << fmt::format("  C(z, N = {:.3g}) of {} against Hogg with {}: {}\n", profiles.revolutions[k],
                                info.components[right].name, D_name, rms_text(rms, "rms difference"));
        }
        write_file_whole(dir / "profile_comparison.csv", out.str());
        summary["profile_comparison"] = rms_json;
        double sum = 0.0;
        std::size_t n = 0, late = 0;  // late: the profiles at N >= first_revolution
        for (std::size_t k = 0; k < profiles.revolutions.size(); ++k)
            if (profiles.revolutions[k] >= options.first_revolution) {
                const auto [s_k, n_k] = rms_at(k, false);
                sum += s_k, n += n_k, ++late;
            }
        const Json collapse = rms_of(sum, n);
        text << fmt::format("  profile collapse of {} (C against z / sqrt(N), N >= {:.3g}) on Hogg with {}: {}\n",
                            info.components[right].name, options.first_revolution, D_name,
                            late == 0 ? fmt::format("no comparison: no profile at N >= {:.3g}", options.first_revolution)
                                      : rms_text(collapse, "rms"));
        summary["profile_collapse"] = Json{{"component", info.components[right].name},
                                           {"D", D_profile},
                                           {"D_source", from_msd ? "msd" : "hogg_pinned"},
                                           {"first_revolution", options.first_revolution},
                                           {"rms", collapse}};
    }

    // Self mode: the two halves are one experiment (identical grains, the
    // bed's centre fixed), so one Hogg fit of (<z>_right - <z>_left) / 2.
    // Two components: the drift of <z>_1 + <z>_2, zero if the two kinds only
    // exchange places; a steady drift means bed volume moves along the axis.
    if (n_components == 2) {
        std::vector<double> N, half_difference, sum;
        const std::size_t left = 1 - right;
        for (std::size_t k = 0; k < series.revolutions.size(); ++k)
            if (series.revolutions[k] >= 0.0) {
                N.push_back(series.revolutions[k]);
                half_difference.push_back(0.5 * (series.mean_z[right][k] - series.mean_z[left][k]));
                sum.push_back(series.mean_z[0][k] + series.mean_z[1][k]);
            }
        if (info.mode == "self") {
            const analysis::HoggFit both = fit_hogg_or_note(N, half_difference, L, {options.first_revolution, false, -1.0},
                                                            hogg_not_applicable(info));
            text << "  both halves, (<z>_right - <z>_left)/2, Hogg amplitude free: " << describe_hogg(both) << "\n";
            summary["self_combined_hogg"] = hogg_json(both, options.first_revolution);
            // The grains are identical: the grains' D and the halves' mixing
            // should be one number. Compared by their 95 % intervals.
            if (both.determined && msd[0].determined && msd[1].determined) {
                const double lo = both.D - 1.96 * both.D_stderr, hi = both.D + 1.96 * both.D_stderr;
                const bool agree = lo <= std::min(msd[0].interval.hi, msd[1].interval.hi) &&
                                   hi >= std::max(msd[0].interval.lo, msd[1].interval.lo);
                text << (agree ? "  the grains' MSD D of both halves and this Hogg D agree within their 95 % intervals\n"
                               : "  the grains' MSD D and this Hogg D DISAGREE beyond their 95 % intervals: <z> moves by "
                                 "more than single-grain diffusion (see the drift lines above: convecting or "
                                 "segregating)\n");
                summary["self_msd_hogg_agree"] = agree;
            }
        } else if (!info.periodic_axis) {  // wrapped coordinates have no meaningful sum
            std::vector<double> Ns, sums;
            for (std::size_t k = 0; k < N.size(); ++k)
                if (N[k] >= options.first_revolution) Ns.push_back(N[k]), sums.push_back(sum[k]);
            if (Ns.size() >= 3) {
                const analysis::LineFit f = analysis::fit_line(Ns, sums);
                text << fmt::format("  drift of <z>_1 + <z>_2 (bed volume moving along the axis): {:.2e} +- {:.1e} m/rev\n",
                                    f.slope, f.slope_stderr);
                summary["sum_drift"] = Json{{"velocity", f.slope}, {"velocity_stderr", f.slope_stderr}};
            }
        }
    }

    // Where the axial motion happens: by depth below the free surface, from
    // the particle snapshots (tumble drum --snapshots).
    if (const auto mobility = depth_mobility_of_run(frames, info)) {
        write_depth_mobility(dir / "depth_mobility.csv", *mobility, info);
        Json layers_json = Json::array();
        text << fmt::format("  axial motion by depth below the free surface ({} snapshot intervals; "
                            "depth_mobility.csv):\n    share of <dz^2> in the top grain layer (depth < 1 mean "
                            "grain diameter)",
                            mobility->intervals());
        for (std::size_t c = 0; c < n_components; ++c) {
            const int k = static_cast<int>(c);
            const double top = mobility->share(k, 0);
            const double top_occupancy = mobility->occupancy(k, 0);
            text << fmt::format("{} {}: {:.2f} (holding {:.2f} of its grains)", c ? "," : "", info.components[c].name,
                                top, top_occupancy);
            layers_json.push_back(Json{{"name", info.components[c].name},
                                       {"surface_share", top},
                                       {"surface_occupancy", top_occupancy}});
        }
        text << "\n";
        summary["depth_mobility"] = layers_json;
    }
    // The same over windows of one revolution after the start-up, by each
    // grain's mean depth over the window.
    if (const auto steady = steady_frames(frames, options.first_revolution); steady.size() > 2) {
        const double h = steady[1].revolutions - steady[0].revolutions;
        const auto span = static_cast<std::size_t>(std::llround(1.0 / h));  // frame spacings per revolution
        if (steady.size() > span) {
            analysis::DepthMobility long_lag(static_cast<int>(n_components), depth_layers,
                                             info.periodic_axis ? info.inner_length : 0.0);
            for (std::size_t f = 0; f + span < steady.size(); ++f)
                long_lag.add_window(&steady[f], span + 1, info.inner_radius);
            write_depth_mobility(dir / "depth_mobility_long.csv", long_lag, info);
            Json long_json = Json::array();
            text << fmt::format("  over one revolution, by mean depth ({} windows; depth_mobility_long.csv): share of "
                                "<dz^2> of the grains whose mean depth is under 1 grain diameter",
                                long_lag.intervals());
            for (std::size_t c = 0; c < n_components; ++c) {
                const int k = static_cast<int>(c);
                text << fmt::format("{} {}: {:.2f} (holding {:.2f})", c ? "," : "", info.components[c].name,
                                    long_lag.share(k, 0), long_lag.occupancy(k, 0));
                long_json.push_back(Json{{"name", info.components[c].name},
                                         {"surface_share", long_lag.share(k, 0)},
                                         {"surface_occupancy", long_lag.occupancy(k, 0)}});
            }
            text << "\n";
            summary["depth_mobility_long"] = long_json;
        }
    }

    analyze_bed_structure(dir, frames, info, options, text, summary);
    analyze_band_run(dir, dir, info, text, summary, options.bands, frames, msd.size() > 1 ? &msd[1] : nullptr,
                     options.band_report ? BandReport::always : BandReport::when_banded);

    // summary.json last: its presence marks a finished run (tumble sweep).
    // An undefined number (NaN) is null in it (json.hpp).
    // The headline first: one D per component and what it is; then the
    // set-up; then every estimator and measurement under a heading.
    const std::string all = text.str();
    const std::string summary_text =
        all.substr(0, headline_at) +
        "  D, how fast each component's grains spread along the axis (their axial mean squared displacement grows "
        "by 2 D per revolution; from the particle snapshots after N = " +
        fmt::format("{:.3g}", options.first_revolution) + "):\n" + headline.str() +
        all.substr(headline_at, details_at - headline_at) + "\nother estimators and measurements:\n" +
        all.substr(details_at);
    write_file_atomically(dir / "summary.txt", summary_text);
    write_json_file(dir / "summary.json", summary);
    return summary_text;
}

Json determined_value(double D, bool determined) {
    return determined && std::isfinite(D) ? Json(D) : Json(nullptr);
}

Json best_estimate(double D, bool determined) {
    return !determined && std::isfinite(D) ? Json(D) : Json(nullptr);
}

Json estimate_json(double D, const analysis::Interval& interval, bool determined, const std::string& note) {
    return Json{{"D", determined_value(D, determined)},
                {"D_best_estimate", best_estimate(D, determined)},
                {"D_lo", interval.lo},
                {"D_hi", interval.hi},
                {"determined", determined},
                {"note", note}};
}

Json msd_json(const analysis::MsdEstimate& m) {
    Json j = estimate_json(m.D, m.interval, m.determined, m.note);
    j["fit_lag_lo"] = m.fit_lo;
    j["fit_lag_hi"] = m.fit_hi;
    j["blocks"] = static_cast<std::int64_t>(m.blocks);
    return j;
}

}  // namespace tumble::io
