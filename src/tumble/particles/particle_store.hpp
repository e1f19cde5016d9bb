// SPDX-License-Identifier: MIT
// All particles, structure-of-arrays: one contiguous array per field, so the
// force loop streams only what it reads. Array order changes when the store
// is re-sorted in space; a particle's identity is its global id.
#pragma once

#include <cstdint>
#include <tuple>
#include <vector>

#include "tumble/core/parallel.hpp"
#include "tumble/core/vec3.hpp"

namespace tumble {

// Free particles follow Newton's equations; kinematic ones follow a
// prescribed rigid motion (index into Scenario::motions) and only push.
inline constexpr std::int32_t free_motion = -1;

struct ParticleStore {
    std::vector<std::int64_t> id;           // global id, never changes
    std::vector<Vec3> position;             // m
    std::vector<Vec3> velocity;             // m/s
    std::vector<Vec3> angular_velocity;     // rad/s
    std::vector<Vec3> force;                // N; of a kinematic particle not used by the step (its motion is
    std::vector<Vec3> torque;               // N m; prescribed), complete between advance() calls only
    std::vector<Vec3> half_kick;            // dt/2 (F/m + g) of the last forces while the velocities are at the
                                            // half step (0 otherwise, and for kinematic particles): the
                                            // velocity predicted for t + dt is velocity + half_kick, m/s
    std::vector<double> radius;             // m
    std::vector<double> inv_mass;           // 1/kg (0 for kinematic)
    std::vector<double> inv_inertia;        // 1/(kg m^2), solid sphere I = 2/5 m R^2 (0 for kinematic)
    std::vector<double> mass;               // kg (of the sphere, also for kinematic)
    std::vector<std::int32_t> material;     // index into the material list
    std::vector<std::int32_t> motion;       // free_motion or index of a prescribed motion
    std::vector<std::int32_t> tag;          // user label (e.g. the half a grain started in)
    std::vector<Vec3> reference_position;   // kinematic: position at t = 0 of the motion, m
    std::vector<Vec3> image_shift;          // kinematic: periodic wraps applied since t = 0, m

    // Every field above, in this order: for what is done to all of them
    // alike (reordering, resizing, sending a particle to another rank).
    auto fields() {
        return std::tie(id, position, velocity, angular_velocity, force, torque, half_kick, radius, inv_mass,
                        inv_inertia, mass, material, motion, tag, reference_position, image_shift);
    }
    auto fields() const {
        return std::tie(id, position, velocity, angular_velocity, force, torque, half_kick, radius, inv_mass,
                        inv_inertia, mass, material, motion, tag, reference_position, image_shift);
    }

    std::size_t size() const { return id.size(); }
    bool is_kinematic(std::size_t i) const { return motion[i] != free_motion; }
    std::size_t free_count() const {
        std::size_t n = 0;
        for (std::int32_t m : motion) n += m == free_motion;
        return n;
    }

    // Reorder every field: new index k holds the particle that was at order[k].
    void permute(const std::vector<std::uint32_t>& order);
    // The same for the indices k of range r, from `from` (a store of the
    // same size): the part of a permutation one thread does.
    void gather(const ParticleStore& from, const std::vector<std::uint32_t>& order, IndexRange r);
    // Every field n particles long (the first n kept; new ones zero).
    void resize(std::size_t n);
    // Room for n particles in every field: growing to n then moves no array.
    void reserve(std::size_t n);
    // Keep the particles at `indices` (increasing), in that order.
    void keep(const std::vector<std::uint32_t>& indices);
    // Append particle i of `from`.
    void append(const ParticleStore& from, std::size_t i);
};

}  // namespace tumble
