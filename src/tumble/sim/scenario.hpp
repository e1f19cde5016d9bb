// SPDX-License-Identifier: MIT
// Everything that defines a simulation, as plain data. The engine builds a
// Simulation from it; readers of file formats (src/io) fill it in.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "tumble/contact/contact_law.hpp"
#include "tumble/core/domain.hpp"
#include "tumble/core/vec3.hpp"
#include "tumble/materials/material.hpp"
#include "tumble/particles/particle_store.hpp"
#include "tumble/walls/mesh.hpp"
#include "tumble/walls/wall.hpp"

namespace tumble {

// A prescribed rigid motion for kinematic particles: rotation at
// angular_velocity (rad/s, right-handed about axis_direction) around the
// axis through axis_point, plus a translation at velocity. The axis point
// moves with the translation.
struct RigidMotion {
    Vec3 axis_point;
    Vec3 axis_direction{0.0, 0.0, 1.0};  // need not be normalised
    double angular_velocity = 0.0;       // rad/s
    Vec3 velocity;                       // m/s

    Vec3 unit_axis() const { return (1.0 / norm(axis_direction)) * axis_direction; }  // the direction, of length 1
};

// One particle as the user describes it.
struct ParticleSpec {
    Vec3 position;
    Vec3 velocity;
    Vec3 angular_velocity;
    double radius = 0.0;
    std::int32_t material = 0;
    std::int32_t motion = free_motion;  // free_motion, or an index into Scenario::motions
    std::int32_t tag = 0;
};

// Spheres poured in while the run goes (a scenario's [[insert]], as
// LIGGGHTS's insert/stream does it): a batch of up to `batch` spheres every
// `every` seconds from `start`, each batch placed at random in the box
// [lo, hi] (whole spheres inside) clear of every sphere and wall there at
// that moment, until `count` are in. A batch places what fits and leaves
// the rest to the next. Free spheres of one material, radius uniform in
// [radius_min, radius_max], starting at `velocity` without spin.
struct Insertion {
    Vec3 lo, hi;                   // m
    std::int64_t count = 0;        // spheres in all
    std::int64_t batch = 0;        // at most this many at a time
    double start = 0.0;            // s: the first batch at the first step at or after this time
    double every = 0.0;            // s between batches: a whole number of time steps, at least one (insertion_period())
    double radius_min = 0.0, radius_max = 0.0;  // m
    std::int32_t material = 0;
    std::int32_t tag = 0;
    Vec3 velocity;                 // m/s
    std::uint64_t seed = 0;        // batch k draws from (seed, k)
};

struct TimeStepSettings {
    double dt = 0.0;               // s; 0 chooses it automatically from the collision times
    double reference_speed = 1.0;  // impact speed (m/s) whose Hertz collision must be resolved
    bool allow_unsafe = false;     // accept a given dt above the safe maximum (for experts and tests)
};

struct NeighborSettings {
    double skin = 0.0;        // m; 0 chooses 0.2 x the largest radius
    int sort_every = 1;       // re-sort particles in space at every n-th list rebuild (0: never)
};

struct Scenario {
    std::vector<Material> materials;
    // pair_properties[a][b] for every pair of material indices, symmetric.
    std::vector<std::vector<PairProperties>> pair_properties;
    ContactModel model;
    Domain domain;
    Vec3 gravity;  // m/s^2
    TimeStepSettings time_step;
    NeighborSettings neighbor;
    std::vector<RigidMotion> motions;
    std::vector<Wall> walls;  // smooth walls besides the box's flat ones (walls/wall.hpp)
    // The triangles of the mesh walls (Wall::mesh indexes them), placed in
    // the lab frame at the start of their wall's motion; m.
    std::vector<TriangleMesh> meshes;
    std::vector<ParticleSpec> particles;
    // Spheres poured in later; Simulation appends them to `particles` (ids
    // go on from the last), so a running simulation's scenario holds every
    // sphere in so far.
    std::vector<Insertion> insertions;

    // The free particles (of every rank, when the run is shared among ranks).
    std::size_t free_count() const {
        std::size_t n = 0;
        for (const ParticleSpec& p : particles) n += p.motion == free_motion;
        return n;
    }
    // The largest particle radius, m (0 with no particles), of those poured
    // in later too.
    double largest_radius() const {
        double largest = 0.0;
        for (const ParticleSpec& p : particles) largest = std::max(largest, p.radius);
        for (const Insertion& q : insertions) largest = std::max(largest, q.radius_max);
        return largest;
    }
};

// The Verlet-list skin a simulation of the scenario uses, m: neighbor.skin,
// or 0.2 x the largest radius if that is 0 (automatic).
double neighbor_skin(const Scenario& s);

// The steps of insertion q's batches: batch k at step first + k period
// (first = ceil(start / dt), period = round(every / dt), at least 1).
struct InsertionSteps {
    std::int64_t first = 0, period = 1;
};
InsertionSteps insertion_steps(const Insertion& q, double dt);

// Reason why a scenario cannot be simulated, or empty if it can. Checks
// materials, pair table completeness and symmetry, particle radii, material
// and motion indices, and that the particles fit in periodic axes.
std::string scenario_problem(const Scenario& s);
// Reason why a prescribed motion cannot be followed (a zero axis, a value
// not finite, an axis whose length overflows), or empty: of the scenario's
// motions and of a new one given to Simulation::set_motion alike.
std::string motion_problem(const RigidMotion& m);

// The largest overlap between two particles of the scenario, relative to the
// smaller radius, and which two (indices into Scenario::particles); or
// between a free particle and a flat wall (a sphere of infinite radius:
// relative to the particle's radius), and which.
struct OverlapReport {
    double ratio = 0.0;  // h / min(R_a, R_b); 0 if nothing touches
    std::size_t a = 0, b = 0;
    int wall = -1;  // the flat wall b overlaps (2 x axis + 0 at lo, 1 at hi; a unused); -1: a and b
};
OverlapReport largest_overlap(const Scenario& s);

}  // namespace tumble
