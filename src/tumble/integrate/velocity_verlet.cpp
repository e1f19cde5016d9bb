// SPDX-License-Identifier: MIT
#include "tumble/integrate/velocity_verlet.hpp"

#include <algorithm>
#include <type_traits>

#include "tumble/core/isa.hpp"

namespace tumble {

namespace {

// The displacement from the list's build, squared, one component at a time
// (((0 + dx^2) + dy^2) + dz^2: the sums of VerletList::needs_rebuild()).
inline void add_square(double& sum, double d) { sum += d * d; }

// The loops over particles [r.begin, r.end), on the particles' arrays as
// plain numbers (3 per vector) that do not overlap (`__restrict`).
// Kinematic particles keep their prescribed motion: each update is written
// as a choice between the new and the old value rather than a skipped
// update. Both let the compiler run the loops on several particles per
// instruction, compiled for the instruction set in use (run_for_isa).
// Kicks = 1: the kick, v += dv with dv = half_dt (F/m + g), and omega +=
// half_dt T/I. Kicks = 2: the kick that ends a step and the one that begins
// the next, with the same F and T (dv added twice, rounded as two calls of
// the single kick round it). With Drift, then x += dt v (the drift), the
// velocity change is written to half_kick (the change predicted for the
// step's second kick; 0 for kinematic particles) and the forces and torques
// are spent (set to zero); without, half_kick = 0. With Check, returns how
// many free particles are now farther than sqrt(limit2) from at_build
// (DisplacementLimit), summed as VerletList::needs_rebuild() sums them.
template <int Kicks, bool Drift, bool Check>
std::size_t kick_range(IndexRange r, const std::int32_t* __restrict motion, const double* __restrict inv_mass,
                       const double* __restrict inv_inertia, double* __restrict force, double* __restrict torque,
                       double* __restrict velocity, double* __restrict angular_velocity,
                       double* __restrict half_kick, double* __restrict position, const double* __restrict at_build,
                       double limit2, Vec3 gravity, double half_dt, double dt) {
    std::size_t far = 0;
    for (std::size_t i = r.begin; i < r.end; ++i) {
        const bool free = motion[i] == free_motion;
        const double spin_factor = half_dt * inv_inertia[i];
        // A kinematic particle drifts by 0 times its velocity
        // (Simulation::move_kinematic() sets its position right after). The
        // choice of the factor, not of the step, lets GCC vectorise the loop.
        const double step = free ? dt : 0.0;
        double distance2 = 0.0;  // from where it was at the list's build
        for (std::size_t c = 0; c < 3; ++c) {
            const double v = velocity[3 * i + c], omega = angular_velocity[3 * i + c];
            const double dv = half_dt * (inv_mass[i] * force[3 * i + c] + gravity[static_cast<int>(c)]);
            const double domega = spin_factor * torque[3 * i + c];
            double v_kicked = v + dv, omega_kicked = omega + domega;
            if constexpr (Kicks == 2) {
                v_kicked += dv;
                omega_kicked += domega;
            }
            const double v_new = free ? v_kicked : v;
            velocity[3 * i + c] = v_new;
            angular_velocity[3 * i + c] = free ? omega_kicked : omega;
            half_kick[3 * i + c] = free && Drift ? dv : 0.0;
            if constexpr (Drift) {
                position[3 * i + c] += step * v_new;
                force[3 * i + c] = 0.0;
                torque[3 * i + c] = 0.0;
            }
            if constexpr (Check) add_square(distance2, position[3 * i + c] - at_build[3 * i + c]);
        }
        if constexpr (Check) far += free && distance2 > limit2 ? 1 : 0;
    }
    return far;
}

// The particles of motion k in range r turned about its axis from their
// reference positions (Rodrigues) and carried along it: x = axis point +
// arm + periodic image shift, v = velocity + omega u x arm, omega u. Others
// keep their values, again written as a choice. With All (every particle of
// r has motion k, as the drum's wall spheres) there is no choice to make:
// GCC then runs the loop on several particles per instruction, which it
// does not with the choice (the loads it would mask), nor without the
// motion copied (studies/performance/LOG.md, "The wall's motion on several spheres
// per instruction, the pairs apart zeroed without a look"). With Check,
// returns how many of them are now farther than sqrt(limit2) from at_build.
template <bool All, bool Check>
std::size_t move_range(IndexRange r, std::int32_t k, const MotionNow& m, const std::int32_t* __restrict motion,
                       const double* __restrict reference, const double* __restrict image_shift,
                       double* __restrict position, double* __restrict velocity, double* __restrict angular_velocity,
                       double* __restrict force, double* __restrict torque, const double* __restrict at_build,
                       double limit2) {
    const MotionNow now = m;  // a copy: GCC cannot tell that no array written here holds m
    const Vec3 spin = now.angular_velocity * now.turn.u;
    std::size_t far = 0;
    for (std::size_t i = r.begin; i < r.end; ++i) {
        const bool mine = All || motion[i] == k;
        const Vec3 from{reference[3 * i], reference[3 * i + 1], reference[3 * i + 2]};
        const Vec3 shift{image_shift[3 * i], image_shift[3 * i + 1], image_shift[3 * i + 2]};
        const Vec3 arm = rotate(from - now.start_axis_point, now.turn);
        const Vec3 x = now.axis_point + arm + shift;
        const Vec3 v = now.velocity + now.angular_velocity * cross(now.turn.u, arm);
        const double xs[3] = {x.x, x.y, x.z}, vs[3] = {v.x, v.y, v.z}, spins[3] = {spin.x, spin.y, spin.z};
        double distance2 = 0.0;  // from where it was at the list's build
        for (std::size_t c = 0; c < 3; ++c) {
            position[3 * i + c] = mine ? xs[c] : position[3 * i + c];
            velocity[3 * i + c] = mine ? vs[c] : velocity[3 * i + c];
            angular_velocity[3 * i + c] = mine ? spins[c] : angular_velocity[3 * i + c];
            force[3 * i + c] = mine ? 0.0 : force[3 * i + c];
            torque[3 * i + c] = mine ? 0.0 : torque[3 * i + c];
            if constexpr (Check) add_square(distance2, position[3 * i + c] - at_build[3 * i + c]);
        }
        if constexpr (Check) far += mine && distance2 > limit2 ? 1 : 0;
    }
    return far;
}

template <int Kicks, bool Drift>
std::size_t kick_range(ParticleStore& p, IndexRange r, const Vec3& gravity, double half_dt, double dt,
                       const DisplacementLimit& limit) {
    const double* at_build = limit.at_build ? &limit.at_build->x : nullptr;
    const auto run = [&](auto check) {
        return kick_range<Kicks, Drift, decltype(check)::value>(
            r, p.motion.data(), p.inv_mass.data(), p.inv_inertia.data(), &p.force.data()->x, &p.torque.data()->x,
            &p.velocity.data()->x, &p.angular_velocity.data()->x, &p.half_kick.data()->x, &p.position.data()->x,
            at_build, limit.limit2, gravity, half_dt, dt);
    };
    std::size_t far = 0;
    run_for_isa([&] { far = at_build ? run(std::true_type{}) : run(std::false_type{}); });
    return far;
}

}  // namespace

// The loops run in the copy for the processor's instruction set (core/isa.hpp).
void kick(ParticleStore& p, const Vec3& gravity, double half_dt, IndexRange r) {
    kick_range<1, false>(p, r, gravity, half_dt, 0.0, {});
}

std::size_t kick_drift(ParticleStore& p, const Vec3& gravity, double half_dt, double dt, IndexRange r,
                       const DisplacementLimit& limit) {
    return kick_range<1, true>(p, r, gravity, half_dt, dt, limit);
}

std::size_t kick_kick_drift(ParticleStore& p, const Vec3& gravity, double half_dt, double dt, IndexRange r,
                            const DisplacementLimit& limit) {
    return kick_range<2, true>(p, r, gravity, half_dt, dt, limit);
}

std::size_t move_kinematic(ParticleStore& p, const std::vector<MotionNow>& now, IndexRange r,
                           const DisplacementLimit& limit) {
    const double* at_build = limit.at_build ? &limit.at_build->x : nullptr;
    const auto move = [&](auto all, auto check, std::size_t k) {
        return move_range<decltype(all)::value, decltype(check)::value>(
            r, static_cast<std::int32_t>(k), now[k], p.motion.data(), &p.reference_position.data()->x,
            &p.image_shift.data()->x, &p.position.data()->x, &p.velocity.data()->x, &p.angular_velocity.data()->x,
            &p.force.data()->x, &p.torque.data()->x, at_build, limit.limit2);
    };
    const bool one_motion = now.size() == 1 && std::all_of(p.motion.begin() + static_cast<std::ptrdiff_t>(r.begin),
                                                           p.motion.begin() + static_cast<std::ptrdiff_t>(r.end),
                                                           [](std::int32_t m) { return m == 0; });
    const auto move_all = [&](auto check) {
        if (one_motion) return move(std::true_type{}, check, 0);
        std::size_t far = 0;
        for (std::size_t k = 0; k < now.size(); ++k) far += move(std::false_type{}, check, k);
        return far;
    };
    std::size_t far = 0;
    run_for_isa([&] { far = at_build ? move_all(std::true_type{}) : move_all(std::false_type{}); });
    return far;
}

}  // namespace tumble
