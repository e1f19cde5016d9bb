// SPDX-License-Identifier: MIT
#include "tumble/sim/scenario.hpp"

#include <algorithm>
#include <cmath>

#include "tumble/core/constants.hpp"
#include "tumble/materials/pair_table.hpp"
#include "tumble/neighbor/candidate_pairs.hpp"
#include "tumble/sim/particle_setup.hpp"

namespace tumble {

namespace {
bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
}  // namespace

double neighbor_skin(const Scenario& s) { return s.neighbor.skin > 0.0 ? s.neighbor.skin : 0.2 * s.largest_radius(); }

std::string scenario_problem(const Scenario& s) {
    const auto n_materials = static_cast<std::int32_t>(s.materials.size());
    if (n_materials == 0) return "no materials";
    for (const Material& m : s.materials)
        if (auto why = material_problem(m); !why.empty()) return "material " + m.name + ": " + why;
    if (s.pair_properties.size() != s.materials.size()) return "pair table does not cover every material";
    for (std::int32_t a = 0; a < n_materials; ++a) {
        if (s.pair_properties[a].size() != s.materials.size()) return "pair table does not cover every material";
        for (std::int32_t b = 0; b < n_materials; ++b) {
            const PairProperties& p = s.pair_properties[a][b];
            const std::string pair = s.materials[a].name + "-" + s.materials[b].name;
            if (!(p.mu >= 0.0) || !std::isfinite(p.mu)) return "pair " + pair + ": mu must be >= 0";
            if (!(p.W >= 0.0) || !std::isfinite(p.W)) return "pair " + pair + ": W must be >= 0";
            const PairProperties& q = s.pair_properties[b][a];
            if (p.mu != q.mu || p.W != q.W) return "pair " + pair + " is not symmetric";
            // Moduli so large (or small) that the pair's mixing rules
            // overflow: E = 1e308 gives E* = inf / inf.
            const PairCoefficients c = make_pair_coefficients(s.materials[a], s.materials[b], p);
            for (double v : {c.E_star, c.G_star, c.B_star, c.attraction, c.pull_off})
                if (!std::isfinite(v))
                    return "pair " + pair + ": its pair moduli (E*, G*, B*, attraction) overflow; E, G, xi, eta "
                           "or W of its materials are out of range";
        }
    }
    if (!(s.model.slip_velocity_regularisation > 0.0)) return "slip velocity regularisation must be > 0";
    for (int k = 0; k < 3; ++k)
        if (!(s.domain.hi[k] > s.domain.lo[k]) || !std::isfinite(s.domain.hi[k] - s.domain.lo[k]))
            return "domain: hi must exceed lo on every axis";
    for (int k = 0; k < 3; ++k)
        if (s.domain.walls[k] && s.domain.periodic[k])
            return std::string("domain: axis ") + "xyz"[k] + " cannot be both periodic and walled";
    const bool any_wall = s.domain.walls[0] || s.domain.walls[1] || s.domain.walls[2];
    if (any_wall && (s.domain.wall_material < 0 || s.domain.wall_material >= n_materials))
        return "domain: unknown wall material";
    if (!finite(s.gravity)) return "gravity must be finite";
    for (std::size_t k = 0; k < s.motions.size(); ++k)
        if (auto why = motion_problem(s.motions[k]); !why.empty()) return "motion " + std::to_string(k) + ": " + why;
    for (const Wall& w : s.walls) {
        const std::string who = "wall " + w.name + ": ";
        if (auto why = wall_problem(w); !why.empty()) return who + why;
        if (w.material < 0 || w.material >= n_materials) return who + "unknown material";
        if (w.motion < -1 || w.motion >= static_cast<std::int32_t>(s.motions.size())) return who + "unknown motion";
        if (w.shape == WallShape::mesh && w.mesh >= static_cast<std::int32_t>(s.meshes.size())) return who + "unknown mesh";
        if (w.shape != WallShape::mesh && w.mesh != -1) return who + "names a mesh, but is not one";
    }
    for (std::size_t k = 0; k < s.meshes.size(); ++k) {
        const std::string who = "mesh " + std::to_string(k) + ": ";
        try {
            check_mesh(s.meshes[k]);
        } catch (const Error& e) {
            return who + e.what();
        }
        // The features' ids must fit mesh_feature_code (an edge per corner at most).
        if (3 * s.meshes[k].triangles.size() >= (std::size_t{1} << 30) - 1) return who + "too many triangles";
    }
    if (s.particles.empty() && s.insertions.empty()) return "no particles";
    std::size_t total = s.particles.size();
    for (std::size_t k = 0; k < s.insertions.size(); ++k) {
        const Insertion& q = s.insertions[k];
        const std::string who = "insertion " + std::to_string(k) + ": ";
        if (!finite(q.lo) || !finite(q.hi) || !finite(q.velocity) || !std::isfinite(q.start) || !std::isfinite(q.every))
            return who + "its region, velocity and times must be finite";
        if (q.count < 1 || q.batch < 1) return who + "count and batch must be at least 1";
        if (!(q.radius_min > 0.0) || !(q.radius_max >= q.radius_min)) return who + "need 0 < radius_min <= radius_max";
        if (q.material < 0 || q.material >= n_materials) return who + "unknown material";
        if (!(q.start >= 0.0) || !(q.every > 0.0)) return who + "start must be >= 0 and every > 0";
        for (int a = 0; a < 3; ++a) {
            if (!(q.hi[a] - q.lo[a] >= 2.0 * q.radius_max))
                return who + "its region is thinner than one sphere along " + "xyz"[a];
            const bool bounded = s.domain.periodic[a] || s.domain.walls[a];
            if (bounded && (q.lo[a] < s.domain.lo[a] || q.hi[a] > s.domain.hi[a]))
                return who + "its region reaches beyond the domain along " + "xyz"[a];
        }
        total += static_cast<std::size_t>(q.count);
    }
    if (total >= (std::size_t{1} << 31)) return "too many particles (at most 2^31 - 1, those poured in included)";
    for (std::size_t i = 0; i < s.particles.size(); ++i) {
        const ParticleSpec& p = s.particles[i];
        const std::string who = "particle " + std::to_string(i) + ": ";
        if (!(p.radius > 0.0) || !std::isfinite(p.radius)) return who + "radius must be > 0";
        if (p.material < 0 || p.material >= n_materials) return who + "unknown material";
        const double rho = s.materials[static_cast<std::size_t>(p.material)].rho;
        if (!std::isfinite(4.0 / 3.0 * pi * rho * p.radius * p.radius * p.radius))
            return who + "its radius and its material's density rho give an infinite mass: out of range";
        if (p.motion != free_motion && (p.motion < 0 || p.motion >= static_cast<std::int32_t>(s.motions.size())))
            return who + "unknown motion";
        if (!finite(p.position) || !finite(p.velocity) || !finite(p.angular_velocity))
            return who + "position and velocities must be finite";
        for (int k = 0; k < 3; ++k) {
            const bool inside = p.position[k] >= s.domain.lo[k] && p.position[k] < s.domain.hi[k];
            if (s.domain.periodic[k] && !inside) return who + "lies outside the periodic axis " + "xyz"[k];
            if (s.domain.walls[k] && !inside) return who + "lies outside the walls along " + "xyz"[k];
            // A sphere may be clamped between two walls closer than its
            // diameter, but not wider than their distance (it would overlap
            // each by more than its radius); a periodic image must not touch
            // the sphere itself.
            const double room = s.domain.hi[k] - s.domain.lo[k];
            if (s.domain.periodic[k] && 2.0 * p.radius > room)
                return who + "its diameter exceeds the periodic length along " + "xyz"[k];
            if (s.domain.walls[k] && p.radius > room)
                return who + "its radius exceeds the distance between the walls along " + "xyz"[k];
        }
    }
    return {};
}

InsertionSteps insertion_steps(const Insertion& q, double dt) {
    return {static_cast<std::int64_t>(std::ceil(q.start / dt)),
            std::max<std::int64_t>(1, std::llround(q.every / dt))};
}

std::string motion_problem(const RigidMotion& m) {
    if (!(norm(m.axis_direction) > 0.0)) return "axis direction is zero";
    if (!finite(m.axis_point) || !finite(m.axis_direction) || !finite(m.velocity) || !std::isfinite(m.angular_velocity))
        return "values must be finite";
    if (!std::isfinite(norm(m.axis_direction))) return "the axis direction's length overflows";
    return {};
}

OverlapReport largest_overlap(const Scenario& s) {
    const ParticleStore store = make_particle_store(s);
    OverlapReport worst;
    if (store.size() == 0) return worst;  // spheres poured in later only
    PairList pairs;
    cell_list_pairs(store, s.domain, 0.0, pairs);
    const PeriodicImages images(s.domain);
    for (std::size_t k = 0; k < pairs.size(); ++k) {
        const std::uint32_t i = pairs.first[k], j = pairs.second[k];
        const double distance = norm(store.position[i] - store.position[j] + images[pairs.image[k]]);
        const double ratio = (store.radius[i] + store.radius[j] - distance) / std::min(store.radius[i], store.radius[j]);
        if (ratio > worst.ratio) {
            worst.ratio = ratio;
            worst.a = static_cast<std::size_t>(std::min(store.id[i], store.id[j]));
            worst.b = static_cast<std::size_t>(std::max(store.id[i], store.id[j]));
        }
    }
    // Flat walls push free particles only.
    const Domain& box = s.domain;
    for (std::size_t i = 0; i < s.particles.size(); ++i) {
        const ParticleSpec& p = s.particles[i];
        if (p.motion != free_motion) continue;
        for (int axis = 0; axis < 3; ++axis) {
            if (!box.walls[axis]) continue;
            const double distance[2] = {p.position[axis] - box.lo[axis], box.hi[axis] - p.position[axis]};
            for (int side = 0; side < 2; ++side) {
                const double ratio = (p.radius - distance[side]) / p.radius;
                if (ratio > worst.ratio) worst = {ratio, 0, i, 2 * axis + side};
            }
        }
    }
    return worst;
}

}  // namespace tumble
