// SPDX-License-Identifier: MIT
// The pair loop: the contact law applied to a range of the half neighbour
// list. Simulation::compute_forces() runs it, one range per thread; the
// micro-benchmarks (bench/) time it alone.
//
// The loop works through the range in blocks of ContactBlock::capacity
// contacts, in three passes per block:
//   1. gather: find the pairs that touch and copy what the law needs of
//      their two spheres, and their history, into the block (structure of
//      arrays);
//   2. law: the contact law on every contact of the block, several
//      contacts per instruction (SIMD, vectorised by the compiler);
//   3. scatter: add each contact's force and torques to its two spheres,
//      in the order of the pair list, and write the history back.
// Every contact goes through exactly the operations of the scalar law and
// the sums are made in pair order, so the results are bitwise those of one
// contact at a time.
#pragma once

#include <cmath>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "tumble/contact/contact_law.hpp"
#include "tumble/core/parallel.hpp"
#include "tumble/integrate/dashpot.hpp"
#include "tumble/materials/pair_table.hpp"
#include "tumble/neighbor/pair_list.hpp"
#include "tumble/neighbor/periodic_images.hpp"
#include "tumble/particles/particle_store.hpp"

namespace tumble {

// One contact as seen by the force law in the last step (when recording).
// For a contact with a flat wall, id_j is wall_id(face).
struct ContactRecord {
    std::int64_t id_i = 0, id_j = 0;
    ContactGeometry geometry;  // v_n as predicted (the dashpot's force is history.viscous_force)
    ContactForces forces;
    ContactHistory history;  // after the step
};

// The contacts of one block, structure of arrays: one entry per touching
// pair, lane l of every array belongs to pair list entry pair[l]. What the
// law needs of the two spheres and the contact's history are copied in here,
// so that the law's loop reads and writes contiguous arrays only (vector
// loads and stores, which every SIMD instruction set has; scattering the
// history back by pair index would need AVX-512).
struct ContactBlock {
    static constexpr std::size_t capacity = 16;
    struct Vec3s {
        alignas(64) double x[capacity], y[capacity], z[capacity];
        Vec3 operator[](std::size_t l) const { return {x[l], y[l], z[l]}; }
        void set(std::size_t l, const Vec3& v) { x[l] = v.x, y[l] = v.y, z[l] = v.z; }
    };
    std::size_t count = 0;
    alignas(64) std::uint32_t pair[capacity];
    // The pairs of the list found apart while filling the block, and how
    // many (gather_contacts()).
    std::size_t apart_count = 0;
    static constexpr std::size_t apart_capacity = 4 * capacity;
    alignas(64) std::uint32_t apart[apart_capacity];
    alignas(64) std::uint32_t pair_type[capacity];  // PairTable::index() of the two materials
    // Inputs: X_i - X_j (periodic image applied), its square, v_i - v_j and
    // its predicted change (contact/geometry.hpp), the two spheres' radii
    // and angular velocities, 1/m_i + 1/m_j (the dashpot's 1/m*).
    Vec3s d, v_ij, kick_ij, omega_i, omega_j;
    alignas(64) double distance2[capacity], R_i[capacity], R_j[capacity], inverse_mass_sum[capacity];
    // In and out: the contact history (ContactHistory).
    Vec3s slip;
    alignas(64) double angular_slip[capacity], viscous_force[capacity];
    // Outputs of the law.
    Vec3s force_i, torque_i, torque_j;
    alignas(64) double normal_force[capacity], twisting_couple[capacity];

    ContactGeometry geometry(std::size_t l) const {
        return make_contact_geometry(d[l], std::sqrt(distance2[l]), R_i[l], R_j[l], v_ij[l], kick_ij[l], omega_i[l],
                                     omega_j[l]);
    }
    // The history of lane l from and to pair k of the list.
    void load_history(std::size_t l, const PairList& pairs, std::size_t k) {
        slip.set(l, pairs.slip[k]);
        angular_slip[l] = pairs.angular_slip[k];
        viscous_force[l] = pairs.viscous_force[k];
    }
    void store_history(std::size_t l, PairList& pairs, std::size_t k) const {
        pairs.slip[k] = slip[l];
        pairs.angular_slip[k] = angular_slip[l];
        pairs.viscous_force[k] = viscous_force[l];
    }
};

// What the law needs of pair k's two spheres and its history, but their
// separation, into lane l of the block.
inline void copy_inputs(const ParticleStore& p, const PairList& pairs, std::size_t k, const PairTable& table,
                        ContactBlock& b, std::size_t l) {
    const std::uint32_t i = pairs.first[k], j = pairs.second[k];
    b.R_i[l] = p.radius[i];
    b.R_j[l] = p.radius[j];
    b.inverse_mass_sum[l] = p.inv_mass[i] + p.inv_mass[j];
    b.pair_type[l] = table.index(p.material[i], p.material[j]);
    b.v_ij.set(l, p.velocity[i] - p.velocity[j]);
    b.kick_ij.set(l, p.half_kick[i] - p.half_kick[j]);
    b.omega_i.set(l, p.angular_velocity[i]);
    b.omega_j.set(l, p.angular_velocity[j]);
    b.load_history(l, pairs, k);
}

// Pass 1: pairs [k, end) of the list into the block until it is full; the
// pairs found apart drop their history. Returns where it stopped.
//
// Two ways, the same result (studies/performance/LOG.md "The gather in two sweeps,
// the scatter without a branch"):
//   Branch: a pair apart is passed over by a branch, a touching one copied
//     in at once. Best where the branch predicts well: where (nearly)
//     every pair touches, as in a static packing.
//   not Branch: two sweeps, without a branch on whether a pair touches
//     (on the long drum about 3 in 4 do, in no order a predictor learns).
//     The first works out every pair's separation and writes it into the
//     block's next free lane, which only a touching pair keeps (`count +=
//     touching`), and lists the pairs apart alike (either list full ends
//     the block); the second copies the rest into the lanes kept. The
//     pairs apart then drop their history (which only the contacts that
//     ended this step have).
//
// Periodic: whether the domain has a periodic axis; if not, no pair has a
// shift to add, and its code and shift are not read.
template <bool Branch, bool Periodic>
inline std::size_t gather_contacts(const ParticleStore& p, PairList& pairs, std::size_t k, std::size_t end,
                                   const PeriodicImages& images, const PairTable& table, ContactBlock& b) {
    std::size_t count = 0, apart = 0;
    for (; k < end && count < ContactBlock::capacity && apart < ContactBlock::apart_capacity; ++k) {
        const std::uint32_t i = pairs.first[k], j = pairs.second[k];
        const Vec3 d = Periodic ? p.position[i] - p.position[j] + images[pairs.image[k]] : p.position[i] - p.position[j];
        const double distance2 = norm2(d);
        const double reach = p.radius[i] + p.radius[j];
        const bool touching = distance2 < reach * reach;
        if constexpr (Branch) {
            if (!touching) {
                if (!pairs.history(k).is_zero()) pairs.set_history(k, ContactHistory{});  // contact ended
                ++apart;
                continue;
            }
        }
        b.pair[count] = static_cast<std::uint32_t>(k);
        b.d.set(count, d);
        b.distance2[count] = distance2;
        if constexpr (Branch) {
            copy_inputs(p, pairs, k, table, b, count++);
        } else {
            b.apart[apart] = static_cast<std::uint32_t>(k);
            count += touching;
            apart += !touching;
        }
    }
    b.count = count;
    b.apart_count = apart;
    if constexpr (!Branch) {
        // One contact at a time: GCC 12 runs this loop on two contacts per
        // instruction, loading each lane on its own and keeping the arrays'
        // addresses on the stack, which is slower (studies/performance/LOG.md, "The
        // kicks in one pass, the gather's copy one contact at a time").
        // The empty asm hides how l runs, so the loop is not vectorised
        // (GCC 12 has no pragma for that).
        for (std::size_t l = 0; l < count; ++l) {
            asm("" : "+r"(l));
            copy_inputs(p, pairs, b.pair[l], table, b, l);
        }
        // The pairs apart: every one's history zeroed, without reading it
        // first (rarely is there one to drop: the contacts that ended this
        // step); the stores cost less than the loads and the test
        // (studies/performance/LOG.md, "The wall's motion on several spheres per
        // instruction, the pairs apart zeroed without a look").
        for (std::size_t a = 0; a < apart; ++a) pairs.set_history(b.apart[a], ContactHistory{});
    }
    return k;
}

// Pass 2: geometry and contact law of every contact in the block. With a
// Model whose terms are fixed when compiling (AllTermsOn) the compiler runs
// this loop on several contacts per instruction (`ivdep`: the coefficient
// columns it gathers by pair type are not among what it writes). The loop
// vectorises only if the whole law is inlined into it: `flatten` makes sure
// (the paper's saw-tooth window made the law larger than GCC's inlining
// limits, and the loop ran one contact at a time, 3x slower).
template <class Model>
[[gnu::flatten]] inline void apply_contact_law(ContactBlock& b, const PairColumns& coefficients, const Model& model,
                                              double dt) {
#pragma GCC ivdep
    for (std::size_t l = 0; l < b.count; ++l) {
        const PairCoefficients c = coefficients.at(b.pair_type[l]);
        // The history, field by field (a copy of the whole record does not
        // vectorise).
        ContactHistory history;
        history.slip = b.slip[l];
        history.angular_slip = b.angular_slip[l];
        history.viscous_force = b.viscous_force[l];
        ContactGeometry g = b.geometry(l);
        treat_dashpot(g, c, b.inverse_mass_sum[l], dt, history);
        const ContactForces f = contact_law(c, g, model, dt, history);
        b.slip.set(l, history.slip);
        b.angular_slip[l] = history.angular_slip;
        b.viscous_force[l] = history.viscous_force;
        b.force_i.set(l, f.force_i);
        b.torque_i.set(l, f.torque_i);
        b.torque_j.set(l, f.torque_j);
        b.normal_force[l] = f.normal_force;
        b.twisting_couple[l] = f.twisting_couple;
    }
}

// Pass 3: the block's forces onto the spheres, in pair order (Newton's
// third law: j gets -force_i), the history back into the pair list, and the
// records when recording. Every sphere receives the same additions in the
// same order as with one contact at a time. (Keeping i's sums in registers
// while the list's first sphere stays the same needs a branch on its
// change, which a predictor misses: about 1.6 contacts per first sphere.)
template <bool Record>
inline void scatter_contacts(const ParticleStore& p, PairList& pairs, const ContactBlock& b, Vec3* force,
                             Vec3* torque, std::vector<ContactRecord>& records) {
    for (std::size_t l = 0; l < b.count; ++l) {
        const std::size_t k = b.pair[l];
        const std::uint32_t i = pairs.first[k], j = pairs.second[k];
        b.store_history(l, pairs, k);
        force[i] += b.force_i[l];
        force[j] -= b.force_i[l];
        torque[i] += b.torque_i[l];
        torque[j] += b.torque_j[l];
        if constexpr (Record) {
            const ContactForces f{b.force_i[l], b.torque_i[l], b.torque_j[l], b.normal_force[l],
                                  b.twisting_couple[l]};
            records.push_back({p.id[i], p.id[j], b.geometry(l), f, pairs.history(k)});
        }
    }
}

// The pair loop over pairs [range.begin, range.end) of the half list: for
// every candidate pair in contact, build the contact geometry, apply the
// contact law, and add the result to both particles (Newton's third law; the
// half list holds each pair once) in `force` and `torque`. A pair that is
// not touching drops its history. Each thread runs it on its own range of
// pairs into its own force arrays; the force law itself does not change.
template <bool Record, class Model>
void add_contact_forces(const ParticleStore& p, PairList& pairs, IndexRange range, const PeriodicImages& images,
                        const PairTable& table, const Model& model, double dt, Vec3* force, Vec3* torque,
                        std::vector<ContactRecord>& records) {
    const auto loop = [&](auto periodic) {
        constexpr bool Periodic = decltype(periodic)::value;
        ContactBlock block;
        bool all_touched = false;  // by the last block's pairs: then the branch on touching predicts well
        for (std::size_t k = range.begin; k < range.end;) {
            k = all_touched ? gather_contacts<true, Periodic>(p, pairs, k, range.end, images, table, block)
                            : gather_contacts<false, Periodic>(p, pairs, k, range.end, images, table, block);
            all_touched = block.apart_count == 0;
            apply_contact_law(block, table.columns(), model, dt);
            scatter_contacts<Record>(p, pairs, block, force, torque, records);
        }
    };
    if (images.periodic())
        loop(std::true_type{});
    else
        loop(std::false_type{});
}

// The same for a model given at run time: the paper's model (every term on)
// goes to the vectorised law, any other to the law with its switches.
template <bool Record>
void add_contact_forces(const ParticleStore& p, PairList& pairs, IndexRange range, const PeriodicImages& images,
                        const PairTable& table, const ContactModel& model, double dt, Vec3* force, Vec3* torque,
                        std::vector<ContactRecord>& records) {
    auto run = [&](auto all_terms_on) {
        all_terms_on.friction_normal = model.friction_normal;
        all_terms_on.slip_velocity_regularisation = model.slip_velocity_regularisation;
        add_contact_forces<Record>(p, pairs, range, images, table, all_terms_on, dt, force, torque, records);
    };
    if (model.all_terms_on() && model.shear == ShearModel::Paper)
        run(AllTermsOn<ShearModel::Paper>{});
    else if (model.all_terms_on() && model.shear == ShearModel::Coulomb)
        run(AllTermsOn<ShearModel::Coulomb>{});
    else if (model.all_terms_on() && model.shear == ShearModel::Spring)
        run(AllTermsOn<ShearModel::Spring>{});
    else
        add_contact_forces<Record, ContactModel>(p, pairs, range, images, table, model, dt, force, torque, records);
}

}  // namespace tumble
