// SPDX-License-Identifier: MIT
// The contacts of spheres with the walls (walls/wall.hpp; the box's flat
// walls are infinite planes) in blocks, as the pair loop (pair_loop.hpp)
// takes the contacts of pairs: the contacts found one sphere and wall at a
// time are copied into a block (structure of arrays), the contact law runs
// on the whole block several contacts per instruction, and the forces go
// back to the spheres in the order they were found. Every contact goes
// through the operations of the scalar law, and every sphere receives its
// walls' forces in the order of the walls, so the results are bitwise
// those of one contact at a time. Simulation::add_wall_forces() runs it.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "tumble/contact/contact_law.hpp"
#include "tumble/integrate/dashpot.hpp"
#include "tumble/materials/pair_table.hpp"
#include "tumble/sim/pair_loop.hpp"
#include "tumble/walls/wall.hpp"

namespace tumble {

// Up to `capacity` contacts of spheres with walls. Lane l: sphere
// particle[l] (array index) against wall wall[l] (index into the walls in
// force), its history record[l] (index into the history by global id and
// wall slot).
struct WallContactBlock {
    static constexpr std::size_t capacity = ContactBlock::capacity;
    using Vec3s = ContactBlock::Vec3s;
    std::size_t count = 0;
    alignas(64) std::uint32_t particle[capacity];
    alignas(64) std::uint32_t wall[capacity];
    alignas(64) std::size_t record[capacity];
    alignas(64) std::uint32_t pair_type[capacity];  // PairTable::index() of the sphere's and the wall's materials
    // Inputs of make_wall_geometry() and the dashpot's 1/m (the sphere's).
    Vec3s n, v_i, kick_i, omega_i, v_wall, omega_wall;
    alignas(64) double distance[capacity], R_i[capacity], R_star[capacity], inverse_mass[capacity];
    // In and out: the contact history.
    Vec3s slip;
    alignas(64) double angular_slip[capacity], viscous_force[capacity];
    // Outputs of the law.
    Vec3s force_i, torque_i;
    // The last R* found and what it was found from (a square root and a
    // division: the contacts of a drum's mantle have one curvature and few
    // radii).
    double last_R = 0.0, last_curvature = 0.0, last_R_star = 0.0;

    ContactGeometry geometry(std::size_t l) const {
        return make_wall_geometry(n[l], distance[l], R_i[l], R_star[l], v_i[l], kick_i[l], omega_i[l], v_wall[l],
                                  omega_wall[l]);
    }
};

// The contact law on every contact of the block (as apply_contact_law()).
template <class Model>
[[gnu::flatten]] inline void apply_wall_law(WallContactBlock& b, const PairColumns& coefficients, const Model& model,
                                           double dt) {
#pragma GCC ivdep
    for (std::size_t l = 0; l < b.count; ++l) {
        const PairCoefficients c = coefficients.at(b.pair_type[l]);
        ContactHistory history;
        history.slip = b.slip[l];
        history.angular_slip = b.angular_slip[l];
        history.viscous_force = b.viscous_force[l];
        ContactGeometry g = b.geometry(l);
        treat_dashpot(g, c, b.inverse_mass[l], dt, history);
        const ContactForces f = contact_law(c, g, model, dt, history);
        b.slip.set(l, history.slip);
        b.angular_slip[l] = history.angular_slip;
        b.viscous_force[l] = history.viscous_force;
        b.force_i.set(l, f.force_i);
        b.torque_i.set(l, f.torque_i);
    }
}

// The pairs of a sphere and a wall close enough to touch before the
// neighbour list is next rebuilt, with their histories, while every wall
// stays put (stays_put()): built from the spheres' places (in the store's
// order, then by wall) and the history by global id, and used until the
// next rebuild re-sorts the store (or a wall would move), when the
// histories go back. A sphere has then moved at most the skin since the
// list was built (half of it since the last rebuild, at either end), so a
// pair farther apart than the sphere's radius plus the skin does not touch
// before; the others are looked at every step, their histories read in
// turn instead of all over the memory by global id. Empty and not valid
// where a wall moves.
struct WallList {
    bool valid = false;
    std::vector<std::uint32_t> particle, wall;  // the pairs: the sphere's place in the store, the wall's index
    std::vector<std::size_t> record;            // the pair's record in the history by global id
    std::vector<ContactHistory> history;        // its history while the list is valid
};

// What the wall loop works on: the spheres, the walls where their motions
// have carried them, each one's history slot and number (wall_id(): 6 + k
// for the scenario's wall k), the history by global id (`slots` records a
// sphere) with a byte per record that says whether it may be non-zero, the
// pair table, and the loads on the scenario's walls that this chunk sums.
// Mesh walls are left out: they find their own contacts.
struct WallLoop {
    ParticleStore& p;
    const std::vector<PlacedWall>& walls;
    const std::vector<std::size_t>& slot;
    const std::vector<std::size_t>& number;
    std::size_t slots;
    std::vector<ContactHistory>& history;
    std::vector<std::uint8_t>& history_set;
    const PairTable& table;
    double dt;
    WallLoad* loads;
};

// The block's contacts with their histories (histories[b.record[l]]: by
// global id, or the wall list's) through the law, their forces onto the
// spheres in the order the contacts were found (the wall feels -F at the
// contact and the couples' reaction), and the histories back.
template <class Model>
void settle_wall_block(const WallLoop& w, WallContactBlock& b, ContactHistory* histories, const Model& model) {
    for (std::size_t l = 0; l < b.count; ++l) {
        const ContactHistory& h = histories[b.record[l]];
        b.slip.set(l, h.slip);
        b.angular_slip[l] = h.angular_slip;
        b.viscous_force[l] = h.viscous_force;
    }
    apply_wall_law(b, w.table.columns(), model, w.dt);
    for (std::size_t l = 0; l < b.count; ++l) {
        const std::size_t i = b.particle[l], k = b.wall[l];
        ContactHistory& h = histories[b.record[l]];
        h.slip = b.slip[l];
        h.angular_slip = b.angular_slip[l];
        h.viscous_force = b.viscous_force[l];
        const Vec3 f = b.force_i[l], t = b.torque_i[l];
        w.p.force[i] += f;
        w.p.torque[i] += t;
        if (w.number[k] >= 6) {
            WallLoad& load = w.loads[w.number[k] - 6];
            load.force -= f;
            load.torque -= t + cross(w.p.position[i] - w.walls[k].origin, f);
        }
    }
    b.count = 0;
}

// A contact of sphere i with wall k into the next lane of the block: n (lab
// frame, unit, from the wall to the centre), the centre's distance from the
// wall (m), the Hertz radius R* (m), the wall's surface velocity and
// angular velocity at the contact, and where its history is (an index into
// the histories the block is settled with).
inline void put_wall_lane(const WallLoop& w, WallContactBlock& b, std::size_t i, std::size_t k, std::size_t history,
                          const Vec3& n, double distance, double R_star, const Vec3& v_wall, const Vec3& omega_wall) {
    const ParticleStore& p = w.p;
    const std::size_t l = b.count++;
    b.particle[l] = static_cast<std::uint32_t>(i);
    b.wall[l] = static_cast<std::uint32_t>(k);
    b.record[l] = history;
    b.pair_type[l] = w.table.index(p.material[i], w.walls[k].wall->material);
    b.n.set(l, n);
    b.distance[l] = distance;
    b.R_i[l] = p.radius[i];
    b.R_star[l] = R_star;
    b.v_i.set(l, p.velocity[i]);
    b.kick_i.set(l, p.half_kick[i]);
    b.omega_i.set(l, p.angular_velocity[i]);
    b.v_wall.set(l, v_wall);
    b.omega_wall.set(l, omega_wall);
    b.inverse_mass[l] = p.inv_mass[i];
}

// Sphere i against wall k: whether they touch, and if they do, the contact
// into the next lane of the block (its history at `history`, an index into
// the histories the block is settled with). `x` is i's centre in the frame
// of `frame`'s motion once `found`, for the next moving wall of the same
// motion (a still wall is touched in the lab frame, where i's centre is).
inline bool wall_touches(const WallLoop& w, std::size_t i, std::size_t k, std::size_t history, WallContactBlock& b,
                         const MotionNow*& frame, bool& found, Vec3& x) {
    const ParticleStore& p = w.p;
    const PlacedWall& wall = w.walls[k];
    if (surely_beyond(wall, p.position[i], p.radius[i])) return false;
    if (!wall.still && (!found || wall.now != frame)) {
        frame = wall.now;
        found = true;
        x = wall_frame_point(wall, p.position[i]);
    }
    const WallTouch in_wall_frame = frame_touch(wall, wall.still ? p.position[i] : x);
    if (in_wall_frame.distance >= p.radius[i]) return false;
    const WallContact contact = wall_contact_of(wall, p.position[i], in_wall_frame);
    if (p.radius[i] != b.last_R || contact.touch.curvature != b.last_curvature || b.last_R == 0.0) {
        b.last_R = p.radius[i];
        b.last_curvature = contact.touch.curvature;
        b.last_R_star = wall_contact_radius(p.radius[i], contact.touch.curvature);
    }
    put_wall_lane(w, b, i, k, history, contact.touch.n, contact.touch.distance, b.last_R_star, contact.velocity,
                  contact.angular_velocity);
    return true;
}

// Every free sphere of range r nearer to a wall than its radius is in
// contact with it; the others drop their history with it. Most spheres
// touch no wall: for them the loop only finds that the sphere is clear of
// each wall where its motion has carried it (surely_beyond(): a few
// products, no square root, no turning of the sphere into the wall's
// frame), and a history record is read only where history_set says it may
// be non-zero. Near a wall the touch is found where the wall lies if it is
// still (a drum's mantle and caps turning about their axis), else in the
// frame of the wall's motion, the sphere's centre turned into it once for
// all the moving walls of one motion.
template <class Model>
void add_wall_contacts(const WallLoop& w, IndexRange r, const Model& model) {
    const ParticleStore& p = w.p;
    WallContactBlock b;
    for (std::size_t i = r.begin; i < r.end; ++i) {
        if (p.is_kinematic(i)) continue;
        const MotionNow* frame = nullptr;
        bool found = false;
        Vec3 x;
        for (std::size_t k = 0; k < w.walls.size(); ++k) {
            if (w.walls[k].wall->shape == WallShape::mesh) continue;
            const std::size_t record = w.slots * static_cast<std::size_t>(p.id[i]) + w.slot[k];
            if (!wall_touches(w, i, k, record, b, frame, found, x)) {
                if (w.history_set[record]) {
                    w.history[record] = ContactHistory{};
                    w.history_set[record] = 0;
                }
                continue;
            }
            w.history_set[record] = 1;
            // The records lie by global id, all over the memory: asked for
            // now, a block's worth on the way at once costs about as much
            // as one (a record, 40 bytes, spans at most two cache lines).
            __builtin_prefetch(&w.history[record]);
            __builtin_prefetch(reinterpret_cast<const char*>(&w.history[record]) + sizeof(ContactHistory) - 1);
            if (b.count == WallContactBlock::capacity) settle_wall_block(w, b, w.history.data(), model);
        }
    }
    if (b.count > 0) settle_wall_block(w, b, w.history.data(), model);
}

// The same over the wall list's pairs of range r (the list valid): the
// pairs of the list whose sphere lies in r, in the list's order, which is
// that of the loop above; the same contacts in the same order, so the same
// forces, loads and histories, to the bit.
template <class Model>
void add_listed_wall_contacts(const WallLoop& w, WallList& list, IndexRange r, const Model& model) {
    WallContactBlock b;
    const auto first = std::lower_bound(list.particle.begin(), list.particle.end(), r.begin);
    const auto last = std::lower_bound(first, list.particle.end(), r.end);
    const MotionNow* frame = nullptr;
    bool found = false;
    Vec3 x;
    std::size_t sphere = r.end;  // the sphere of the pairs before (x is its)
    for (auto e = static_cast<std::size_t>(first - list.particle.begin());
         e < static_cast<std::size_t>(last - list.particle.begin()); ++e) {
        const std::size_t i = list.particle[e];
        if (i != sphere) {
            sphere = i;
            found = false;
        }
        if (!wall_touches(w, i, list.wall[e], e, b, frame, found, x)) {
            list.history[e] = ContactHistory{};
            continue;
        }
        if (b.count == WallContactBlock::capacity) settle_wall_block(w, b, list.history.data(), model);
    }
    if (b.count > 0) settle_wall_block(w, b, list.history.data(), model);
}

// f(law) with the law for a model given at run time, as
// add_contact_forces(): the paper's model (every term on) as the vectorised
// law's type, any other as the model with its switches.
template <class F>
void with_wall_law(const ContactModel& model, F&& f) {
    auto run = [&](auto all_terms_on) {
        all_terms_on.friction_normal = model.friction_normal;
        all_terms_on.slip_velocity_regularisation = model.slip_velocity_regularisation;
        f(all_terms_on);
    };
    if (model.all_terms_on() && model.shear == ShearModel::Paper)
        run(AllTermsOn<ShearModel::Paper>{});
    else if (model.all_terms_on() && model.shear == ShearModel::Coulomb)
        run(AllTermsOn<ShearModel::Coulomb>{});
    else if (model.all_terms_on() && model.shear == ShearModel::Spring)
        run(AllTermsOn<ShearModel::Spring>{});
    else
        f(model);
}

}  // namespace tumble
