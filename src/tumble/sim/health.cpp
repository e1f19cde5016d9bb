// SPDX-License-Identifier: MIT
#include "tumble/sim/health.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "tumble/walls/wall_surface.hpp"

namespace tumble {

namespace {

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::ostream& operator<<(std::ostream& out, const Vec3& v) {
    return out << '(' << v.x << ", " << v.y << ", " << v.z << ')';
}

// The message of a problem, to 6 digits. Made only when there is one: a
// stream costs about a microsecond to make (its locale), which for every
// sphere at every check was 2 to 3 % of a drum run.
template <class... Parts>
std::string message(const Parts&... parts) {
    std::ostringstream text;
    text.precision(6);
    (text << ... << parts);
    return text.str();
}

// "particle 17 (free) at (x, y, z) m" for messages.
std::string who(const ParticleStore& p, std::size_t i) {
    return message("particle ", p.id[i], p.is_kinematic(i) ? " (kinematic)" : " (free)", " at ", p.position[i], " m");
}

std::string particle_problem(const ParticleStore& p, std::size_t i, const HealthLimits& limits) {
    if (!finite(p.position[i]) || !finite(p.velocity[i]) || !finite(p.angular_velocity[i]))
        return message(who(p, i), " has a non-finite position, velocity or spin: v = ", p.velocity[i],
                       " m/s, omega = ", p.angular_velocity[i], " rad/s");
    if (p.is_kinematic(i)) return "";
    const double speed = norm(p.velocity[i]);
    if (limits.max_speed > 0.0 && speed > limits.max_speed)
        return message(who(p, i), " moves at ", speed, " m/s, above the limit ", limits.max_speed,
                       " m/s: the kinetic energy has exploded");
    for (int k = 0; k < 3; ++k)
        if (limits.bounded[k] && (p.position[i][k] < limits.lo[k] || p.position[i][k] > limits.hi[k]))
            return message(who(p, i), " is outside ", limits.region, " (", limits.lo, " to ", limits.hi, " m)");
    return "";
}

std::string contact_problem(const Simulation& sim, const HealthLimits& limits) {
    const ParticleStore& p = sim.particles();
    const PairList& pairs = sim.neighbors().pairs();
    for (std::size_t k = 0; k < pairs.size(); ++k) {
        const std::uint32_t i = pairs.first[k], j = pairs.second[k];
        if (p.is_kinematic(i) && p.is_kinematic(j)) continue;  // wall spheres may overlap each other
        const double distance = norm(p.position[i] - p.position[j] + sim.neighbors().images()[pairs.image[k]]);
        const double overlap = p.radius[i] + p.radius[j] - distance;
        const double ratio = overlap / std::min(p.radius[i], p.radius[j]);
        if (ratio <= limits.max_overlap_ratio) continue;
        return message("the contact of ", who(p, i), " and ", who(p, j), " overlaps ", overlap, " m, ", ratio,
                       " of the smaller radius, above the limit ", limits.max_overlap_ratio);
    }
    return "";
}

}  // namespace

HealthLimits default_health_limits(const Scenario& s) {
    HealthLimits limits;
    limits.max_speed = 100.0 * s.time_step.reference_speed;
    const double largest = s.largest_radius();
    limits.bounded = s.domain.walls;
    limits.lo = s.domain.lo - Vec3{largest, largest, largest};
    limits.hi = s.domain.hi + Vec3{largest, largest, largest};
    return limits;
}

std::string motion_speed_problem(const Scenario& s, const RigidMotion& m, double reach) {
    if (reach < 0.0) return {};
    const double limit = default_health_limits(s).max_speed;
    const double translation = std::hypot(m.velocity.x, m.velocity.y, m.velocity.z);  // without overflow
    const double spin = m.angular_velocity == 0.0 ? 0.0 : std::abs(m.angular_velocity) * reach;
    const double speed = translation + spin;
    if (speed <= limit) return {};
    std::ostringstream why;
    why.precision(3);
    why << "its spheres and walls would move at up to " << speed << " m/s (|velocity| " << translation
        << " m/s + |angular_velocity| " << std::abs(m.angular_velocity) << " rad/s x " << reach
        << " m, the farthest surface from the axis), faster than the " << limit
        << " m/s at which the blow-up check stops a run (100 x time_step.reference_speed): a free sphere it struck "
           "would be flung faster";
    return why.str();
}

double walls_reach(const Scenario& s, std::size_t k, const RigidMotion& m, const MotionNow* now) {
    const Vec3 u = m.unit_axis();
    double reach = -1.0;
    for (const Wall& w : s.walls) {
        if (w.motion != static_cast<std::int32_t>(k)) continue;
        const TriangleMesh* mesh = w.mesh >= 0 ? &s.meshes[static_cast<std::size_t>(w.mesh)] : nullptr;
        for (const Vec3& v : wall_surface(place_wall(w, now), s.domain, 48, mesh).vertices)
            reach = std::max(reach, distance_from_axis(v, m.axis_point, u));
    }
    return reach;
}

namespace {
std::string health_problem(const Simulation& sim, const HealthLimits& limits, bool contacts) {
    std::string problem;
    for (std::size_t i = 0; i < sim.particles().size() && problem.empty(); ++i)
        problem = particle_problem(sim.particles(), i, limits);
    if (problem.empty() && contacts) problem = contact_problem(sim, limits);
    if (problem.empty()) return "";
    return message("step ", sim.step_count(), " (t = ", sim.time(), " s): ", problem);
}
}  // namespace

std::string health_problem(const Simulation& sim, const HealthLimits& limits) {
    return health_problem(sim, limits, true);
}

std::string particle_health_problem(const Simulation& sim, const HealthLimits& limits) {
    return health_problem(sim, limits, false);
}

}  // namespace tumble
