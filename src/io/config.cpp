// SPDX-License-Identifier: MIT
// The scenario reader. The format is documented key by key in
// docs/SCENARIO.md; keep the two in step.
#include "io/config.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <optional>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "io/names.hpp"
#include "io/toml_reader.hpp"
#include "io/particle_csv.hpp"
#include "io/stl.hpp"
#include "tumble/core/constants.hpp"
#include "tumble/sim/time_step.hpp"
#include "tumble/walls/wall.hpp"
#include "tumble/setup/generators.hpp"

namespace tumble::io {

namespace fs = std::filesystem;

namespace {

std::string compose(const fs::path& file, const std::string& key, const std::string& reason) {
    return key.empty() ? fmt::format("{}: {}", file.string(), reason)
                       : fmt::format("{}: {}: {}", file.string(), key, reason);
}

}  // namespace

ConfigError::ConfigError(const fs::path& file, std::string key, std::string reason)
    : tumble::Error(compose(file, key, reason)), file_(file), key_(std::move(key)), reason_(std::move(reason)) {}

namespace {

constexpr auto max_particles = static_cast<std::int64_t>(max_scenario_particles);

std::uint64_t splitmix64(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

// The seed of one random stream of one [[particles]] block: the scenario
// seed mixed with the block index and the purpose, so that blocks (and
// placement and velocities) draw independent numbers.
enum class Stream : std::uint64_t { placement = 0, velocities = 1 };
std::uint64_t block_seed(std::uint64_t seed, std::size_t block, Stream stream) {
    return splitmix64(splitmix64(seed) ^ splitmix64(2 * block + static_cast<std::uint64_t>(stream) + 1));
}

// Where each particle of the scenario came from, for messages.
struct Block {
    std::string path;  // particles[b]
    std::string kind;
    std::size_t first = 0;                // index of its first particle in Scenario::particles
    std::vector<std::size_t> csv_lines;   // csv: file line of each particle
    fs::path csv_file;
};

class ScenarioReader {
public:
    ScenarioReader(const fs::path& name, const fs::path& base_dir) : r_(name), base_dir_(base_dir) {}

    RunConfig read(const toml::table& root) {
        r_.only_keys(root, "", {"simulation", "time_step", "domain", "model", "neighbor", "material", "pair",
                                "motion", "wall", "particles", "output"});
        config_.source = r_.file();
        read_simulation(*r_.table(root, "simulation", true));
        read_materials(root);
        read_pairs(root);
        read_motions(root);
        read_domain(*r_.table(root, "domain", true));
        read_walls(root);
        read_model(r_.table(root, "model", false));
        read_time_step(r_.table(root, "time_step", false));
        read_neighbor(r_.table(root, "neighbor", false));
        read_output(r_.table(root, "output", false));
        read_particles(root);
        check_assembled();
        return std::move(config_);
    }

private:
    Scenario& s() { return config_.scenario; }

    void read_simulation(const toml::table& t) {
        const std::string p = "simulation";
        r_.only_keys(t, p, {"duration", "seed", "gravity", "max_initial_overlap"});
        config_.duration = r_.required_number(t, p, "duration", Bound::positive);
        if (const toml::node* n = t.get("seed"))
            config_.seed = static_cast<std::uint64_t>(
                r_.integer(*n, join(p, "seed"), 0, std::numeric_limits<std::int64_t>::max()));
        s().gravity = r_.vec3(t, p, "gravity").value_or(Vec3{});
        max_initial_overlap_ = r_.number(t, p, "max_initial_overlap", Bound::non_negative, 0.05);
    }

    void read_materials(const toml::table& root) {
        const auto entries = r_.tables(root, "", "material");
        if (entries.empty()) r_.fail("material", "missing: at least one [[material]] is required");
        for (std::size_t i = 0; i < entries.size(); ++i) {
            const toml::table& t = *entries[i];
            const std::string p = at("material", i);
            r_.only_keys(t, p, {"name", "E", "G", "nu", "xi", "eta", "rho", "radius"});
            Material m;
            m.name = r_.string(r_.required(t, p, "name"), join(p, "name"));
            for (std::size_t j = 0; j < i; ++j)
                if (s().materials[j].name == m.name)
                    r_.fail(join(p, "name"), fmt::format("duplicate material name \"{}\" (also material[{}])", m.name, j),
                            t.get("name"));
            m.E = r_.required_number(t, p, "E", Bound::positive);
            m.G = r_.required_number(t, p, "G", Bound::positive);
            m.nu = r_.required_number(t, p, "nu", Bound::any);
            if (!(m.nu > -1.0 && m.nu < 0.5))
                r_.fail(join(p, "nu"), "Poisson ratio must lie in (-1, 0.5), got " + show(m.nu), t.get("nu"));
            m.xi = r_.required_number(t, p, "xi", Bound::non_negative);
            m.eta = r_.required_number(t, p, "eta", Bound::non_negative);
            m.rho = r_.required_number(t, p, "rho", Bound::positive);
            m.radius = r_.required_number(t, p, "radius", Bound::positive);
            if (const std::string why = material_problem(m); !why.empty()) r_.fail(p, why, &t);
            s().materials.push_back(m);
            material_names_.push_back(m.name);
        }
    }

    std::int32_t material_index(const toml::node& n, const std::string& key) const {
        const std::string name = r_.string(n, key);
        const auto found = std::find(material_names_.begin(), material_names_.end(), name);
        if (found == material_names_.end())
            r_.fail(key,
                    "unknown material \"" + name + "\"" + detail::did_you_mean(name, material_names_) +
                        "; known materials: " + detail::quoted_list(material_names_),
                    &n);
        return static_cast<std::int32_t>(found - material_names_.begin());
    }

    std::int32_t motion_index(const toml::node& n, const std::string& key) const {
        const std::string name = r_.string(n, key);
        const auto found = std::find(motion_names_.begin(), motion_names_.end(), name);
        if (found == motion_names_.end())
            r_.fail(key,
                    "unknown motion \"" + name + "\"" + detail::did_you_mean(name, motion_names_) +
                        "; known motions: " + detail::quoted_list(motion_names_),
                    &n);
        return static_cast<std::int32_t>(found - motion_names_.begin());
    }

    void read_pairs(const toml::table& root) {
        const std::size_t n = s().materials.size();
        s().pair_properties.assign(n, std::vector<PairProperties>(n));
        std::vector<std::vector<int>> given(n, std::vector<int>(n, -1));  // which [[pair]] gave it
        const auto entries = r_.tables(root, "", "pair");
        for (std::size_t i = 0; i < entries.size(); ++i) {
            const toml::table& t = *entries[i];
            const std::string p = at("pair", i);
            r_.only_keys(t, p, {"materials", "mu", "W"});
            const std::string key = join(p, "materials");
            const toml::node& names = r_.required(t, p, "materials");
            const toml::array& a = r_.array(names, key, 2, "an array of 2 material names [\"a\", \"b\"]");
            const std::int32_t m0 = material_index(*a.get(0), at(key, 0));
            const std::int32_t m1 = material_index(*a.get(1), at(key, 1));
            if (given[m0][m1] >= 0)
                r_.fail(key,
                        fmt::format("duplicate pair \"{}\" - \"{}\" (already given by pair[{}])", material_names_[m0],
                                    material_names_[m1], given[m0][m1]),
                        &names);
            PairProperties props;
            props.mu = r_.required_number(t, p, "mu", Bound::non_negative);
            props.W = r_.required_number(t, p, "W", Bound::non_negative);
            s().pair_properties[m0][m1] = s().pair_properties[m1][m0] = props;
            given[m0][m1] = given[m1][m0] = static_cast<int>(i);
        }
        for (std::size_t a = 0; a < n; ++a)
            for (std::size_t b = a; b < n; ++b)
                if (given[a][b] < 0)
                    r_.fail("pair", fmt::format("missing [[pair]] with materials = [\"{}\", \"{}\"] (every pair of "
                                                "materials, including each with itself, needs mu and W)",
                                                material_names_[a], material_names_[b]));
    }

    void read_motions(const toml::table& root) {
        const auto entries = r_.tables(root, "", "motion");
        for (std::size_t i = 0; i < entries.size(); ++i) {
            const toml::table& t = *entries[i];
            const std::string p = at("motion", i);
            r_.only_keys(t, p, {"name", "axis_point", "axis_direction", "angular_velocity", "velocity"});
            const std::string name = r_.string(r_.required(t, p, "name"), join(p, "name"));
            for (std::size_t j = 0; j < i; ++j)
                if (motion_names_[j] == name)
                    r_.fail(join(p, "name"), fmt::format("duplicate motion name \"{}\" (also motion[{}])", name, j),
                            t.get("name"));
            RigidMotion m;
            m.axis_point = r_.vec3(t, p, "axis_point").value_or(Vec3{});
            m.axis_direction = r_.vec3(t, p, "axis_direction").value_or(Vec3{0.0, 0.0, 1.0});
            if (!(norm(m.axis_direction) > 0.0))
                r_.fail(join(p, "axis_direction"), "must not be the zero vector", t.get("axis_direction"));
            m.angular_velocity = r_.number(t, p, "angular_velocity", Bound::any, 0.0);
            m.velocity = r_.vec3(t, p, "velocity").value_or(Vec3{});
            s().motions.push_back(m);
            motion_names_.push_back(name);
        }
    }

    void read_domain(const toml::table& t) {
        const std::string p = "domain";
        r_.only_keys(t, p, {"lo", "hi", "periodic", "walls", "wall_material"});
        Domain& d = s().domain;
        d.lo = r_.required_vec3(t, p, "lo");
        d.hi = r_.required_vec3(t, p, "hi");
        for (int k = 0; k < 3; ++k)
            if (!(d.hi[k] > d.lo[k]))
                r_.fail(at(join(p, "hi"), k),
                        fmt::format("must exceed lo along {} ({} <= {})", "xyz"[k], show(d.hi[k]), show(d.lo[k])),
                        t.get("hi"));
        if (const toml::node* n = t.get("periodic")) d.periodic = r_.bool3(*n, join(p, "periodic"));
        if (const toml::node* n = t.get("walls")) d.walls = r_.bool3(*n, join(p, "walls"));
        for (int k = 0; k < 3; ++k)
            if (d.walls[k] && d.periodic[k])
                r_.fail(at(join(p, "walls"), k),
                        fmt::format("axis {} cannot be both periodic and walled", "xyz"[k]), t.get("walls"));
        const bool any_wall = d.walls[0] || d.walls[1] || d.walls[2];
        if (const toml::node* n = t.get("wall_material")) {
            d.wall_material = material_index(*n, join(p, "wall_material"));
            if (!any_wall) r_.fail(join(p, "wall_material"), "given, but no axis has walls (domain.walls)", n);
        } else if (any_wall) {
            r_.fail(join(p, "wall_material"), "missing: required when domain.walls has an axis set");
        }
    }

    // [[wall]]: an analytic wall (walls/wall.hpp). The keys that describe
    // its shape are those of the shape alone; a cylinder with `caps` gets a
    // disc at each end, "NAME.start" and "NAME.end", of `cap_material`
    // (else its own).
    void read_walls(const toml::table& root) {
        const auto entries = r_.tables(root, "", "wall");
        std::vector<std::string> names;
        for (std::size_t i = 0; i < entries.size(); ++i) {
            const toml::table& t = *entries[i];
            const std::string p = at("wall", i);
            Wall w;
            w.name = r_.string(r_.required(t, p, "name"), join(p, "name"));
            w.shape = r_.keyword(r_.required(t, p, "shape"), join(p, "shape"), wall_shapes)->value;
            const std::vector<std::string_view> common{"name", "shape", "material", "motion", "point"};
            std::vector<std::string_view> keys = common;
            switch (w.shape) {
                case WallShape::plane: keys.insert(keys.end(), {"normal"}); break;
                case WallShape::rectangle: keys.insert(keys.end(), {"normal", "edge", "size"}); break;
                case WallShape::disc: keys.insert(keys.end(), {"normal", "radius"}); break;
                case WallShape::cylinder:
                    keys.insert(keys.end(), {"axis", "radius", "length", "inside", "caps", "cap_material"});
                    break;
                case WallShape::cone: keys.insert(keys.end(), {"axis", "radius", "end_radius", "length", "inside"}); break;
                case WallShape::mesh: keys.insert(keys.end(), {"file", "scale", "rotation", "offset"}); break;
            }
            r_.only_keys(t, p, keys);
            w.material = material_index(r_.required(t, p, "material"), join(p, "material"));
            if (const toml::node* n = t.get("motion")) w.motion = motion_index(*n, join(p, "motion"));
            w.point = r_.vec3(t, p, "point").value_or(Vec3{});
            const bool revolution = w.shape == WallShape::cylinder || w.shape == WallShape::cone;
            const std::string direction = revolution ? "axis" : "normal";
            w.normal = unit(t, p, direction, Vec3{0.0, 0.0, 1.0});
            switch (w.shape) {
                case WallShape::plane: break;
                case WallShape::rectangle: {
                    const Vec3 edge = unit(t, p, "edge", Vec3{1.0, 0.0, 0.0});
                    const Vec3 in_plane = edge - dot(edge, w.normal) * w.normal;
                    if (!(norm(in_plane) > 1e-9))
                        r_.fail(join(p, "edge"), "must not be parallel to the normal", t.get("edge"));
                    w.edge = (1.0 / norm(in_plane)) * in_plane;
                    const std::string key = join(p, "size");
                    const toml::array& a = r_.array(r_.required(t, p, "size"), key, 2, "an array of 2 lengths [along edge, across]");
                    w.half_width = 0.5 * r_.number(*a.get(0), at(key, 0), Bound::positive);
                    w.half_height = 0.5 * r_.number(*a.get(1), at(key, 1), Bound::positive);
                    break;
                }
                case WallShape::disc: w.radius = r_.required_number(t, p, "radius", Bound::positive); break;
                case WallShape::cylinder:
                    w.radius = r_.required_number(t, p, "radius", Bound::positive);
                    w.length = r_.number(t, p, "length", Bound::positive, w.length);
                    break;
                case WallShape::cone:
                    w.radius = r_.required_number(t, p, "radius", Bound::non_negative);
                    w.end_radius = r_.required_number(t, p, "end_radius", Bound::non_negative);
                    w.length = r_.required_number(t, p, "length", Bound::positive);
                    break;
                case WallShape::mesh:
                    w.mesh = static_cast<std::int32_t>(s().meshes.size());
                    s().meshes.push_back(read_mesh(t, p));
                    break;
            }
            if (const toml::node* n = t.get("inside")) w.inside = r_.boolean(*n, join(p, "inside"));
            if (const std::string why = wall_problem(w); !why.empty()) r_.fail(p, why, &t);
            const bool caps = t.get("caps") && r_.boolean(*t.get("caps"), join(p, "caps"));
            if (t.get("cap_material") && !caps) r_.fail(join(p, "cap_material"), "given, but caps is not true", t.get("cap_material"));
            if (caps && std::isinf(w.length)) r_.fail(join(p, "caps"), "an infinite cylinder has no ends to cap", t.get("caps"));
            std::vector<Wall> made{w};
            if (caps) {
                Wall cap = w;
                cap.shape = WallShape::disc;
                if (const toml::node* n = t.get("cap_material")) cap.material = material_index(*n, join(p, "cap_material"));
                cap.name = w.name + ".start";
                made.push_back(cap);
                cap.name = w.name + ".end";
                cap.point = w.point + w.length * w.normal;
                made.push_back(cap);
            }
            for (const Wall& m : made) {
                if (std::find(names.begin(), names.end(), m.name) != names.end())
                    r_.fail(join(p, "name"), fmt::format("duplicate wall name \"{}\"", m.name), t.get("name"));
                names.push_back(m.name);
                s().walls.push_back(m);
            }
        }
    }

    // A mesh wall's triangles: its STL file (relative to the scenario's
    // directory), scaled, turned (rotation's angle in degrees) and moved.
    TriangleMesh read_mesh(const toml::table& t, const std::string& p) const {
        const std::string fkey = join(p, "file");
        const toml::node& n = r_.required(t, p, "file");
        const fs::path given = r_.string(n, fkey);
        const fs::path file = given.is_absolute() ? given : base_dir_ / given;
        std::error_code ec;
        if (!fs::exists(file, ec)) r_.fail(fkey, "no such file: " + file.string(), &n);
        if (!fs::is_regular_file(file, ec))
            r_.fail(fkey, "not a regular file (a device, a folder or a link to one): " + file.string(), &n);
        io::StlPlacement placement;
        placement.scale = r_.number(t, p, "scale", Bound::positive, 1.0);
        placement.offset = r_.vec3(t, p, "offset").value_or(Vec3{});
        if (const toml::node* rn = t.get("rotation")) {
            const std::string rkey = join(p, "rotation");
            const toml::table* rt = rn->as_table();
            if (!rt) r_.fail(rkey, "expected a table { axis = [x, y, z], angle = degrees }", rn);
            r_.only_keys(*rt, rkey, {"axis", "angle"});
            const Vec3 axis = unit(*rt, rkey, "axis", Vec3{0.0, 0.0, 1.0});
            const double degrees = r_.required_number(*rt, rkey, "angle", Bound::any);
            placement.rotation = io::StlRotation{axis, degrees * pi / 180.0};
        }
        try {
            return io::read_stl(file, placement);
        } catch (const ConfigError& e) {  // the STL file, and where in it
            r_.fail(fkey, e.what(), &n);
        }
    }

    // A direction at `key`, made a unit vector; it must not be zero.
    Vec3 unit(const toml::table& t, const std::string& path, const std::string& key, Vec3 fallback) const {
        const Vec3 v = r_.vec3(t, path, key).value_or(fallback);
        if (!(norm(v) > 0.0)) r_.fail(join(path, key), "must not be the zero vector", t.get(key));
        return (1.0 / norm(v)) * v;
    }

    void read_model(const toml::table* t) {
        if (!t) return;
        const std::string p = "model";
        r_.only_keys(*t, p,
                     {"elastic", "viscous", "attraction", "twisting", "shear", "friction_normal",
                      "tangential_stiffness", "slip_velocity_regularisation"});
        ContactModel& m = s().model;
        m.elastic = r_.boolean(*t, p, "elastic", true);
        m.viscous = r_.boolean(*t, p, "viscous", true);
        m.attraction = r_.boolean(*t, p, "attraction", true);
        m.twisting = r_.boolean(*t, p, "twisting", true);
        if (const toml::node* n = t->get("shear")) m.shear = r_.keyword(*n, join(p, "shear"), shear_models)->value;
        if (const toml::node* n = t->get("friction_normal"))
            m.friction_normal = r_.keyword(*n, join(p, "friction_normal"), friction_normals)->value;
        if (const toml::node* n = t->get("tangential_stiffness"))
            m.tangential_stiffness = r_.keyword(*n, join(p, "tangential_stiffness"), tangential_stiffnesses)->value;
        m.slip_velocity_regularisation =
            r_.number(*t, p, "slip_velocity_regularisation", Bound::positive, m.slip_velocity_regularisation);
    }

    void read_time_step(const toml::table* t) {
        if (!t) return;
        const std::string p = "time_step";
        r_.only_keys(*t, p, {"dt", "reference_speed", "allow_unsafe"});
        TimeStepSettings& ts = s().time_step;
        if (const toml::node* n = t->get("dt")) {
            if (const auto* text = n->as_string()) {
                if (text->get() != "auto")
                    r_.fail(join(p, "dt"), "expected \"auto\" or a time step in s, got \"" + text->get() + "\"", n);
                ts.dt = 0.0;
            } else {
                if (!n->is_number()) r_.fail(join(p, "dt"), "expected \"auto\" or a number (s), got " + type_name(*n), n);
                ts.dt = r_.number(*n, join(p, "dt"), Bound::positive);
            }
        }
        ts.reference_speed = r_.number(*t, p, "reference_speed", Bound::positive, ts.reference_speed);
        ts.allow_unsafe = r_.boolean(*t, p, "allow_unsafe", ts.allow_unsafe);
    }

    void read_neighbor(const toml::table* t) {
        if (!t) return;
        const std::string p = "neighbor";
        r_.only_keys(*t, p, {"skin", "sort_every"});
        s().neighbor.skin = r_.number(*t, p, "skin", Bound::non_negative, 0.0);
        if (const toml::node* n = t->get("sort_every"))
            s().neighbor.sort_every =
                static_cast<int>(r_.integer(*n, join(p, "sort_every"), 0, std::numeric_limits<int>::max()));
    }

    void read_output(const toml::table* t) {
        OutputSettings& o = config_.output;
        o.time_series_interval = config_.duration / 100.0;
        if (!t) return;
        const std::string p = "output";
        r_.only_keys(*t, p, {"directory", "time_series_interval", "snapshot_interval"});
        if (const toml::node* n = t->get("directory")) o.directory = r_.string(*n, join(p, "directory"));
        o.time_series_interval = r_.number(*t, p, "time_series_interval", Bound::non_negative, o.time_series_interval);
        o.snapshot_interval = r_.number(*t, p, "snapshot_interval", Bound::non_negative, 0.0);
    }

    // ---- [[particles]] ----

    // Keys every kind accepts: defaults for the block's particles.
    struct BlockDefaults {
        std::optional<std::int32_t> material;
        std::int32_t motion = free_motion;
        std::int32_t tag = 0;
        std::optional<double> speed;
        std::optional<Vec3> velocity;
        Vec3 angular_velocity;
        std::optional<double> radius;
    };

    BlockDefaults read_block_defaults(const toml::table& t, const std::string& p) const {
        BlockDefaults d;
        if (const toml::node* n = t.get("material")) d.material = material_index(*n, join(p, "material"));
        if (const toml::node* n = t.get("motion")) d.motion = motion_index(*n, join(p, "motion"));
        if (const toml::node* n = t.get("tag"))
            d.tag = static_cast<std::int32_t>(r_.integer(*n, join(p, "tag"), std::numeric_limits<std::int32_t>::min(),
                                                         std::numeric_limits<std::int32_t>::max()));
        d.speed = r_.number(t, p, "speed", Bound::non_negative);
        d.velocity = r_.vec3(t, p, "velocity");
        if (d.speed && d.velocity)
            r_.fail(join(p, "speed"), "give speed (random directions) or velocity, not both", t.get("speed"));
        d.angular_velocity = r_.vec3(t, p, "angular_velocity").value_or(Vec3{});
        d.radius = r_.number(t, p, "radius", Bound::positive);
        return d;
    }

    std::int32_t required_material(const toml::table& t, const std::string& p, const BlockDefaults& d) const {
        if (!d.material) r_.required(t, p, "material");
        return *d.material;
    }

    double default_radius(const BlockDefaults& d, std::int32_t material) const {
        return d.radius ? *d.radius : config_.scenario.materials[static_cast<std::size_t>(material)].radius;
    }

    // Motion, tag, velocities of a generated block.
    static void apply_defaults(std::vector<ParticleSpec>& block, const BlockDefaults& d) {
        for (ParticleSpec& q : block) {
            q.motion = d.motion;
            q.tag = d.tag;
            q.velocity = d.velocity.value_or(Vec3{});
            q.angular_velocity = d.angular_velocity;
        }
    }

    // Spheres that the blocks still to be read may add.
    std::int64_t room() const { return max_particles - static_cast<std::int64_t>(config_.scenario.particles.size()); }

    std::vector<ParticleSpec> read_lattice(const toml::table& t, const std::string& p, const BlockDefaults& d) const {
        const std::int32_t material = required_material(t, p, d);
        const Vec3 origin = r_.required_vec3(t, p, "origin");
        const std::string ckey = join(p, "counts");
        const toml::array& c = r_.array(r_.required(t, p, "counts"), ckey, 3, "an array of 3 positive integers [nx, ny, nz]");
        std::array<int, 3> counts{};
        std::int64_t total = 1;
        for (int k = 0; k < 3; ++k) {
            counts[k] = static_cast<int>(r_.integer(*c.get(k), at(ckey, k), 1, max_particles));
            total *= counts[k];
            if (total > room())
                r_.fail(ckey, fmt::format("more than {} spheres in the scenario", max_particles), t.get("counts"));
        }
        const double spacing = r_.required_number(t, p, "spacing", Bound::positive);
        std::vector<ParticleSpec> out = lattice(origin, counts, spacing, default_radius(d, material), material);
        apply_defaults(out, d);
        return out;
    }

    std::vector<ParticleSpec> read_random_fill(const toml::table& t, const std::string& p, const BlockDefaults& d,
                                               std::size_t block) const {
        const std::int32_t material = required_material(t, p, d);
        const Vec3 lo = r_.required_vec3(t, p, "lo");
        const Vec3 hi = r_.required_vec3(t, p, "hi");
        for (int k = 0; k < 3; ++k)
            if (!(hi[k] > lo[k]))
                r_.fail(at(join(p, "hi"), k),
                        fmt::format("must exceed lo along {} ({} <= {})", "xyz"[k], show(hi[k]), show(lo[k])),
                        t.get("hi"));
        const auto count = static_cast<std::size_t>(
            r_.integer(r_.required(t, p, "count"), join(p, "count"), 1, max_particles));
        if (static_cast<std::int64_t>(count) > room())
            r_.fail(join(p, "count"), fmt::format("more than {} spheres in the scenario", max_particles), t.get("count"));
        double radius_min = default_radius(d, material), radius_max = radius_min;
        const auto rmin = r_.number(t, p, "radius_min", Bound::positive);
        const auto rmax = r_.number(t, p, "radius_max", Bound::positive);
        if (rmin || rmax) {
            if (d.radius) r_.fail(join(p, rmin ? "radius_min" : "radius_max"), "give radius or radius_min and radius_max, not both",
                                  t.get(rmin ? "radius_min" : "radius_max"));
            if (!rmin) r_.required(t, p, "radius_min");
            if (!rmax) r_.required(t, p, "radius_max");
            if (*rmax < *rmin)
                r_.fail(join(p, "radius_max"), fmt::format("must be >= radius_min = {}, got {}", show(*rmin), show(*rmax)),
                        t.get("radius_max"));
            radius_min = *rmin;
            radius_max = *rmax;
        }
        // Random sequential placement jams near a volume fraction of 0.38;
        // refuse at once what cannot fit instead of trying for minutes.
        const Vec3 size = hi - lo;
        const double fraction = static_cast<double>(count) * 4.0 / 3.0 * 3.141592653589793 * radius_min * radius_min *
                                radius_min / (size.x * size.y * size.z);
        if (fraction > 0.5)
            r_.fail(join(p, "count"),
                    fmt::format("{} spheres of radius >= {} m would fill {:.2g} of the region's volume; random placement "
                                "cannot exceed about 0.38 (enlarge the region or ask for fewer)",
                                count, show(radius_min), fraction),
                    t.get("count"));
        std::vector<ParticleSpec> out;
        try {
            out = random_fill(lo, hi, count, radius_min, radius_max, material,
                              block_seed(config_.seed, block, Stream::placement), config_.scenario.particles);
        } catch (const ConfigError&) {
            throw;
        } catch (const tumble::Error& e) {
            r_.fail(p, e.what(), &t);
        }
        apply_defaults(out, d);
        return out;
    }

    std::vector<ParticleSpec> read_list(const toml::table& t, const std::string& p, const BlockDefaults& d) const {
        const std::string lkey = join(p, "particles");
        r_.required(t, p, "particles");
        const auto entries = r_.tables(t, p, "particles");
        if (entries.empty()) r_.fail(lkey, "the list is empty", t.get("particles"));
        std::vector<ParticleSpec> out;
        for (std::size_t i = 0; i < entries.size(); ++i) {
            const toml::table& e = *entries[i];
            const std::string ep = at(lkey, i);
            r_.only_keys(e, ep, {"position", "velocity", "angular_velocity", "radius", "material", "motion", "tag"});
            ParticleSpec q;
            q.position = r_.required_vec3(e, ep, "position");
            if (const toml::node* n = e.get("material"))
                q.material = material_index(*n, join(ep, "material"));
            else if (d.material)
                q.material = *d.material;
            else
                r_.fail(join(ep, "material"), "missing: give it here or as the block's material", &e);
            q.velocity = d.velocity.value_or(Vec3{});
            if (const auto v = r_.vec3(e, ep, "velocity")) {
                if (d.speed)
                    r_.fail(join(ep, "velocity"), "conflicts with the block's speed (random directions)",
                            e.get("velocity"));
                q.velocity = *v;
            }
            q.angular_velocity = r_.vec3(e, ep, "angular_velocity").value_or(d.angular_velocity);
            q.radius = r_.number(e, ep, "radius", Bound::positive).value_or(default_radius(d, q.material));
            q.motion = d.motion;
            if (const toml::node* n = e.get("motion")) q.motion = motion_index(*n, join(ep, "motion"));
            q.tag = d.tag;
            if (const toml::node* n = e.get("tag"))
                q.tag = static_cast<std::int32_t>(r_.integer(*n, join(ep, "tag"), std::numeric_limits<std::int32_t>::min(),
                                                             std::numeric_limits<std::int32_t>::max()));
            out.push_back(q);
        }
        return out;
    }

    std::vector<ParticleSpec> read_csv(const toml::table& t, const std::string& p, const BlockDefaults& d,
                                       Block& info) const {
        const std::string fkey = join(p, "file");
        const toml::node& n = r_.required(t, p, "file");
        const fs::path given = r_.string(n, fkey);
        const fs::path file = given.is_absolute() ? given : base_dir_ / given;
        std::error_code ec;
        if (!fs::exists(file, ec)) r_.fail(fkey, "no such file: " + file.string(), &n);
        if (!fs::is_regular_file(file, ec))
            r_.fail(fkey, "not a regular file (a device, a folder or a link to one): " + file.string(), &n);
        if (fs::file_size(file, ec) > max_input_file_bytes)
            r_.fail(fkey, fmt::format("{}: larger than {} MiB: not an input file of tumble", file.string(),
                                      max_input_file_bytes >> 20),
                    &n);
        CsvDefaults defaults;
        defaults.material = d.material;
        defaults.motion = d.motion;
        defaults.tag = d.tag;
        defaults.velocity = d.velocity.value_or(Vec3{});
        defaults.angular_velocity = d.angular_velocity;
        defaults.radius = d.radius;
        info.csv_file = file;
        return read_particle_csv(file, config_.scenario.materials, motion_names_, defaults, &info.csv_lines);
    }

    void read_particles(const toml::table& root) {
        const auto entries = r_.tables(root, "", "particles");
        if (entries.empty()) r_.fail("particles", "missing: at least one [[particles]] block is required");
        static const std::vector<std::string> kinds{"lattice", "random_fill", "list", "csv"};
        for (std::size_t b = 0; b < entries.size(); ++b) {
            const toml::table& t = *entries[b];
            const std::string p = at("particles", b);
            Block info;
            info.path = p;
            info.first = s().particles.size();
            info.kind = r_.string(r_.required(t, p, "kind"), join(p, "kind"));
            const auto common = {"kind", "material", "motion", "tag", "speed", "velocity", "angular_velocity", "radius"};
            auto keys = [&](std::initializer_list<std::string_view> more) {
                std::vector<std::string_view> all(common.begin(), common.end());
                all.insert(all.end(), more.begin(), more.end());
                return all;
            };
            std::vector<std::string_view> known;
            if (info.kind == "lattice") known = keys({"origin", "counts", "spacing"});
            else if (info.kind == "random_fill") known = keys({"lo", "hi", "count", "radius_min", "radius_max"});
            else if (info.kind == "list") known = keys({"particles"});
            else if (info.kind == "csv") known = keys({"file"});
            else
                r_.fail(join(p, "kind"),
                        "unknown kind \"" + info.kind + "\"" + detail::did_you_mean(info.kind, kinds) +
                            "; known kinds: " + detail::quoted_list(kinds),
                        t.get("kind"));
            r_.only_keys(t, p, known);
            const BlockDefaults d = read_block_defaults(t, p);

            std::vector<ParticleSpec> block;
            if (info.kind == "lattice") block = read_lattice(t, p, d);
            else if (info.kind == "random_fill") block = read_random_fill(t, p, d, b);
            else if (info.kind == "list") block = read_list(t, p, d);
            else block = read_csv(t, p, d, info);

            if (static_cast<std::int64_t>(block.size()) > room())
                r_.fail(p, fmt::format("more than {} spheres in the scenario", max_particles));
            if (d.speed) randomize_velocities(block, *d.speed, block_seed(config_.seed, b, Stream::velocities));
            s().particles.insert(s().particles.end(), block.begin(), block.end());
            blocks_.push_back(std::move(info));
        }
    }

    // ---- checks on the whole scenario ----

    const Block& block_of(std::size_t particle) const {
        auto it = std::upper_bound(blocks_.begin(), blocks_.end(), particle,
                                   [](std::size_t i, const Block& b) { return i < b.first; });
        return *(it - 1);
    }

    // Key path of a particle: the list entry, or the block.
    std::string key_of(std::size_t particle) const {
        const Block& b = block_of(particle);
        const std::size_t k = particle - b.first;
        return b.kind == "list" ? at(join(b.path, "particles"), k) : b.path;
    }

    // A particle as a user can find it.
    std::string describe(std::size_t particle) const {
        const Block& b = block_of(particle);
        const std::size_t k = particle - b.first;
        const Vec3& x = s_const().particles[particle].position;
        const std::string where = fmt::format("at ({}, {}, {})", show(x.x), show(x.y), show(x.z));
        if (b.kind == "list") return fmt::format("{}.particles[{}] {}", b.path, k, where);
        if (b.kind == "csv") return fmt::format("{} ({} line {}) {}", b.path, b.csv_file.string(), b.csv_lines[k], where);
        return fmt::format("{} sphere {} {}", b.path, k, where);
    }

    // The same, for a message whose key is key_of(particle).
    std::string describe_under_key(std::size_t particle) const {
        const Block& b = block_of(particle);
        const std::size_t k = particle - b.first;
        const Vec3& x = s_const().particles[particle].position;
        const std::string where = fmt::format("at ({}, {}, {})", show(x.x), show(x.y), show(x.z));
        if (b.kind == "list") return "the particle " + where;
        if (b.kind == "csv") return fmt::format("the particle of {} line {} {}", b.csv_file.string(), b.csv_lines[k], where);
        return fmt::format("sphere {} {}", k, where);
    }

    const Scenario& s_const() const { return config_.scenario; }

    void check_assembled() {
        const Scenario& sc = s_const();
        const Domain& d = sc.domain;
        for (std::size_t i = 0; i < sc.particles.size(); ++i) {
            const ParticleSpec& q = sc.particles[i];
            for (int k = 0; k < 3; ++k) {
                // Periodic and walled axes hold [lo, hi); on open axes the
                // box only bounds where particles start, [lo, hi].
                const bool bounded = d.periodic[k] || d.walls[k];
                const bool inside = q.position[k] >= d.lo[k] && (bounded ? q.position[k] < d.hi[k] : q.position[k] <= d.hi[k]);
                if (inside) continue;
                r_.fail(key_of(i), fmt::format("{} lies outside the domain along the {} axis {}: [{}, {}{}",
                                               describe_under_key(i), d.periodic[k] ? "periodic" : d.walls[k] ? "walled" : "open",
                                               "xyz"[k], show(d.lo[k]), show(d.hi[k]), bounded ? ")" : "]"));
            }
        }

        OverlapReport worst;
        try {
            worst = largest_overlap(sc);
        } catch (const tumble::Error& e) {
            r_.fail("domain", e.what());
        }
        if (worst.ratio > max_initial_overlap_)
            r_.fail(key_of(worst.b),
                    fmt::format("{} overlaps {} by {:.3g} of the smaller radius, more than "
                                "simulation.max_initial_overlap = {}",
                                describe_under_key(worst.b), describe(worst.a), worst.ratio, show(max_initial_overlap_)));

        if (const std::string why = scenario_problem(sc); !why.empty()) r_.fail("scenario", why);
        try {
            (void)assess_time_step(sc);
        } catch (const tumble::Error& e) {
            r_.fail(sc.time_step.dt > 0.0 ? "time_step.dt" : "time_step", e.what());
        }
    }

    Reader r_;
    fs::path base_dir_;
    RunConfig config_;
    double max_initial_overlap_ = 0.05;
    std::vector<std::string> material_names_;
    std::vector<std::string> motion_names_;
    std::vector<Block> blocks_;
};

}  // namespace

RunConfig read_run_config(const toml::table& root, const fs::path& name, const fs::path& base_dir) {
    return ScenarioReader(name, base_dir).read(root);
}

RunConfig parse_run_config(std::string_view toml_text, const fs::path& name, const fs::path& base_dir) {
    return read_run_config(parse_toml(toml_text, name), name, base_dir);
}

RunConfig load_run_config(const fs::path& file) {
    fs::path base = file.parent_path();
    if (base.empty()) base = ".";
    return parse_run_config(read_text_file(file), file, base);
}

}  // namespace tumble::io
