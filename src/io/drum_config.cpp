// SPDX-License-Identifier: MIT
#include "io/drum_config.hpp"

#include <algorithm>
#include <cmath>

#include "io/material_tables.hpp"
#include "io/stl.hpp"
#include "io/toml_reader.hpp"
#include "tumble/core/constants.hpp"
#include "tumble/setup/paper_materials.hpp"

namespace tumble::io {

namespace {
constexpr double g = 9.81;  // m/s^2, as the drum's gravity
}

double DrumSettings::omega() const {
    switch (speed_unit) {
        case SpeedUnit::rpm: return speed * 2.0 * pi / 60.0;
        case SpeedUnit::froude: return std::sqrt(speed * g / (0.5 * geometry.diameter));
        case SpeedUnit::rad_per_s: break;
    }
    return speed;
}

std::size_t DrumSettings::grain_count() const {
    if (!(fill_fraction > 0.0)) return grains;
    constexpr double packing = 0.6;
    const double R = 0.5 * geometry.diameter;
    const double solid = packing * fill_fraction * pi * R * R * geometry.length;  // m^3 of grains
    const auto volume = [](double r) { return 4.0 / 3.0 * pi * r * r * r; };
    const auto radius = [&](std::int32_t m) {
        return m >= 0 && static_cast<std::size_t>(m) < materials.materials.size() ? materials.materials[m].radius : 0.0;
    };
    const double R1 = radius(materials.large), R2 = radius(materials.small);
    if (!(R1 > 0.0)) return grains;  // refused by check_drum_settings
    if (mode == "self") return static_cast<std::size_t>(std::llround(solid / volume(R1)));
    if (!(R2 > 0.0)) return grains;
    // Equal masses of the paper's grains (same density) are half the volume
    // in each material; by default the grains' volume is shared as equal
    // masses share it.
    const Material* m1 = &materials.materials[materials.large];
    const Material* m2 = &materials.materials[materials.small];
    const double small =
        fill.small_volume_fraction.value_or(m2->rho > 0.0 && m1->rho > 0.0 ? m1->rho / (m1->rho + m2->rho) : 0.5);
    return static_cast<std::size_t>(std::llround((1.0 - small) * solid / volume(R1)) +
                                    std::llround(small * solid / volume(R2)));
}

std::optional<double> DrumSettings::uniform_surface_energy() const {
    if (surface_energy) return surface_energy;
    std::vector<std::int32_t> used;
    for (const std::int32_t m : {materials.large, materials.small, materials.wall, materials.cap})
        if (m >= 0 && static_cast<std::size_t>(m) < materials.materials.size()) used.push_back(m);
    std::optional<double> W;
    for (const std::int32_t a : {materials.large, materials.small})  // the pairs that touch: a grain and anything
        for (const std::int32_t b : used) {
            if (a < 0 || static_cast<std::size_t>(a) >= materials.materials.size()) continue;
            const double w = materials.pair_properties.at(a).at(b).W;
            if (W && *W != w) return std::nullopt;
            W = w;
        }
    return W;
}

void check_drum_settings(const DrumSettings& s, const std::string& source) {
    auto fail = [&](const char* key, const std::string& reason) { throw ConfigError(source, key, reason); };
    if (s.mode != "two-component" && s.mode != "self")
        fail("mode", "must be \"two-component\" or \"self\", got \"" + s.mode + "\"");
    if (!(s.speed > 0.0) || !std::isfinite(s.speed))
        fail("speed", "the rotation speed must be > 0, got " + show(s.speed));
    if (!(s.revolutions > 0.0) || !std::isfinite(s.revolutions))
        fail("revolutions", "must be > 0, got " + show(s.revolutions));
    if (!(s.until_band_change >= 0.0 && s.until_band_change < s.revolutions))
        fail("until_band_change",
             "must be >= 0 (0: off) and below revolutions (" + show(s.revolutions) + "), got " + show(s.until_band_change));
    if (s.grains < 2) fail("grains", "need at least 2 grains");
    if (!(s.fill_fraction >= 0.0 && s.fill_fraction <= 1.0))
        fail("fill_fraction", "must lie in (0, 1], got " + show(s.fill_fraction));
    if (s.grains > 10'000'000) fail("grains", "at most 10^7 grains");
    if (s.samples_per_revolution < 1) fail("samples_per_revolution", "must be >= 1");
    if (s.profile_bins < 2) fail("profile_bins", "must be >= 2");
    if (s.band_bins != 0 && (s.band_bins < 2 || s.band_bins > 100000))
        fail("band_bins", "must lie in 2 .. 100000 (0: the default, L / 4 mm), got " + std::to_string(s.band_bins));
    if (s.snapshots_per_revolution < 0) fail("snapshots_per_revolution", "must be >= 0 (0: none)");
    if (!(s.settle_speed > 0.0)) fail("settle_speed", "must be > 0");
    if (!(s.settle_max_time > 0.0)) fail("settle_max_time", "must be > 0");
    if (!(s.dt >= 0.0)) fail("dt", "must be >= 0 (0: automatic)");
    if (!(s.spin_up_time >= 0.0) || !std::isfinite(s.spin_up_time)) fail("spin_up_time", "must be >= 0 s (0: none)");
    for (auto [key, value] : {std::pair{"length", s.geometry.length}, std::pair{"diameter", s.geometry.diameter},
                              std::pair{"wall_radius", s.geometry.wall_radius}})
        if (!(value > 0.0) || !std::isfinite(value)) fail(key, "must be > 0, got " + show(value));
    if (s.geometry.walls == DrumWalls::mesh && s.geometry.periodic_axis)
        fail("periodic_axis", "a mesh mantle has ends: it needs the drum's caps, not a periodic axis (--periodic-axis)");
    if (!(s.skin >= 0.0 && s.skin < s.geometry.diameter))
        fail("neighbor.skin", "must be >= 0 m (0: automatic, 0.3 x the largest radius) and below the drum's diameter (" +
                                  show(s.geometry.diameter) + " m), got " + show(s.skin) + " (--skin)");
    if (s.surface_energy && (!(*s.surface_energy >= 0.0) || !std::isfinite(*s.surface_energy)))
        fail("model.surface_energy",
             "must be >= 0 J/m^2 (0: no attraction), got " + show(*s.surface_energy) + " (--surface-energy)");
    if (const auto problem = drum_materials_problem(s.materials, s.mode, s.geometry.periodic_axis))
        throw ConfigError(source, "materials." + problem->key, problem->reason);
    if (const auto problem = drum_fill_problem(s.geometry, s.mode, s.fill, s.materials)) {
        std::string option = problem->key;
        std::replace(option.begin(), option.end(), '_', '-');
        throw ConfigError(source, problem->key, problem->reason + " (tumble drum --" + option + ")");
    }
}

void load_drum_mantle(DrumSettings& s, const std::string& source, const std::string& key) {
    s.geometry.mantle.reset();
    if (s.mesh.empty()) return;
    if (s.geometry.walls == DrumWalls::particles) s.geometry.walls = DrumWalls::mesh;
    if (s.geometry.walls != DrumWalls::mesh)
        throw ConfigError(source, key, "a mantle mesh needs walls = \"mesh\", not \"" +
                                           std::string(keyword_of(drum_wall_kinds, s.geometry.walls)) + "\"");
    if (s.geometry.periodic_axis)
        throw ConfigError(source, key, "a mantle mesh has ends: it needs the drum's caps, not a periodic axis");
    if (!(s.mesh_scale > 0.0) || !std::isfinite(s.mesh_scale))
        throw ConfigError(source, key == "--mesh" ? "--mesh-scale" : "drum.mesh_scale",
                          "must be > 0 (the file's unit in m), got " + show(s.mesh_scale));
    StlPlacement placement;
    placement.scale = s.mesh_scale;
    try {
        s.geometry.mantle = std::make_shared<const TriangleMesh>(read_stl(s.mesh, placement));
    } catch (const Error& e) {
        throw ConfigError(source, key, e.what());
    }
}

namespace {

// [[material]], [[pair]] and [materials]: the drum's own materials and
// which is which (the roles of DrumMaterials); without them the paper's.
void read_drum_materials(const Reader& r, const toml::table& root, DrumSettings& s) {
    const MaterialTables tables = read_material_tables(r, root, false);
    const toml::table* roles = r.table(root, "materials", false);
    if (!roles) {
        if (!tables.materials.empty())
            r.fail("materials",
                   "missing: with [[material]] tables, say which material is which: [materials] with large, small "
                   "and wall (and cap, if the caps have their own) naming them");
        return;
    }
    if (tables.materials.empty())
        r.fail("materials", "given, but no [[material]] table defines a material (the paper's drum needs neither)",
               roles);
    r.only_keys(*roles, "materials", {"large", "small", "wall", "cap"});
    DrumMaterials m;
    m.paper = false;
    m.materials = tables.materials;
    m.pair_properties = tables.pair_properties;
    m.large = tables.index(r, r.required(*roles, "materials", "large"), "materials.large");
    m.wall = tables.index(r, r.required(*roles, "materials", "wall"), "materials.wall");
    m.small = roles->get("small") ? tables.index(r, *roles->get("small"), "materials.small") : -1;
    m.cap = roles->get("cap") ? tables.index(r, *roles->get("cap"), "materials.cap") : -1;
    s.materials = std::move(m);
}

}  // namespace

DrumSettings load_drum_settings(const std::filesystem::path& file) {
    return read_drum_settings(parse_toml(read_text_file(file), file), file);
}

DrumSettings read_drum_settings(const toml::table& root, const std::filesystem::path& file) {
    const Reader r(file);
    DrumSettings s;
    r.only_keys(root, "", {"drum", "fill", "rotation", "measure", "settle", "time_step", "neighbor", "model", "output",
                           "material", "pair", "materials"});
    read_drum_materials(r, root, s);
    if (const toml::table* t = r.table(root, "drum", false)) {
        r.only_keys(*t, "drum",
                    {"length", "diameter", "wall_radius", "periodic_axis", "cap_friction", "walls", "mesh", "mesh_scale"});
        if (const toml::node* n = t->get("walls")) s.geometry.walls = r.keyword(*n, "drum.walls", drum_wall_kinds)->value;
        if (auto mu = r.number(*t, "drum", "cap_friction", Bound::non_negative)) s.fill.cap_friction = *mu;
        if (const toml::node* n = t->get("periodic_axis"))
            s.geometry.periodic_axis = r.boolean(*n, "drum.periodic_axis");
        s.geometry.length = r.number(*t, "drum", "length", Bound::positive, s.geometry.length);
        s.geometry.diameter = r.number(*t, "drum", "diameter", Bound::positive, s.geometry.diameter);
        s.geometry.wall_radius = r.number(*t, "drum", "wall_radius", Bound::positive, s.geometry.wall_radius);
        s.mesh_scale = r.number(*t, "drum", "mesh_scale", Bound::positive, s.mesh_scale);
        if (const toml::node* n = t->get("mesh")) {  // beside the drum file, as a scenario's STL files
            const std::filesystem::path given = r.string(*n, "drum.mesh");
            s.mesh = given.is_absolute() ? given : std::filesystem::absolute(file).parent_path() / given;
            load_drum_mantle(s, file.string(), "drum.mesh");
        }
    }
    if (const toml::table* t = r.table(root, "fill", false)) {
        r.only_keys(*t, "fill", {"mode", "grains", "fill_fraction", "seed", "arrangement", "bands", "band_widths",
                                 "boundaries", "ends", "small_volume_fraction"});
        if (const toml::node* n = t->get("arrangement"))
            s.fill.arrangement = r.keyword(*n, "fill.arrangement", arrangements)->value;
        if (const toml::node* n = t->get("bands")) s.fill.bands = static_cast<int>(r.integer(*n, "fill.bands", 2, 100000));
        if (const toml::node* n = t->get("band_widths")) s.fill.band_widths = r.numbers(*n, "fill.band_widths");
        if (const toml::node* n = t->get("boundaries")) s.fill.boundaries = r.numbers(*n, "fill.boundaries");
        if (const toml::node* n = t->get("ends")) s.fill.ends = r.keyword(*n, "fill.ends", species_names)->value;
        if (auto f = r.number(*t, "fill", "small_volume_fraction", Bound::positive)) s.fill.small_volume_fraction = *f;
        if (t->get("grains") && t->get("fill_fraction"))
            r.fail("fill", "give either grains or fill_fraction, not both", t);
        if (auto f = r.number(*t, "fill", "fill_fraction", Bound::positive)) {
            if (*f > 1.0) r.fail("fill.fill_fraction", "must lie in (0, 1], got " + show(*f), t->get("fill_fraction"));
            s.fill_fraction = *f;
        }
        if (const toml::node* n = t->get("mode")) s.mode = r.string(*n, "fill.mode");
        if (const toml::node* n = t->get("grains"))
            s.grains = static_cast<std::size_t>(r.integer(*n, "fill.grains", 2, 10'000'000));
        if (const toml::node* n = t->get("seed"))
            s.seed = static_cast<std::uint64_t>(r.integer(*n, "fill.seed", 0, INT64_MAX));
    }
    if (const toml::table* t = r.table(root, "rotation", false)) {
        r.only_keys(*t, "rotation", {"omega", "rpm", "froude", "revolutions", "spin_up_time", "until_band_change"});
        s.spin_up_time = r.number(*t, "rotation", "spin_up_time", Bound::non_negative, s.spin_up_time);
        int given = 0;
        for (auto [key, unit] : {std::pair{"omega", SpeedUnit::rad_per_s}, std::pair{"rpm", SpeedUnit::rpm},
                                 std::pair{"froude", SpeedUnit::froude}})
            if (auto v = r.number(*t, "rotation", key, Bound::positive)) {
                s.speed = *v;
                s.speed_unit = unit;
                ++given;
            }
        if (given > 1) r.fail("rotation", "give the speed once: omega (rad/s), rpm or froude");
        s.revolutions = r.number(*t, "rotation", "revolutions", Bound::positive, s.revolutions);
        s.until_band_change = r.number(*t, "rotation", "until_band_change", Bound::non_negative, s.until_band_change);
    }
    if (const toml::table* t = r.table(root, "measure", false)) {
        r.only_keys(*t, "measure", {"samples_per_revolution", "profile_bins", "band_bins", "snapshots_per_revolution"});
        if (const toml::node* n = t->get("snapshots_per_revolution"))
            s.snapshots_per_revolution = static_cast<int>(r.integer(*n, "measure.snapshots_per_revolution", 0, 100000));
        if (const toml::node* n = t->get("samples_per_revolution"))
            s.samples_per_revolution = static_cast<int>(r.integer(*n, "measure.samples_per_revolution", 1, 100000));
        if (const toml::node* n = t->get("profile_bins"))
            s.profile_bins = static_cast<int>(r.integer(*n, "measure.profile_bins", 2, 10000));
        if (const toml::node* n = t->get("band_bins"))
            s.band_bins = static_cast<int>(r.integer(*n, "measure.band_bins", 0, 100000));
    }
    if (const toml::table* t = r.table(root, "settle", false)) {
        r.only_keys(*t, "settle", {"speed", "max_time"});
        s.settle_speed = r.number(*t, "settle", "speed", Bound::positive, s.settle_speed);
        s.settle_max_time = r.number(*t, "settle", "max_time", Bound::positive, s.settle_max_time);
    }
    if (const toml::table* t = r.table(root, "time_step", false)) {
        r.only_keys(*t, "time_step", {"dt"});
        s.dt = r.number(*t, "time_step", "dt", Bound::positive, 0.0);
    }
    if (const toml::table* t = r.table(root, "neighbor", false)) {
        r.only_keys(*t, "neighbor", {"skin"});
        s.skin = r.number(*t, "neighbor", "skin", Bound::non_negative, 0.0);
    }
    if (const toml::table* t = r.table(root, "model", false)) {
        r.only_keys(*t, "model", {"shear", "friction_normal", "tangential_stiffness", "surface_energy"});
        if (const toml::node* n = t->get("shear")) s.shear = r.keyword(*n, "model.shear", shear_models)->value;
        if (const toml::node* n = t->get("friction_normal"))
            s.friction_normal = r.keyword(*n, "model.friction_normal", friction_normals)->value;
        if (const toml::node* n = t->get("tangential_stiffness"))
            s.tangential_stiffness = r.keyword(*n, "model.tangential_stiffness", tangential_stiffnesses)->value;
        if (auto W = r.number(*t, "model", "surface_energy", Bound::non_negative)) s.surface_energy = *W;
    }
    if (const toml::table* t = r.table(root, "output", false)) {
        r.only_keys(*t, "output", {"directory"});
        if (const toml::node* n = t->get("directory")) s.output = r.string(*n, "output.directory");
    }
    check_drum_settings(s, file.string());
    return s;
}

}  // namespace tumble::io
