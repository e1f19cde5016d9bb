// SPDX-License-Identifier: MIT
// The scenario reader. The format is documented key by key in
// docs/SCENARIO.md; keep the two in step.
#include "io/config.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <limits>
#include <optional>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "io/material_tables.hpp"
#include "io/names.hpp"
#include "io/toml_reader.hpp"
#include "io/particle_csv.hpp"
#include "io/stl.hpp"
#include "tumble/core/constants.hpp"
#include "tumble/sim/health.hpp"
#include "tumble/sim/placement.hpp"
#include "tumble/sim/time_step.hpp"
#include "tumble/walls/clearance.hpp"
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
    ScenarioReader(const fs::path& name, const fs::path& base_dir, ParticleCheck check)
        : r_(name), base_dir_(base_dir), check_(std::move(check)) {}

    RunConfig read(const toml::table& root) {
        r_.only_keys(root, "", {"simulation", "time_step", "domain", "model", "neighbor", "material", "pair",
                                "motion", "wall", "particles", "insert", "output", "fields"});
        config_.source = r_.file();
        read_simulation(*r_.table(root, "simulation", true));
        read_materials(root);
        read_motions(root);
        read_domain(*r_.table(root, "domain", true));
        read_walls(root);
        read_model(r_.table(root, "model", false));
        read_time_step(r_.table(root, "time_step", false));
        read_neighbor(r_.table(root, "neighbor", false));
        read_output(r_.table(root, "output", false));
        read_fields(r_.table(root, "fields", false));
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
        // A start the run's own blow-up check would stop at (its overlaps
        // relax within a few steps, between two checks: the outcome would
        // depend on where the checks fall).
        const double blow_up = HealthLimits{}.max_overlap_ratio;
        if (max_initial_overlap_ > blow_up)
            r_.fail(join(p, "max_initial_overlap"),
                    fmt::format("must be at most {}, the overlap at which the blow-up check stops a run, got {}",
                                show(blow_up), show(max_initial_overlap_)),
                    t.get("max_initial_overlap"));
    }

    // [[material]] and [[pair]] (material_tables.hpp, shared with the drum reader).
    void read_materials(const toml::table& root) {
        materials_ = read_material_tables(r_, root, true);
        s().materials = materials_.materials;
        s().pair_properties = materials_.pair_properties;
    }

    std::int32_t material_index(const toml::node& n, const std::string& key) const {
        return materials_.index(r_, n, key);
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
            if (!std::isfinite(norm(m.axis_direction)))
                r_.fail(join(p, "axis_direction"),
                        "its length overflows; it need not be normalised ([1, 1, 0] is the axis of [1e308, 1e308, 0])",
                        t.get("axis_direction"));
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
        for (int k = 0; k < 3; ++k) {
            if (!(d.hi[k] > d.lo[k]))
                r_.fail(at(join(p, "hi"), k),
                        fmt::format("must exceed lo along {} ({} <= {})", "xyz"[k], show(d.hi[k]), show(d.lo[k])),
                        t.get("hi"));
            if (!std::isfinite(d.hi[k] - d.lo[k]))
                r_.fail(at(join(p, "hi"), k),
                        fmt::format("the box's length along {}, hi - lo = {} - ({}), overflows", "xyz"[k],
                                    show(d.hi[k]), show(d.lo[k])),
                        t.get("hi"));
        }
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
                case WallShape::disc: keys.insert(keys.end(), {"normal", "radius", "hole_radius"}); break;
                case WallShape::cylinder:
                    keys.insert(keys.end(), {"axis", "radius", "length", "inside", "caps", "cap_material"});
                    break;
                case WallShape::cone: keys.insert(keys.end(), {"axis", "radius", "end_radius", "length", "inside"}); break;
                case WallShape::mesh: keys.insert(keys.end(), {"file", "scale", "rotation", "offset", "inside"}); break;
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
                case WallShape::disc:
                    w.radius = r_.required_number(t, p, "radius", Bound::positive);
                    w.hole_radius = r_.number(t, p, "hole_radius", Bound::non_negative, 0.0);
                    break;
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
            if (const toml::node* n = t.get("inside")) {
                w.inside = r_.boolean(*n, join(p, "inside"));
                if (w.shape == WallShape::mesh) {
                    w.sided = true;
                    const std::string why = closed_surface_problem(MeshTopology(s().meshes.back()));
                    if (!why.empty()) r_.fail(join(p, "inside"), "a mesh has an inside only if it is closed: " + why, n);
                }
            }
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

    // [fields]: the values as text, checked with the command line's (RunConfig::fields).
    void read_fields(const toml::table* t) {
        if (!t) return;
        r_.only_keys(*t, "fields", std::vector<std::string_view>(std::begin(field_keys), std::end(field_keys)));
        for (const auto& [name, node] : *t) {
            const std::string key = join("fields", name.str());
            std::string value;
            if (node.is_string()) value = r_.string(node, key);
            else if (node.is_array())
                for (const double x : r_.numbers(node, key)) value += fmt::format("{}{}", value.empty() ? "" : ",", x);
            else value = fmt::format("{}", r_.number(node, key));
            config_.fields.push_back(std::string(name.str()) + "=" + value);
        }
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

    // A [[particles]] block read and checked, its spheres not yet made: how
    // many it makes and of which radii, from its keys. A list's and a CSV
    // file's particles are read already; a generator runs in make().
    struct PlannedBlock {
        Block info;
        BlockDefaults defaults;
        std::size_t count = 0;
        std::string count_key;  // the key that sets the count
        double smallest_radius = 0.0, largest_radius = 0.0;
        std::vector<ParticleSpec> particles;                   // a list's or a CSV file's
        std::function<std::vector<ParticleSpec>()> make;       // a generator's
        bool poured = false;                                   // an [[insert]]'s: counted, made while the run goes
    };

    // Spheres that the blocks still to be read may add.
    std::int64_t room() const { return max_particles - static_cast<std::int64_t>(planned_); }

    // The scenario's walls, meshes included, for placing spheres of radius
    // up to `reach` clear of them (none without walls).
    std::optional<WallDistances> wall_distances(double reach) const {
        if (s_const().walls.empty()) return std::nullopt;
        return std::optional<WallDistances>(std::in_place, s_const().walls, s_const().meshes, reach);
    }

    void plan_lattice(const toml::table& t, const std::string& p, PlannedBlock& plan) const {
        const BlockDefaults& d = plan.defaults;
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
        const double radius = default_radius(d, material);
        plan.count = static_cast<std::size_t>(total);
        plan.count_key = ckey;
        plan.smallest_radius = plan.largest_radius = radius;
        plan.make = [this, &t, p, origin, counts, spacing, radius, material, d] {
            const std::optional<WallDistances> walls = wall_distances(radius);
            std::vector<ParticleSpec> out = lattice(origin, counts, spacing, radius, material, walls ? &*walls : nullptr);
            if (out.empty()) r_.fail(p, "every site of the lattice touches or lies beyond a [[wall]]", &t);
            apply_defaults(out, d);
            return out;
        };
    }

    // The region, material and radii of a random fill or an insertion.
    struct RandomRegion {
        Vec3 lo, hi;
        std::int32_t material = 0;
        double radius_min = 0.0, radius_max = 0.0;
    };

    RandomRegion read_random_region(const toml::table& t, const std::string& p, const BlockDefaults& d) const {
        RandomRegion g;
        g.material = required_material(t, p, d);
        g.lo = r_.required_vec3(t, p, "lo");
        g.hi = r_.required_vec3(t, p, "hi");
        for (int k = 0; k < 3; ++k)
            if (!(g.hi[k] > g.lo[k]))
                r_.fail(at(join(p, "hi"), k),
                        fmt::format("must exceed lo along {} ({} <= {})", "xyz"[k], show(g.hi[k]), show(g.lo[k])),
                        t.get("hi"));
        g.radius_min = g.radius_max = default_radius(d, g.material);
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
            g.radius_min = *rmin;
            g.radius_max = *rmax;
        }
        return g;
    }

    // Random sequential placement jams near a volume fraction of 0.38;
    // refuse at once what cannot fit instead of trying for minutes.
    void refuse_overfull(const toml::table& t, const std::string& p, const std::string& key, std::size_t count,
                         const RandomRegion& g) const {
        const Vec3 size = g.hi - g.lo;
        const double fraction = static_cast<double>(count) * 4.0 / 3.0 * pi * g.radius_min * g.radius_min *
                                g.radius_min / (size.x * size.y * size.z);
        if (fraction > 0.5)
            r_.fail(join(p, key),
                    fmt::format("{} spheres of radius >= {} m would fill {:.2g} of the region's volume; random placement "
                                "cannot exceed about 0.38 (enlarge the region or ask for fewer)",
                                count, show(g.radius_min), fraction),
                    t.get(key));
    }

    void plan_random_fill(const toml::table& t, const std::string& p, std::size_t block, PlannedBlock& plan) const {
        const BlockDefaults& d = plan.defaults;
        const RandomRegion g = read_random_region(t, p, d);
        const auto count = static_cast<std::size_t>(
            r_.integer(r_.required(t, p, "count"), join(p, "count"), 1, max_particles));
        if (static_cast<std::int64_t>(count) > room())
            r_.fail(join(p, "count"), fmt::format("more than {} spheres in the scenario", max_particles), t.get("count"));
        refuse_overfull(t, p, "count", count, g);
        const Vec3 lo = g.lo, hi = g.hi;
        const double radius_min = g.radius_min, radius_max = g.radius_max;
        const std::int32_t material = g.material;
        plan.count = count;
        plan.count_key = join(p, "count");
        plan.smallest_radius = radius_min;
        plan.largest_radius = radius_max;
        // Placed among the particles of the blocks before it, made by then, clear of the walls.
        const std::uint64_t seed = block_seed(config_.seed, block, Stream::placement);
        plan.make = [this, &t, p, lo, hi, count, radius_min, radius_max, material, seed, d] {
            std::vector<ParticleSpec> out;
            try {
                const std::optional<WallDistances> walls = wall_distances(radius_max);
                out = random_fill(lo, hi, count, radius_min, radius_max, material, seed, config_.scenario.particles,
                                  walls ? &*walls : nullptr);
            } catch (const ConfigError&) {
                throw;
            } catch (const tumble::Error& e) {
                r_.fail(p, e.what(), &t);
            }
            apply_defaults(out, d);
            return out;
        };
    }

    // [[insert]] k: spheres poured in while the run goes (sim/scenario.hpp,
    // Insertion); counted with the blocks, made by the simulation.
    Insertion read_insertion(const toml::table& t, const std::string& p, std::size_t k) const {
        r_.only_keys(t, p, {"material", "lo", "hi", "count", "batch", "every", "start", "radius", "radius_min",
                            "radius_max", "velocity", "tag"});
        const BlockDefaults d = read_block_defaults(t, p);  // of its keys: material, radius, velocity, tag
        const RandomRegion g = read_random_region(t, p, d);
        Insertion q;
        q.lo = g.lo;
        q.hi = g.hi;
        q.material = g.material;
        q.radius_min = g.radius_min;
        q.radius_max = g.radius_max;
        q.count = r_.integer(r_.required(t, p, "count"), join(p, "count"), 1, max_particles);
        if (q.count > room())
            r_.fail(join(p, "count"), fmt::format("more than {} spheres in the scenario", max_particles), t.get("count"));
        q.batch = q.count;
        if (const toml::node* n = t.get("batch")) q.batch = r_.integer(*n, join(p, "batch"), 1, q.count);
        refuse_overfull(t, p, t.get("batch") ? "batch" : "count", static_cast<std::size_t>(q.batch), g);
        q.start = r_.number(t, p, "start", Bound::non_negative, 0.0);
        if (q.batch < q.count) q.every = r_.required_number(t, p, "every", Bound::positive);
        else q.every = r_.number(t, p, "every", Bound::positive, 1.0);  // one batch: no interval needed
        q.velocity = d.velocity.value_or(Vec3{});
        q.tag = d.tag;
        const Domain& box = s_const().domain;
        for (int a = 0; a < 3; ++a) {
            if (q.hi[a] - q.lo[a] < 2.0 * q.radius_max)
                r_.fail(p, fmt::format("the region is thinner than one sphere of radius {} m along {}", show(q.radius_max),
                                       "xyz"[a]),
                        &t);
            if ((box.periodic[a] || box.walls[a]) && (q.lo[a] < box.lo[a] || q.hi[a] > box.hi[a]))
                r_.fail(p, fmt::format("the region reaches beyond domain.lo or domain.hi along {}", "xyz"[a]), &t);
        }
        // Its own stream, apart from every block's (their inputs are below 2^63).
        q.seed = splitmix64(splitmix64(config_.seed) ^ splitmix64((std::uint64_t{1} << 63) | k));
        return q;
    }

    std::vector<ParticleSpec> read_list(const toml::table& t, const std::string& p, const BlockDefaults& d) const {
        const std::string lkey = join(p, "particles");
        r_.required(t, p, "particles");
        const auto entries = r_.tables(t, p, "particles");
        if (entries.empty()) r_.fail(lkey, "the list is empty", t.get("particles"));
        if (static_cast<std::int64_t>(entries.size()) > room())
            r_.fail(lkey, fmt::format("more than {} spheres in the scenario", max_particles), t.get("particles"));
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
        std::vector<ParticleSpec> out =
            read_particle_csv(file, config_.scenario.materials, motion_names_, defaults, &info.csv_lines);
        if (static_cast<std::int64_t>(out.size()) > room())
            r_.fail(fkey, fmt::format("more than {} spheres in the scenario", max_particles), &n);
        return out;
    }

    // Every block is read and checked, and its spheres counted, before the
    // check_ (the memory a run will need) and before any sphere is made.
    void read_particles(const toml::table& root) {
        const auto entries = r_.tables(root, "", "particles");
        const auto pours = r_.tables(root, "", "insert");
        if (entries.empty() && pours.empty())
            r_.fail("particles", "missing: at least one [[particles]] or [[insert]] block is required");
        static const std::vector<std::string> kinds{"lattice", "random_fill", "list", "csv"};
        std::vector<PlannedBlock> plans;
        for (std::size_t b = 0; b < entries.size(); ++b) {
            const toml::table& t = *entries[b];
            const std::string p = at("particles", b);
            PlannedBlock plan;
            Block& info = plan.info;
            info.path = p;
            info.first = planned_;
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
            plan.defaults = read_block_defaults(t, p);

            if (info.kind == "lattice") {
                plan_lattice(t, p, plan);
            } else if (info.kind == "random_fill") {
                plan_random_fill(t, p, b, plan);
            } else {
                plan.particles = info.kind == "list" ? read_list(t, p, plan.defaults) : read_csv(t, p, plan.defaults, info);
                plan.count = plan.particles.size();
                plan.count_key = join(p, info.kind == "list" ? "particles" : "file");
                plan.smallest_radius = INFINITY;
                for (const ParticleSpec& q : plan.particles) {
                    plan.smallest_radius = std::min(plan.smallest_radius, q.radius);
                    plan.largest_radius = std::max(plan.largest_radius, q.radius);
                }
            }
            planned_ += plan.count;
            plans.push_back(std::move(plan));
        }
        for (std::size_t k = 0; k < pours.size(); ++k) {
            const std::string p = at("insert", k);
            const Insertion q = read_insertion(*pours[k], p, k);
            s().insertions.push_back(q);
            PlannedBlock plan;
            plan.count = static_cast<std::size_t>(q.count);
            plan.info.path = p;
            plan.count_key = join(p, "count");
            plan.smallest_radius = q.radius_min;
            plan.largest_radius = q.radius_max;
            plan.poured = true;
            planned_ += plan.count;
            plans.push_back(std::move(plan));
        }
        if (check_) check_(config_, count_of(plans));

        s().particles.reserve(planned_);
        for (std::size_t b = 0; b < plans.size(); ++b) {
            PlannedBlock& plan = plans[b];
            if (plan.poured) continue;
            std::vector<ParticleSpec> block = plan.make ? plan.make() : std::move(plan.particles);
            if (plan.defaults.speed)
                randomize_velocities(block, *plan.defaults.speed, block_seed(config_.seed, b, Stream::velocities));
            s().particles.insert(s().particles.end(), block.begin(), block.end());
            blocks_.push_back(std::move(plan.info));
        }
    }

    // The spheres of all blocks, and the keys that set the most of them.
    static ParticleCount count_of(const std::vector<PlannedBlock>& plans) {
        ParticleCount c;
        c.smallest_radius = INFINITY;
        for (const PlannedBlock& plan : plans) {
            c.spheres += plan.count;
            c.smallest_radius = std::min(c.smallest_radius, plan.smallest_radius);
            c.largest_radius = std::max(c.largest_radius, plan.largest_radius);
        }
        if (plans.size() == 1) {
            c.keys = plans.front().count_key;
            return c;
        }
        std::vector<const PlannedBlock*> largest;
        for (const PlannedBlock& plan : plans) largest.push_back(&plan);
        std::stable_sort(largest.begin(), largest.end(),
                         [](const PlannedBlock* a, const PlannedBlock* b) { return a->count > b->count; });
        constexpr std::size_t named = 3;
        for (std::size_t k = 0; k < std::min(named, largest.size()); ++k)
            c.keys += fmt::format("{}{} {}", k ? ", " : "", largest[k]->count_key, largest[k]->count);
        if (largest.size() > named) c.keys += fmt::format(", and {} more blocks", largest.size() - named);
        return c;
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

        check_periodic_lengths();
        if (const std::string why = scenario_problem(sc); !why.empty()) r_.fail("scenario", why);

        OverlapReport worst;
        try {
            worst = largest_overlap(sc);
        } catch (const tumble::Error& e) {
            r_.fail("domain", e.what());
        }
        if (worst.ratio > max_initial_overlap_ && worst.wall >= 0) {
            const int axis = worst.wall / 2;
            const bool hi = worst.wall % 2;
            r_.fail(key_of(worst.b),
                    fmt::format("{} overlaps the flat wall at domain.{}[{}] = {} by {:.3g} of its radius, more than "
                                "simulation.max_initial_overlap = {}",
                                describe_under_key(worst.b), hi ? "hi" : "lo", axis,
                                show(hi ? d.hi[axis] : d.lo[axis]), worst.ratio, show(max_initial_overlap_)));
        }
        if (worst.ratio > max_initial_overlap_)
            r_.fail(key_of(worst.b),
                    fmt::format("{} overlaps {} by {:.3g} of the smaller radius, more than "
                                "simulation.max_initial_overlap = {}",
                                describe_under_key(worst.b), describe(worst.a), worst.ratio, show(max_initial_overlap_)));
        const std::optional<WallDistances> walls = wall_distances(sc.largest_radius());
        for (std::size_t i = 0; walls && i < sc.particles.size(); ++i)  // a grain that starts in or beyond a wall
            for (std::size_t k = 0; k < sc.walls.size(); ++k) {
                const ParticleSpec& q = sc.particles[i];
                const double ratio = 1.0 - walls->distance(k, q.position) / q.radius;
                if (q.motion == free_motion && ratio > max_initial_overlap_)
                    r_.fail(key_of(i), fmt::format("{} overlaps wall \"{}\" by {:.3g} of its radius{}, more than "
                                                   "simulation.max_initial_overlap = {}",
                                                   describe_under_key(i), sc.walls[k].name, ratio,
                                                   ratio > 1.0 ? " (its centre lies beyond the wall)" : "",
                                                   show(max_initial_overlap_)));
            }

        check_motion_speeds();
        try {
            (void)assess_time_step(sc);
        } catch (const tumble::Error& e) {
            r_.fail(sc.time_step.dt > 0.0 ? "time_step.dt" : "time_step", e.what());
        }
    }

    // The neighbour search puts at least three cells of one interaction
    // range, 2 R_max + skin, across a periodic axis (a sphere's images must
    // not be its own neighbours).
    void check_periodic_lengths() const {
        const Scenario& sc = s_const();
        const double largest = sc.largest_radius(), skin = neighbor_skin(sc), range = 2.0 * largest + skin;
        for (int k = 0; k < 3; ++k) {
            const double length = sc.domain.hi[k] - sc.domain.lo[k];
            if (!sc.domain.periodic[k] || length >= 3.0 * range) continue;
            // The skin's fault if it was given and the spheres alone fit.
            const bool skin_given = sc.neighbor.skin > 0.0 && length >= 3.0 * 2.0 * largest;
            r_.fail(skin_given ? "neighbor.skin" : at("domain.hi", static_cast<std::size_t>(k)),
                    fmt::format("the periodic axis {} is {} m long (domain.hi - domain.lo), shorter than three "
                                "interaction ranges, 3 x (2 x the largest radius {} m + the skin {} m{}) = {} m, which "
                                "the neighbour search needs across a periodic axis; {}",
                                "xyz"[k], show(length), show(largest), show(skin), sc.neighbor.skin > 0.0 ? "" : ", automatic",
                                show(3.0 * range),
                                skin_given ? "make the skin smaller or the axis longer" : "make the axis longer"));
        }
    }

    // A prescribed motion moves its spheres' surfaces at up to |velocity| +
    // |angular_velocity| x (the largest distance of a sphere's centre from
    // the axis + its radius). Faster than the blow-up check lets a free
    // sphere move (sim/health.hpp: 100 x the reference speed), any sphere it
    // struck would stop the run; a rotation about an axis 1e6 m away, or a
    // rate of 1e308 rad/s, is nearly always a slip.
    void check_motion_speeds() const {
        const Scenario& sc = s_const();
        std::vector<double> reach(sc.motions.size(), -1.0);  // -1: no sphere follows it
        for (const ParticleSpec& q : sc.particles) {
            if (q.motion == free_motion) continue;
            const RigidMotion& m = sc.motions[static_cast<std::size_t>(q.motion)];
            const Vec3 from_point = q.position - m.axis_point, u = m.unit_axis();
            const double from_axis = length(from_point - dot(from_point, u) * u) + q.radius;
            double& r = reach[static_cast<std::size_t>(q.motion)];
            r = std::isnan(from_axis) ? from_axis : std::max(r, from_axis);
        }
        const double limit = default_health_limits(sc).max_speed;
        for (std::size_t k = 0; k < sc.motions.size(); ++k) {  // and the farthest point of each wall it carries
            const RigidMotion& m = sc.motions[k];
            reach[k] = std::max(reach[k], walls_reach(sc, k, m, nullptr));
            if (auto why = motion_speed_problem(sc, m, reach[k]); !why.empty())
                r_.fail(join(at("motion", k), length(m.velocity) > limit ? "velocity" : "angular_velocity"),
                        why + ". If this motion is meant, raise time_step.reference_speed to its speed");
        }
    }

    // |v| without overflow for components up to the largest double.
    static double length(const Vec3& v) { return std::hypot(v.x, v.y, v.z); }

    Reader r_;
    fs::path base_dir_;
    ParticleCheck check_;
    RunConfig config_;
    std::size_t planned_ = 0;  // spheres of the blocks read so far
    double max_initial_overlap_ = 0.05;
    MaterialTables materials_;
    std::vector<std::string> motion_names_;
    std::vector<Block> blocks_;
};

}  // namespace

RunConfig read_run_config(const toml::table& root, const fs::path& name, const fs::path& base_dir,
                          const ParticleCheck& check) {
    return ScenarioReader(name, base_dir, check).read(root);
}

RunConfig parse_run_config(std::string_view toml_text, const fs::path& name, const fs::path& base_dir,
                           const ParticleCheck& check) {
    return read_run_config(parse_toml(toml_text, name), name, base_dir, check);
}

RunConfig load_run_config(const fs::path& file, const ParticleCheck& check) {
    fs::path base = file.parent_path();
    if (base.empty()) base = ".";
    return parse_run_config(read_text_file(file), file, base, check);
}

}  // namespace tumble::io
