// SPDX-License-Identifier: MIT
#include "tumble/sim/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>
#include <utility>

#include "tumble/core/error.hpp"
#include "tumble/core/isa.hpp"
#include "tumble/core/mpi.hpp"
#include "tumble/core/parallel.hpp"
#include "tumble/integrate/velocity_verlet.hpp"
#include "tumble/particles/rigid_motion.hpp"
#include "tumble/sim/pair_loop.hpp"
#include "tumble/sim/particle_setup.hpp"
#include "tumble/sim/placement.hpp"
#include "tumble/sim/health.hpp"

namespace tumble {

namespace {

// The vertices of a mesh feature (mesh_feature_code), 1 to 3 of them.
std::size_t feature_vertices(const MeshTopology& m, std::uint32_t code, std::array<std::uint32_t, 3>& v) {
    const std::uint32_t id = (code - 1) & ((1u << 30) - 1);
    switch (static_cast<MeshFeature>((code - 1) >> 30)) {
        case MeshFeature::face: v = m.triangles()[id]; return 3;
        case MeshFeature::edge: v = {m.edges()[id][0], m.edges()[id][1], 0}; return 2;
        case MeshFeature::vertex: v = {id, 0, 0}; return 1;
    }
    return 0;
}

// How many vertices two features of a mesh share: 2 for a face and its
// edge or two faces of an edge, 1 for features about one vertex, 0 for
// features apart.
std::size_t shared_vertices(const MeshTopology& m, std::uint32_t a, std::uint32_t b) {
    std::array<std::uint32_t, 3> va{}, vb{};
    const std::size_t na = feature_vertices(m, a, va), nb = feature_vertices(m, b, vb);
    std::size_t shared = 0;
    for (std::size_t i = 0; i < na; ++i)
        for (std::size_t j = 0; j < nb; ++j) shared += va[i] == vb[j];
    return shared;
}

// Whether a code names a feature of the mesh.
bool valid_feature(const MeshTopology& m, std::uint32_t code) {
    if (code == 0) return false;
    const std::uint32_t kind = (code - 1) >> 30, id = (code - 1) & ((1u << 30) - 1);
    return (kind == 0 && id < m.face_count()) || (kind == 1 && id < m.edge_count()) ||
           (kind == 2 && id < m.vertex_count());
}

// The axis a domain is cut along when shared among ranks: its longest (a
// drum's rotation axis z; z, then y, on a tie).
int decomposition_axis(const Domain& d) {
    const Vec3 L = d.length();
    int axis = 2;
    for (int k : {1, 0})
        if (L[k] > L[axis]) axis = k;
    return axis;
}

}  // namespace

Simulation::Simulation(Scenario scenario, int threads, Ranks ranks) : scenario_(std::move(scenario)) {
    if (const std::string why = scenario_problem(scenario_); !why.empty()) throw Error("scenario: " + why);
    set_threads(threads);
    isa_in_use();  // a wrong TUMBLE_ISA is an error here, not in a thread
    pair_table_ = PairTable(scenario_.materials, scenario_.pair_properties, scenario_.model.tangential_stiffness);
    time_step_report_ = assess_time_step(scenario_);
    dt_ = time_step_report_.dt;
    particles_ = make_particle_store(scenario_);
    const double skin = neighbor_skin(scenario_);
    const Domain& box = scenario_.domain;
    for (int axis = 0; axis < 3; ++axis)  // the box's flat walls, facing into the box
        for (int side = 0; side < 2 && box.walls[axis]; ++side) {
            Wall face;
            face.name = std::string(side == 0 ? "lo " : "hi ") + "xyz"[axis];
            face.point = side == 0 ? box.lo : box.hi;
            face.normal = Vec3{};
            face.normal[axis] = side == 0 ? 1.0 : -1.0;
            face.material = box.wall_material;
            walls_.push_back(face);
            wall_slot_.push_back(static_cast<std::size_t>(2 * axis + side));
            wall_number_.push_back(static_cast<std::size_t>(2 * axis + side));
            mesh_wall_.push_back(0);
        }
    const double reach = scenario_.largest_radius();
    for (std::size_t k = 0; k < scenario_.walls.size(); ++k) {
        const Wall& w = scenario_.walls[k];
        walls_.push_back(w);
        wall_slot_.push_back(wall_slots_);
        wall_number_.push_back(6 + k);
        mesh_wall_.push_back(mesh_walls_.size());
        if (w.shape != WallShape::mesh) {
            ++wall_slots_;
            continue;
        }
        const TriangleMesh& mesh = scenario_.meshes[static_cast<std::size_t>(w.mesh)];
        MeshTopology topology(mesh);
        // Cells of the largest radius plus the skin: fewer faces to test near
        // a wall than in cells of the neighbour list's size (the long drum on
        // its mantle in facets: 13 % faster; half that size gains nothing).
        // Each cell lists the faces within that reach too, for the list of the
        // faces near each sphere (MeshList).
        FacetGrid grid(facet_cell(mesh, std::max(reach + skin, 1e-6), reach + skin), reach + skin);
        grid.rebuild(topology);
        mesh_walls_.push_back({std::move(topology), std::move(grid)});
        wall_slots_ += mesh_wall_slots;
    }
    if (!walls_.empty()) {  // by global id
        wall_history_.resize(wall_slots() * particles_.size());
        wall_feature_.resize(wall_history_.size());
        wall_history_set_.assign(wall_history_.size(), 0);
    }
    if (ranks == Ranks::world && mpi::size() > 1) {
        const int axis = decomposition_axis(scenario_.domain);
        slabs_ = std::make_unique<Slabs>(scenario_.domain, axis, particles_, 2.0 * scenario_.largest_radius() + skin);
        slabs_->keep_own(particles_);
        neighbors_ = VerletList(slabs_->local_domain(), skin, scenario_.neighbor.sort_every);
    } else {
        neighbors_ = VerletList(scenario_.domain, skin, scenario_.neighbor.sort_every);
    }
    owned_ = particles_.size();
    inserted_.assign(scenario_.insertions.size(), 0);
    std::size_t total = particles_.size();  // the store's arrays stay where they are as spheres are poured in
    for (const Insertion& q : scenario_.insertions) total += static_cast<std::size_t>(q.count);
    particles_.reserve(total);
    if (!scenario_.insertions.empty() && !scenario_.walls.empty())
        insertion_walls_.emplace(scenario_.walls, scenario_.meshes, reach);
    for (const RigidMotion& m : scenario_.motions) motions_.push_back({m, 0.0});
    move_kinematic(particles_, motions_now(time_), {0, owned_});
    prepare_chunks();
    run_in_team(chunks(), [&](Team& team) {
        rebuild(team);
        locate_kinds(team);
        compute_forces(team, Sums::all, time_, motions_now(time_), [](int, IndexRange) {});
    });
    note_build(time_);
}

// On one rank the Verlet list's rebuild. Shared among ranks (sim/slabs.hpp):
// the histories keyed by global id, the ghosts dropped, the spheres that
// left the slab sent away and those that came taken in, the own spheres
// sorted, the ghosts made anew, and the list found with the keyed histories.
// The store's size changes, and with it the chunks' force arrays.
void Simulation::rebuild(Team& team, bool keep_histories) {
    // The chunks' sums on kinematic particles are never added up
    // (compute_forces()); cleared before the store is sorted anew, so that
    // no particle that takes such a slot finds them. The wall list's
    // histories go back (by chunk 0): its places are about to change.
    team.each([&](int c) {
        if (c == 0 && wall_list_.valid) flush_wall_list();
        if (c == 0) mesh_list_.valid = false;
        const IndexRange r = team.range(c, chunk_force_.size());
        const auto from = static_cast<std::ptrdiff_t>(r.begin), to = static_cast<std::ptrdiff_t>(r.end);
        std::fill(chunk_force_.begin() + from, chunk_force_.begin() + to, Vec3{});
        std::fill(chunk_torque_.begin() + from, chunk_torque_.begin() + to, Vec3{});
    });
    if (!slabs_ && !keep_histories) {
        neighbors_.rebuild(particles_, team);
        return;
    }
    team.one([&] {
        if (!keep_histories) histories_ = keyed_histories(particles_, neighbors_.pairs());
        particles_.resize(owned_);
        if (slabs_ && neighbors_.builds() % Slabs::rebalance_every == 0 && neighbors_.builds() > 0)
            slabs_->rebalance(particles_, owned_, neighbors_.pairs());  // the cuts where the work now is, before the spheres migrate
        if (slabs_) {
            slabs_->migrate(particles_, histories_, wall_history_, wall_feature_, wall_slots());
            std::fill(wall_history_set_.begin(), wall_history_set_.end(), 1);  // the records that came: any
        }
        owned_ = particles_.size();
    });
    neighbors_.arrange(particles_, team);
    team.one([&] {
        if (slabs_) slabs_->make_ghosts(particles_);
        prepare_chunks();
        // Keyed by the spheres' places now that they have them, for lookups in the new list's order.
        history_table_.build(keyed_by_place(histories_, particles_, scenario_.particles.size()), particles_.size());
    });
    neighbors_.find_pairs(particles_, owned_, history_table_, team);
}

// Where the free and the kinematic particles lie in the store, after a
// rebuild (which may have re-sorted it) or a restore: each chunk looks at its
// part, then one thread combines the parts (a few numbers each).
void Simulation::locate_kinds(Team& team) {
    const ParticleStore& p = particles_;
    team.each([&](int c) {
        const IndexRange r = team.range(c, owned_);
        IndexRange kinds{owned_, 0};  // first kinematic, one past the last free; written once (the chunks' entries share a cache line)
        for (std::size_t i = r.begin; i < r.end; ++i)
            if (p.is_kinematic(i))
                kinds.begin = std::min(kinds.begin, i);
            else
                kinds.end = i + 1;
        chunk_kinds_[static_cast<std::size_t>(c)] = kinds;
        const PairList& pairs = neighbors_.pairs();
        const IndexRange list = team.range(c, pairs.size());
        std::size_t first_wall = owned_;
        for (std::size_t k = list.begin; k < list.end; ++k) {
            const std::size_t j = pairs.second[k];
            if (j < first_wall && p.is_kinematic(j)) first_wall = j;
        }
        chunk_first_wall_[static_cast<std::size_t>(c)] = first_wall;
    });
    team.one([&] {
        kinematic_begin_ = owned_;
        free_end_ = 0;
        for (const IndexRange& kinds : chunk_kinds_) {
            kinematic_begin_ = std::min(kinematic_begin_, kinds.begin);
            free_end_ = std::max(free_end_, kinds.end);
        }
        const std::size_t split = kinematic_split();
        wall_from_[0] = split;
        for (std::size_t c = 1; c < chunk_first_wall_.size(); ++c)
            wall_from_[c] = std::clamp(chunk_first_wall_[c], wall_from_[c - 1], owned_);
        wall_from_.back() = owned_;
    });
}

IndexRange Simulation::free_part(IndexRange r) const {
    const std::size_t end = std::min(r.end, free_end_);
    return {std::min(r.begin, end), end};
}

IndexRange Simulation::kinematic_part(IndexRange r) const { return {std::max(r.begin, kinematic_begin_), r.end}; }

// Where the kinematic particles begin when the sort has put them after the
// free ones; owned_ when it has not (then the own spheres are one range).
std::size_t Simulation::kinematic_split() const { return kinematic_begin_ >= free_end_ ? kinematic_begin_ : owned_; }

// Chunk c's own particles: its part of the free ones and its part of the
// kinematic ones, which the sort puts after them (when it has not, one
// range). Each thread moves the wall spheres from the first its part of
// the pairs touches (wall_from_), so that its pairs read wall spheres it
// moved itself, and kicks the share of the grains that evens out the
// phase (studies/performance/LOG.md, "Where two threads lose their tenth" and "The
// wall moved by the thread that reads it").
std::array<IndexRange, 2> Simulation::own_parts(const Team& team, int c) const {
    const std::size_t split = kinematic_split();
    const auto k = static_cast<std::size_t>(c);
    const IndexRange free{free_boundary(c, team.chunks(), split), free_boundary(c + 1, team.chunks(), split)};
    return {free, IndexRange{wall_from_[k], wall_from_[k + 1]}};
}

// Where chunk c's part of the free particles [0, split) begins: the parts
// take equal shares of a step's per-particle work, in which a free particle
// costs 1 and adding another chunk's force sums to it (every chunk c' >= 1
// from touched_from_[c'] on) costs add_weight more. Without it the chunk
// with the list's later particles, which gets every chunk's sums, was the
// slower by 12 us a step on the long drum.
std::size_t Simulation::free_boundary(int c, int chunks, std::size_t split) const {
    // Measured on the long drum (2 threads, an Intel Xeon): 0 (equal counts)
    // 14.54 M grain updates/s, 0.4 14.85 M, 0.8 14.70 M (medians of 3).
    constexpr double add_weight = 0.4;
    const auto cost = [&](std::size_t x) {
        double sum = static_cast<double>(x);
        for (std::size_t part = 1; part < touched_from_.size(); ++part)
            if (x > touched_from_[part]) sum += add_weight * static_cast<double>(x - touched_from_[part]);
        return sum;
    };
    // The wall spheres' shares are uneven (wall_from_): the free particles
    // even out the whole, a wall sphere moved costing wall_weight (on the
    // long drum moving the 5,229 wall spheres takes as long as kicking the
    // 6,481 grains twice: studies/performance/LOG.md, "The wall moved by the
    // thread that reads it").
    constexpr double wall_weight = 1.0;
    const double total = cost(split) + wall_weight * static_cast<double>(owned_ - split);
    double share = 0.0;  // the most of the chunks up to c, so that the parts do not cross
    for (int before = 1; before <= c; ++before)
        share = std::max(share, total * before / chunks -
                                    wall_weight * static_cast<double>(wall_from_[static_cast<std::size_t>(before)] - split));
    std::size_t lo = 0, hi = split;  // the first x whose cost reaches the share
    while (lo < hi) {
        const std::size_t mid = lo + (hi - lo) / 2;
        if (cost(mid) < share) lo = mid + 1; else hi = mid;
    }
    return c == chunks ? split : lo;
}

// Time step `next` of velocity Verlet (integrate/velocity_verlet.hpp) by
// the threads of a team: each takes a part of the particles, then a part of
// the pairs, then its part of the particles again, and waits for the others
// after the first two (a rebuild of the neighbour list adds its own
// phases). The last phase and the first of the next step touch only the
// chunk's own particles, so no wait is needed between them, and where the
// next step follows in the same team (`after` is After::step) the last phase
// also does the next step's kick and drift, in the same pass over the
// particles as the step's last kick (the same numbers, each particle read
// once instead of twice); that step then begins with the drift done
// (`drifted`).
void Simulation::step(Team& team, std::int64_t next, bool drifted, After after) {
    const double half_dt = 0.5 * dt_, time = static_cast<double>(next) * dt_;
    const std::vector<MotionNow> now = motions_now(time);
    ParticleStore& p = particles_;
    // Whether a particle has moved far enough for a rebuild is found as the
    // particles are moved: the kinematic ones here, the free ones in the
    // drift that ends the step before (counted in drifted_far_) or here.
    const auto limit = [&] {
        return DisplacementLimit{neighbors_.positions_at_build(p.size()), neighbors_.rebuild_limit2()};
    };
    const DisplacementLimit since_build = limit();
    // The wall spheres one by one only where their motion's bound comes near the limit.
    const DisplacementLimit walls_since_build = walls_within_limit(time) ? DisplacementLimit{} : since_build;
    clock_.start(team);
    team.each([&](int c) {
        const auto part = static_cast<std::size_t>(c);
        std::size_t far = std::exchange(drifted_far_[part], 0);
        for (const IndexRange r : own_parts(team, c)) {
            if (!drifted)  // v(t) -> v(t + dt/2), x(t) -> x(t + dt); F = 0
                far += kick_drift(p, scenario_.gravity, half_dt, dt_, free_part(r), since_build);
            far += move_kinematic(p, now, kinematic_part(r), walls_since_build);  // prescribed x, v, omega at t + dt; F = 0
            if (after == After::stop) clear_chunk_sums(kinematic_part(r));  // their sums of this step only
        }
        moved_[part] = far > 0 || !since_build.at_build;
    });
    clock_.lap(team, StepPhase::motion);
    const bool moved_here = std::find(moved_.begin(), moved_.end(), 1) != moved_.end();
    if (slabs_) {  // the ghosts where their owners moved them; a rebuild on every rank if one needs it
        team.one([&] {
            slabs_->update_ghosts(p, owned_);
            rebuild_now_ = mpi::any(moved_here);
        });
        clock_.lap(team, StepPhase::exchange);
    }
    if (slabs_ ? rebuild_now_ : moved_here) {
        rebuild(team);
        locate_kinds(team);
        team.one([&] { note_build(time); });
        clock_.lap(team, StepPhase::neighbours);
    }
    const DisplacementLimit since_this_build = limit();  // the list's positions may have changed with a rebuild
    const Sums sums = after == After::stop ? Sums::all : Sums::free;
    compute_forces(team, sums, time, now, [&](int c, IndexRange r) {  // F(t + dt), with v(t + dt/2) and v(t + dt) predicted
        if (after == After::step)  // v(t + dt/2) -> v(t + dt) -> v(t + 3dt/2), x(t + dt) -> x(t + 2dt); F = 0
            drifted_far_[static_cast<std::size_t>(c)] +=
                kick_kick_drift(p, scenario_.gravity, half_dt, dt_, free_part(r), since_this_build);
        else  // v(t + dt/2) -> v(t + dt)
            kick(p, scenario_.gravity, half_dt, free_part(r));
        if (c == 0) {  // the clock, once
            step_ = next;
            time_ = time;
        }
    });
    clock_.stop(team, StepPhase::motion);
}

void Simulation::step() { advance(1); }

void Simulation::set_threads(int threads) {
    if (threads < 1 || threads > max_threads)
        throw Error("threads: need 1 to " + std::to_string(max_threads) + ", got " + std::to_string(threads));
    threads_ = threads;
}

// All the steps in one parallel region (core/parallel.hpp).
// All the steps in one parallel region (core/parallel.hpp), or one region
// from each batch of poured spheres to the next.
void Simulation::advance(std::int64_t steps) {
    while (steps > 0) {
        insert_due();
        const std::int64_t run = std::min(steps, next_insertion_step() - step_);
        prepare_chunks();
        const std::int64_t first = step_;  // step_ is written while the team runs: each step is given its number
        run_in_team(chunks(), [&](Team& team) {
            for (std::int64_t s = 1; s <= run; ++s) step(team, first + s, s > 1, s < run ? After::step : After::stop);
        });
        steps -= run;
    }
}

std::int64_t Simulation::next_insertion_step() const {
    std::int64_t next = std::numeric_limits<std::int64_t>::max();
    for (std::size_t q = 0; q < scenario_.insertions.size(); ++q) {
        if (inserted_[q] >= scenario_.insertions[q].count) continue;
        const InsertionSteps at = insertion_steps(scenario_.insertions[q], dt_);
        const std::int64_t after = step_ + 1;  // the first batch step after step_
        next = std::min(next, after <= at.first ? at.first : at.first + (after - at.first + at.period - 1) / at.period * at.period);
    }
    return next;
}

// A batch: the spheres near its region (every rank's, by global id) and
// the walls where they are now are the obstacles of place_at_random; the
// new spheres get the next global ids on every rank, each rank keeps those
// in its slab, and the list is found anew with the histories by global id.
// The new spheres touch nothing, so every force stays as it is.
void Simulation::insert_due() {
    std::vector<ParticleSpec> poured;
    for (std::size_t q = 0; q < scenario_.insertions.size(); ++q) {
        const Insertion& in = scenario_.insertions[q];
        const InsertionSteps at = insertion_steps(in, dt_);
        if (inserted_[q] >= in.count || step_ < at.first || (step_ - at.first) % at.period != 0) continue;
        const std::int64_t k = (step_ - at.first) / at.period;
        const std::int64_t due = std::min(in.count, (k + 1) * in.batch) - inserted_[q];
        // The obstacles: every sphere whose centre lies within the reach of
        // the region (across a periodic axis, its image nearest the region).
        const double reach = in.radius_max + scenario_.largest_radius();
        const Domain& box = scenario_.domain;
        const auto image = [&](Vec3 x) {
            for (int a = 0; a < 3; ++a)
                if (box.periodic[a]) {
                    const double length = box.hi[a] - box.lo[a];
                    x[a] -= length * std::round((x[a] - 0.5 * (in.lo[a] + in.hi[a])) / length);
                }
            return x;
        };
        const auto near = [&](const Vec3& x) {
            for (int a = 0; a < 3; ++a)
                if (x[a] < in.lo[a] - reach || x[a] > in.hi[a] + reach) return false;
            return true;
        };
        // Shared among ranks, every rank's (their order does not matter: a
        // place is free or not whatever the order of the spheres around it).
        const auto picked = [&](std::size_t i) { return near(image(particles_.position[i])); };
        std::vector<ParticleSpec> existing;
        const auto add = [&](const ParticleStore& q, std::size_t i) {
            existing.push_back({image(q.position[i]), {}, {}, q.radius[i]});
        };
        if (slabs_) {
            const ParticleStore around = slabs_->gather_own(particles_, owned_, picked, Slabs::Everywhere::yes);
            for (std::size_t i = 0; i < around.size(); ++i) add(around, i);
        } else {
            for (std::size_t i = 0; i < owned_; ++i)
                if (picked(i)) add(particles_, i);
        }
        for (const ParticleSpec& p : poured)  // this step's earlier batches
            if (near(image(p.position))) existing.push_back({image(p.position), {}, {}, p.radius});
        ClearOfWalls clear;
        const std::vector<MotionNow> now = motions_now(time_);
        if (insertion_walls_) clear = [&](const Vec3& x, double r) { return insertion_walls_->clear(x, r, now); };
        constexpr std::size_t give_up_after = 10000;  // tries in a row: the region is full for now
        const std::uint64_t seed = splitmix64(in.seed ^ splitmix64(static_cast<std::uint64_t>(k)));
        for (ParticleSpec p : place_at_random(in.lo, in.hi, static_cast<std::size_t>(due), in.radius_min, in.radius_max,
                                              in.material, seed, existing, clear, give_up_after)) {
            p.velocity = in.velocity;
            p.tag = in.tag;
            poured.push_back(p);
            ++inserted_[q];
        }
    }
    if (poured.empty()) return;
    run_in_team(chunks(), [&](Team& team) {
        team.one([&] {
            histories_ = keyed_histories(particles_, neighbors_.pairs());
            particles_.resize(owned_);  // the ghosts go; rebuild() makes them anew
            ParticleStore fresh;
            for (const ParticleSpec& p : poured) {
                add_particle(fresh, p, static_cast<std::int64_t>(scenario_.particles.size()), scenario_.materials);
                scenario_.particles.push_back(p);
            }
            if (slabs_) slabs_->keep_own(fresh);
            for (std::size_t i = 0; i < fresh.size(); ++i) particles_.append(fresh, i);
            owned_ = particles_.size();
            if (!walls_.empty()) {  // by global id: records for the new ids
                const std::size_t records = wall_slots() * scenario_.particles.size();
                wall_history_.resize(records);
                wall_feature_.resize(records);
                wall_history_set_.resize(records, 0);
            }
        });
        rebuild(team, true);
        locate_kinds(team);
    });
    note_build(time_);
}

// The arrays each chunk writes on its own, for the current chunk count
// (zero when the count or the store's size changes).
void Simulation::prepare_chunks() {
    const auto count = static_cast<std::size_t>(chunks());
    const std::size_t extra = (count - 1) * particles_.size();
    if (chunk_force_.size() != extra || touched_from_.size() != count) {
        chunk_force_.assign(extra, Vec3{});
        chunk_torque_.assign(extra, Vec3{});
    }
    touched_from_.resize(count);
    moved_.resize(count);
    drifted_far_.assign(count, 0);
    chunk_wall_load_.resize(count * scenario_.walls.size());
    mesh_contacts_.resize(count);
    chunk_kinds_.resize(count);
    chunk_first_wall_.resize(count);
    if (wall_from_.size() != count + 1) {  // a new chunk count: equal shares of the wall until the next rebuild
        const std::size_t split = kinematic_split();
        wall_from_.resize(count + 1);
        for (std::size_t c = 0; c <= count; ++c) wall_from_[c] = split + (owned_ - split) * c / count;
    }
}

namespace {

// sum[k] += part[k], part[k] = 0 for k in [begin, end): the adding up of one
// thread's forces, on the arrays as plain numbers that do not overlap
// (`__restrict`), so that it runs several per instruction.
void add_and_clear(double* __restrict sum, double* __restrict part, std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
        sum[k] += part[k];
        part[k] = 0.0;
    }
}

}  // namespace

// Forces and torques on every particle from its contacts, in two phases of
// the team, then `then(c, r)` on each part r (chunk c) of the particles,
// whose forces are complete by then. The second phase does not wait at its
// end: what comes next must begin with a phase on the same parts of the
// particles (or end the team). The forces must be zero on entry (kick_drift() leaves
// them so).
//
// Phase 1: chunk c takes the c-th part of the pair list; chunk 0 sums into
// the particles' arrays, chunk c >= 1 into its own. Phase 2: chunk c takes
// its part of the own spheres (own_parts(), and the c-th part of the
// ghosts) and adds the other chunks' sums to theirs, in chunk order, then
// the flat walls. The sums are thus the same bitwise on every run with the
// same chunk count, and differ from one chunk's only by the order of the
// additions (round-off). Recording runs on one chunk.
//
// The list is sorted by first particle and j > i in every pair, so chunk
// c >= 1 touches only particles from the first particle of its part on
// (touched_from_[c]); its arrays are added from there only, and cleared as
// they are read, so they are zero between calls. The parts left out are +0
// (a sum begun at +0 is never -0), so adding them would change nothing.
// The kinematic particles' sums are added only with Sums::all: the step
// does not read them (their motion is prescribed), and with the store
// sorted they are the wall spheres at its end, most of what chunk c >= 1
// touches; adding them at every step cost 2 threads 3 to 5 % of a step on
// the long drum (docs/BENCHMARKS.md). Within an advance() they stay in the
// chunks' arrays; the step that ends it clears its chunks' sums on them
// before its forces (clear_chunk_sums()) and adds them here, so that
// between calls every particle's forces are complete (a user reads the
// load on each wall sphere), as are those from the set-up.
template <class Then>
void Simulation::compute_forces(Team& team, Sums sums, double time, const std::vector<MotionNow>& now, Then&& then) {
    ParticleStore& p = particles_;
    std::vector<PlacedWall> walls;  // where the motions have carried them
    for (const Wall& w : walls_) walls.push_back(place_wall(w, w.motion >= 0 ? &now[static_cast<std::size_t>(w.motion)] : nullptr));
    PairList& pairs = neighbors_.pairs();
    const std::size_t n = p.size();
    if (recording_) records_.clear();
    team.each([&](int c) {
        // The wall list while every wall stays put and the contacts are not
        // recorded, made or given up by chunk 0 (no chunk reads it, nor the
        // wall histories, before the walls' phase below).
        if (c == 0 && !walls.empty()) {
            bool put = !recording_;
            for (const PlacedWall& w : walls) put = put && (w.wall->shape == WallShape::mesh || w.still);
            if (put && !wall_list_.valid) build_wall_list(walls);
            if (!put && wall_list_.valid) flush_wall_list();
            if (!recording_ && !mesh_walls_.empty() && !mesh_list_holds(time)) build_mesh_list(walls, time);
        }
        const IndexRange range = team.range(c, pairs.size());
        const auto part = static_cast<std::size_t>(c);
        Vec3* force = c == 0 ? p.force.data() : chunk_force_.data() + (part - 1) * n;
        Vec3* torque = c == 0 ? p.torque.data() : chunk_torque_.data() + (part - 1) * n;
        touched_from_[part] = range.begin < range.end ? pairs.first[range.begin] : n;
        run_for_isa([&] {
            if (recording_)
                add_contact_forces<true>(p, pairs, range, neighbors_.images(), pair_table_, scenario_.model, dt_,
                                         force, torque, records_);
            else
                add_contact_forces<false>(p, pairs, range, neighbors_.images(), pair_table_, scenario_.model, dt_,
                                          force, torque, records_);
        });
    });
    clock_.lap(team, StepPhase::forces);  // within a step (the clock stands still outside one)
    const auto add_chunk_sums = [&](IndexRange r) {
        for (std::size_t part = 1; part < touched_from_.size(); ++part) {
            const std::size_t from = std::max(r.begin, touched_from_[part]), offset = (part - 1) * n;
            if (from >= r.end) continue;
            run_for_isa([&] {
                add_and_clear(&p.force.data()->x, &(chunk_force_.data() + offset)->x, 3 * from, 3 * r.end);  // 3 numbers per vector
                add_and_clear(&p.torque.data()->x, &(chunk_torque_.data() + offset)->x, 3 * from, 3 * r.end);
            });
        }
    };
    team.each_own([&](int c) {
        // The chunk's own spheres are split as in step()'s first phase, which
        // follows without a wait; the ghosts (after them) apart: their sums
        // are only cleared for the next call (no ghost's force is used).
        const IndexRange ghosts = team.range(c, n - owned_);
        add_chunk_sums({owned_ + ghosts.begin, owned_ + ghosts.end});
        const std::array<IndexRange, 2> own = own_parts(team, c);  // free, kinematic
        add_chunk_sums(own[0]);
        if (sums == Sums::all) add_chunk_sums(own[1]);
        const std::size_t n_walls = scenario_.walls.size(), part = static_cast<std::size_t>(c);
        std::fill_n(chunk_wall_load_.begin() + static_cast<std::ptrdiff_t>(part * n_walls), n_walls, WallLoad{});
        for (const IndexRange r : own) {
            if (!walls_.empty()) add_wall_forces(r, walls, c);
            then(c, r);
        }
    });
}

// Chunks 1, 2, ...: their sums on particles r set to zero (none if r is
// empty: kinematic_part() of a range without one begins after its end).
void Simulation::clear_chunk_sums(IndexRange r) {
    if (r.begin >= r.end) return;
    const std::size_t n = particles_.size();
    for (std::size_t part = 1; part < touched_from_.size(); ++part) {
        const auto from = static_cast<std::ptrdiff_t>((part - 1) * n + r.begin);
        const auto to = static_cast<std::ptrdiff_t>((part - 1) * n + r.end);
        std::fill(chunk_force_.begin() + from, chunk_force_.begin() + to, Vec3{});
        std::fill(chunk_torque_.begin() + from, chunk_torque_.begin() + to, Vec3{});
    }
}

// The walls (walls/wall.hpp; the box's flat walls are infinite planes):
// every free sphere of range r nearer to a wall than its radius is in
// contact with it; a mesh wall gives its contacts by itself. Each particle
// only touches its own forces and wall histories, and chunk c its own sums
// of the loads on the walls. The analytic walls' contacts go through the
// law in blocks (sim/wall_loop.hpp), then the meshes' one at a time; when
// the contacts are recorded, every one one at a time, in the same order
// for each sphere (its analytic walls, then its meshes), so with the same
// sums.
void Simulation::add_wall_forces(IndexRange r, const std::vector<PlacedWall>& walls, int c) {
    ParticleStore& p = particles_;
    const std::size_t slots = wall_slots();
    std::array<MeshTouch, mesh_wall_slots> touches;
    // f(i, k, touches, n) for the contacts of each free sphere of range q
    // with each mesh wall: from the list where it is valid, else by the
    // facet grid.
    const auto each_mesh_contact = [&](IndexRange q, auto&& f) {
        if (mesh_walls_.empty()) return;
        const auto sphere_on = [&](std::size_t i, std::size_t k, std::span<const std::uint32_t> faces, const Vec3& x) {
            f(i, k, touches, mesh_touches(i, k, walls[k], c, x, faces, touches));
        };
        if (!mesh_list_.valid) {
            for (std::size_t i = q.begin; i < q.end; ++i)
                for (std::size_t k = 0; k < walls.size() && !p.is_kinematic(i); ++k)
                    if (walls[k].wall->shape == WallShape::mesh) {
                        const Vec3 x = to_start_frame(walls[k].now, p.position[i]);
                        sphere_on(i, k, mesh_walls_[mesh_wall_[k]].grid.candidates(x), x);
                    }
            return;
        }
        const MeshList& m = mesh_list_;  // the listed spheres of q
        const auto first = std::lower_bound(m.sphere.begin(), m.sphere.end(), q.begin) - m.sphere.begin();
        const auto last = std::lower_bound(m.sphere.begin() + first, m.sphere.end(), q.end) - m.sphere.begin();
        for (auto e = static_cast<std::size_t>(first); e < static_cast<std::size_t>(last); ++e) {
            // The records by global id lie all over the memory: those of the
            // sphere a few entries on asked for now, on their way while
            // this one's contacts are found.
            if (constexpr std::size_t ahead = 4; e + ahead < static_cast<std::size_t>(last)) {
                const std::size_t record =
                    slots * static_cast<std::size_t>(p.id[m.sphere[e + ahead]]) + wall_slot_[m.wall[e + ahead]];
                __builtin_prefetch(&wall_history_set_[record]);
                __builtin_prefetch(&wall_feature_[record]);
                __builtin_prefetch(&wall_history_[record]);
            }
            const std::size_t i = m.sphere[e], k = m.wall[e];
            sphere_on(i, k, {m.faces.data() + m.start[e], m.faces.data() + m.start[e + 1]},
                      to_start_frame(walls[k].now, p.position[i]));
        }
    };
    if (!recording_) {
        WallLoad* loads = chunk_wall_load_.data() + static_cast<std::size_t>(c) * scenario_.walls.size();
        const WallLoop loop{p, walls, wall_slot_, wall_number_, slots, wall_history_, wall_history_set_, pair_table_, dt_, loads};
        WallList* list = wall_list_.valid ? &wall_list_ : nullptr;
        run_for_isa([&] {
            with_wall_law(scenario_.model, [&](const auto& law) {
                if (list)
                    add_listed_wall_contacts(loop, *list, r, law);
                else
                    add_wall_contacts(loop, r, law);
                // The meshes' contacts after all the analytic walls': each
                // sphere's forces are added in the same order as one at a time.
                WallContactBlock b;
                each_mesh_contact(r, [&](std::size_t i, std::size_t k, const auto& touch, std::size_t n) {
                    for (std::size_t j = 0; j < n; ++j) {
                        // A face is flat, and an edge or a vertex touched by a
                        // sphere is taken as flat too: R* = R.
                        put_wall_lane(loop, b, i, k, touch[j].record, touch[j].n, touch[j].distance, p.radius[i],
                                      touch[j].velocity, touch[j].angular_velocity);
                        if (b.count == WallContactBlock::capacity) settle_wall_block(loop, b, wall_history_.data(), law);
                    }
                });
                if (b.count > 0) settle_wall_block(loop, b, wall_history_.data(), law);
            });
        });
        return;
    }
    for (std::size_t i = r.begin; i < r.end; ++i) {
        if (p.is_kinematic(i)) continue;
        for (std::size_t k = 0; k < walls.size(); ++k) {
            if (walls[k].wall->shape == WallShape::mesh) continue;
            const std::size_t record = slots * static_cast<std::size_t>(p.id[i]) + wall_slot_[k];
            ContactHistory& history = wall_history_[record];
            const WallContact wall = wall_contact(walls[k], p.position[i]);
            const WallTouch& t = wall.touch;
            if (t.distance >= p.radius[i]) {
                history = ContactHistory{};
                wall_history_set_[record] = 0;
                continue;
            }
            wall_history_set_[record] = 1;
            add_wall_contact(i, k, walls[k], t.n, t.distance, wall_contact_radius(p.radius[i], t.curvature),
                             wall.velocity, wall.angular_velocity, history, c);
        }
        each_mesh_contact({i, i + 1}, [&](std::size_t, std::size_t k, const auto& touch, std::size_t n) {
            for (std::size_t j = 0; j < n; ++j)
                add_wall_contact(i, k, walls[k], touch[j].n, touch[j].distance, p.radius[i], touch[j].velocity,
                                 touch[j].angular_velocity, wall_history_[touch[j].record], c);
        });
    }
}

void Simulation::add_wall_contact(std::size_t i, std::size_t k, const PlacedWall& wall, const Vec3& n, double distance,
                                  double contact_radius, const Vec3& wall_velocity, const Vec3& wall_angular_velocity,
                                  ContactHistory& history, int c) {
    ParticleStore& p = particles_;
    ContactGeometry g = make_wall_geometry(n, distance, p.radius[i], contact_radius, p.velocity[i], p.half_kick[i],
                                           p.angular_velocity[i], wall_velocity, wall_angular_velocity);
    const PairCoefficients& coefficients = pair_table_(p.material[i], wall.wall->material);
    treat_dashpot(g, coefficients, p.inv_mass[i], dt_, history);
    const ContactForces f = contact_law(coefficients, g, scenario_.model, dt_, history);
    p.force[i] += f.force_i;
    p.torque[i] += f.torque_i;
    const std::size_t number = wall_number_[k];
    if (number >= 6) {  // the wall feels -F at the contact, and the couples' reaction
        WallLoad& load = chunk_wall_load_[static_cast<std::size_t>(c) * scenario_.walls.size() + (number - 6)];
        load.force -= f.force_i;
        load.torque -= f.torque_i + cross(p.position[i] - wall.origin, f.force_i);
    }
    if (recording_) records_.push_back({p.id[i], wall_id(number), g, f, history});
}

// A mesh wall (walls/mesh.hpp): the centre carried into the mesh's frame at
// the start of its motion, where its grid was built; the contacts there,
// the S deepest of them, each in a history slot of its own (docs/MODEL.md,
// "Walls"): a slot follows its contact from feature to feature. With one
// contact before and one after, the slot carries over whatever the
// features; otherwise a new contact takes the slot of the same feature,
// else of a feature that shares vertices with it (the pairs that share the
// most first: in a V of triangles a face's successor on its side shares an
// edge with it, the other side's face a vertex at most), else a free slot
// afresh. Slots no contact took are cleared.
std::size_t Simulation::mesh_touches(std::size_t i, std::size_t k, const PlacedWall& wall, int c, const Vec3& x,
                                     std::span<const std::uint32_t> faces, std::array<MeshTouch, mesh_wall_slots>& out) {
    constexpr std::size_t S = mesh_wall_slots, none = S;
    ParticleStore& p = particles_;
    const MeshWall& mesh = mesh_walls_[mesh_wall_[k]];
    const std::size_t first = wall_slots() * static_cast<std::size_t>(p.id[i]) + wall_slot_[k];
    ContactHistory* history = wall_history_.data() + first;
    std::uint32_t* feature = wall_feature_.data() + first;
    std::vector<MeshContact>& found = mesh_contacts_[static_cast<std::size_t>(c)];
    const double R = p.radius[i];
    // Most spheres touch no mesh and held no contact with it at the last
    // step: they end here, their slots' records (by global id, all over the
    // memory) unread. The byte of the first slot says whether any may hold
    // one (1 after a restore or a migration: any).
    std::uint8_t& held = wall_history_set_[first];
    if (faces.empty() && !held) return 0;
    mesh_contacts(mesh.topology, x, R, faces, found);
    if (found.empty() && !held) return 0;
    held = found.empty() ? 0 : 1;
    if (found.size() > S) {  // the S deepest, otherwise in their order
        std::stable_sort(found.begin(), found.end(),
                         [](const MeshContact& a, const MeshContact& b) { return a.overlap > b.overlap; });
        found.resize(S);
    }
    const std::size_t n = found.size();
    std::array<std::uint32_t, S> code{};
    for (std::size_t j = 0; j < n; ++j) code[j] = mesh_feature_code(found[j].feature, found[j].id);
    std::array<std::size_t, S> slot_of;
    slot_of.fill(none);
    std::array<bool, S> taken{};
    std::size_t active = 0, last = none;
    for (std::size_t s = 0; s < S; ++s)
        if (feature[s] != 0) ++active, last = s;
    if (n == 1 && active == 1) {
        slot_of[0] = last;
        taken[last] = true;
    } else if (active > 0) {
        for (std::size_t j = 0; j < n; ++j)  // the same feature
            for (std::size_t s = 0; s < S && slot_of[j] == none; ++s)
                if (!taken[s] && feature[s] == code[j]) slot_of[j] = s, taken[s] = true;
        for (;;) {  // a feature that shares vertices with it, the most first
            std::size_t best = 0, best_j = none, best_s = none;
            for (std::size_t j = 0; j < n; ++j)
                for (std::size_t s = 0; s < S && slot_of[j] == none; ++s)
                    if (!taken[s] && feature[s] != 0) {
                        const std::size_t shared = shared_vertices(mesh.topology, feature[s], code[j]);
                        if (shared > best) best = shared, best_j = j, best_s = s;
                    }
            if (best_j == none) break;
            slot_of[best_j] = best_s;
            taken[best_s] = true;
        }
    }
    for (std::size_t s = 0; s < S; ++s)  // the records no contact took
        if (!taken[s]) {
            if (!history[s].is_zero()) history[s] = ContactHistory{};
            feature[s] = 0;
        }
    for (std::size_t j = 0; j < n; ++j) {
        for (std::size_t s = 0; s < S && slot_of[j] == none; ++s)  // a new contact: a free slot
            if (!taken[s]) slot_of[j] = s, taken[s] = true;
        feature[slot_of[j]] = code[j];
        MeshTouch& t = out[j];
        t.record = first + slot_of[j];
        t.n = to_lab_direction(wall.now, found[j].n);
        t.distance = R - found[j].overlap;
        surface_motion(wall.now, p.position[i] - t.distance * t.n, t.velocity, t.angular_velocity);
    }
    return n;
}

// The wall list (sim/wall_loop.hpp) of the own spheres where they are now:
// every pair of a free sphere and a wall that is not surely farther apart
// than the sphere's radius plus the skin, with its history; the records of
// the others set to zero (they would be at this step: no such pair
// touches).
void Simulation::build_wall_list(const std::vector<PlacedWall>& walls) {
    const ParticleStore& p = particles_;
    const std::size_t slots = wall_slots();
    const double skin = neighbors_.skin();
    WallList& list = wall_list_;
    list.particle.clear();
    list.wall.clear();
    list.record.clear();
    list.history.clear();
    for (std::size_t i = 0; i < owned_; ++i) {
        if (p.is_kinematic(i)) continue;
        for (std::size_t k = 0; k < walls.size(); ++k) {
            if (walls[k].wall->shape == WallShape::mesh) continue;  // it finds its own contacts
            const std::size_t record = slots * static_cast<std::size_t>(p.id[i]) + wall_slot_[k];
            if (surely_beyond(walls[k], p.position[i], p.radius[i] + skin)) {
                if (wall_history_set_[record]) {
                    wall_history_[record] = ContactHistory{};
                    wall_history_set_[record] = 0;
                }
                continue;
            }
            list.particle.push_back(static_cast<std::uint32_t>(i));
            list.wall.push_back(static_cast<std::uint32_t>(k));
            list.record.push_back(record);
            list.history.push_back(wall_history_[record]);
        }
    }
    list.valid = true;
}

// The wall list's histories back to the records by global id; the list no
// longer valid.
void Simulation::flush_wall_list() {
    WallList& list = wall_list_;
    for (std::size_t e = 0; e < list.record.size(); ++e) {
        wall_history_[list.record[e]] = list.history[e];
        wall_history_set_[list.record[e]] = 1;
    }
    list = WallList{};
}

void Simulation::build_mesh_list(const std::vector<PlacedWall>& walls, double time) {
    const ParticleStore& p = particles_;
    MeshList& list = mesh_list_;
    list.sphere.clear();
    list.wall.clear();
    list.start.assign(1, 0);
    list.faces.clear();
    list.reach.assign(walls.size(), 0.0);
    list.time = time;
    const Vec3* seen = neighbors_.positions_at_build(p.size());
    list.valid = seen != nullptr;  // (none: the facet grid's path until the next rebuild)
    if (!seen) return;
    const double skin = neighbors_.skin();
    for (std::size_t i = 0; i < owned_; ++i) {
        if (p.is_kinematic(i)) continue;
        for (std::size_t k = 0; k < walls.size(); ++k) {
            if (walls[k].wall->shape != WallShape::mesh) continue;
            const MeshWall& mesh = mesh_walls_[mesh_wall_[k]];
            if (const MotionNow* now = walls[k].now)
                list.reach[k] = std::max(list.reach[k], distance_from_axis(seen[i], now->axis_point, now->turn.u));
            const Vec3 x = to_start_frame(walls[k].now, seen[i]);
            faces_within(mesh.topology, x, p.radius[i] + skin, mesh.grid.candidates(x), list.faces);
            if (list.faces.size() > list.start.back()) {
                list.sphere.push_back(static_cast<std::uint32_t>(i));
                list.wall.push_back(static_cast<std::uint32_t>(k));
                list.start.push_back(static_cast<std::uint32_t>(list.faces.size()));
                continue;
            }
            // Left out: no contact with this mesh until the list is made anew.
            const std::size_t first = wall_slots() * static_cast<std::size_t>(p.id[i]) + wall_slot_[k];
            if (!wall_history_set_[first]) continue;
            std::fill_n(wall_history_.begin() + static_cast<std::ptrdiff_t>(first), mesh_wall_slots, ContactHistory{});
            std::fill_n(wall_feature_.begin() + static_cast<std::ptrdiff_t>(first), mesh_wall_slots, 0u);
            wall_history_set_[first] = 0;
        }
    }
}

bool Simulation::mesh_list_holds(double time) const {
    if (!mesh_list_.valid) return false;
    const double limit = 0.9 * std::sqrt(neighbors_.rebuild_limit2());  // of half the skin
    for (std::size_t k = 0; k < walls_.size(); ++k) {
        if (walls_[k].shape != WallShape::mesh || walls_[k].motion < 0) continue;
        const RigidMotion& m = motions_[static_cast<std::size_t>(walls_[k].motion)].motion;
        if (rigid_displacement_bound(m.velocity, m.angular_velocity, time - mesh_list_.time, mesh_list_.reach[k]) >= limit)
            return false;
    }
    return true;
}

std::vector<WallLoad> Simulation::wall_loads() const {
    const std::size_t n_walls = scenario_.walls.size();
    std::vector<WallLoad> sum(n_walls);
    for (std::size_t c = 0; c * n_walls < chunk_wall_load_.size(); ++c)
        for (std::size_t k = 0; k < n_walls; ++k) {
            sum[k].force += chunk_wall_load_[c * n_walls + k].force;
            sum[k].torque += chunk_wall_load_[c * n_walls + k].torque;
        }
    if (slabs_) {
        std::vector<double> numbers;
        for (const WallLoad& l : sum)
            for (const Vec3& v : {l.force, l.torque}) numbers.insert(numbers.end(), {v.x, v.y, v.z});
        mpi::sum(numbers);
        for (std::size_t k = 0; k < n_walls; ++k) {
            sum[k].force = {numbers[6 * k], numbers[6 * k + 1], numbers[6 * k + 2]};
            sum[k].torque = {numbers[6 * k + 3], numbers[6 * k + 4], numbers[6 * k + 5]};
        }
    }
    return sum;
}

void Simulation::note_build(double time) {
    const ParticleStore& p = particles_;
    motion_reach_.clear();
    for (std::size_t k = 0; k < motions_.size(); ++k) {
        const RigidMotion& m = motions_[k].motion;
        const Vec3 u = m.unit_axis();
        double reach = 0.0;
        for (std::size_t i = 0; i < owned_; ++i)
            if (p.motion[i] == static_cast<std::int32_t>(k))
                reach = std::max(reach, distance_from_axis(p.reference_position[i], m.axis_point, u));
        motion_reach_.push_back(reach);
    }
    list_time_ = time;
}

// Each motion carries its spheres at most rigid_displacement_bound() from
// where the list saw them. Below 0.9 of the limit (half the skin) that
// bound leaves room for far more than the round-off between it and the
// spheres' positions, so the spheres would all be found within the limit,
// as when each is checked: the rebuilds, and the results, are the same.
bool Simulation::walls_within_limit(double time) const {
    if (!list_time_) return false;
    const double limit = 0.9 * std::sqrt(neighbors_.rebuild_limit2());
    for (std::size_t k = 0; k < motions_.size(); ++k) {
        const RigidMotion& m = motions_[k].motion;
        if (rigid_displacement_bound(m.velocity, m.angular_velocity, time - *list_time_, motion_reach_[k]) >= limit)
            return false;
    }
    return true;
}

// Per motion: where the axis is now and the rotation since the motion
// began, worked out once per step for all its particles.
std::vector<MotionNow> Simulation::motions_now(double time) const {
    std::vector<MotionNow> now;
    for (const MotionClock& m : motions_) {
        const double elapsed = time - m.start_time;
        now.push_back({m.motion.axis_point, m.motion.axis_point + elapsed * m.motion.velocity, m.motion.velocity,
                       Rotation(m.motion.unit_axis(), m.motion.angular_velocity * elapsed), m.motion.angular_velocity});
    }
    return now;
}

void Simulation::set_motion(std::size_t k, const RigidMotion& motion) {
    if (k >= motions_.size()) throw Error("set_motion: no motion " + std::to_string(k));
    if (auto why = motion_problem(motion); !why.empty())
        throw Error("set_motion: motion " + std::to_string(k) + ": " + why);
    // As a scenario's motions are checked when it is read (reach: the
    // farthest of the surfaces that follow it from the new axis, where they
    // are now; -1: none follows it).
    const Vec3 u = motion.unit_axis();
    double reach = -1.0;
    for (std::size_t i = 0; i < owned_; ++i)
        if (particles_.motion[i] == static_cast<std::int32_t>(k))
            reach = std::max(reach, distance_from_axis(particles_.position[i], motion.axis_point, u) + particles_.radius[i]);
    if (slabs_) reach = mpi::max(reach);
    reach = std::max(reach, walls_reach(scenario_, k, motion, &motions_now(time_)[k]));
    if (auto why = motion_speed_problem(scenario_, motion, reach); !why.empty())
        throw Error("set_motion: motion " + std::to_string(k) + ": " + why);
    ParticleStore& p = particles_;
    for (std::size_t i = 0; i < owned_; ++i)
        if (p.motion[i] == static_cast<std::int32_t>(k)) p.reference_position[i] = p.position[i] - p.image_shift[i];
    motions_[k] = {motion, time_};
    scenario_.motions[k] = motion;
    move_kinematic(particles_, motions_now(time_), {0, owned_});
    list_time_.reset();  // the motion's bound holds from now on, not from the build
    mesh_list_.valid = false;
}

SimulationState Simulation::capture() const {
    std::vector<ContactHistory> wall_history = wall_history_;
    for (std::size_t e = 0; e < wall_list_.record.size(); ++e)  // the wall list's, where it is valid
        wall_history[wall_list_.record[e]] = wall_list_.history[e];
    return {particles_, neighbors_.state(), std::move(wall_history), wall_feature_, motions_, inserted_, dt_, time_, step_, owned_,
            slabs_ ? slabs_->state() : SlabState{}, slabs_ ? mpi::size() : 1};
}

ParticleStore Simulation::gathered() const { return slabs_ ? slabs_->gather_own(particles_, owned_) : particles_; }

namespace {

// Reason why a captured state cannot belong to a run of the scenario whose
// particles are `fresh` (as built from it), or empty. On one rank the state
// holds every particle; shared among ranks, the rank's own and its ghosts.
// A state is input (a checkpoint file): every index, count and size is
// checked before use.
std::string state_problem(const SimulationState& s, const ParticleStore& fresh, bool shared) {
    const std::size_t n = fresh.size();
    const ParticleStore& p = s.particles;
    const std::size_t held = p.size();
    for (std::size_t size : {p.position.size(), p.velocity.size(), p.angular_velocity.size(), p.force.size(),
                             p.torque.size(), p.radius.size(), p.inv_mass.size(), p.inv_inertia.size(), p.mass.size(),
                             p.material.size(), p.motion.size(), p.tag.size(), p.reference_position.size(),
                             p.image_shift.size()})
        if (size != held || (!shared && held != n) || s.owned > held || (!shared && s.owned != n))
            return "it holds " + std::to_string(held) + " particles (or fields of unequal length), the scenario " +
                   std::to_string(n);
    std::vector<bool> seen(n, false);
    for (std::size_t k = 0; k < held; ++k) {
        const std::int64_t id = p.id[k];
        if (id < 0 || static_cast<std::size_t>(id) >= n || (k < s.owned && seen[static_cast<std::size_t>(id)]))
            return "the particle ids are not among the numbers 0 .. " + std::to_string(n - 1) + " each once";
        seen[static_cast<std::size_t>(id)] = true;
    }
    // What the scenario fixes for each particle must be as it says.
    std::vector<std::size_t> by_id(n);
    for (std::size_t i = 0; i < n; ++i) by_id[static_cast<std::size_t>(fresh.id[i])] = i;
    for (std::size_t k = 0; k < held; ++k) {
        const std::size_t i = by_id[static_cast<std::size_t>(p.id[k])];
        if (p.material[k] != fresh.material[i] || p.motion[k] != fresh.motion[i] || p.tag[k] != fresh.tag[i] ||
            p.radius[k] != fresh.radius[i] || p.mass[k] != fresh.mass[i] || p.inv_mass[k] != fresh.inv_mass[i] ||
            p.inv_inertia[k] != fresh.inv_inertia[i])
            return "particle " + std::to_string(p.id[k]) +
                   " differs from the scenario's in its material, motion, tag, radius or mass";
    }
    const PairList& pairs = s.neighbors.pairs;
    const std::size_t n_pairs = pairs.size();
    if (pairs.second.size() != n_pairs || pairs.image.size() != n_pairs ||
        pairs.slip.size() != n_pairs || pairs.angular_slip.size() != n_pairs || pairs.viscous_force.size() != n_pairs)
        return "the neighbour pairs have fields of unequal length";
    for (std::size_t k = 0; k < pairs.size(); ++k)
        if (pairs.first[k] >= s.owned || pairs.second[k] >= held || pairs.image[k] >= 27)
            return "neighbour pair " + std::to_string(k) + " refers to a particle or image that does not exist";
        else if (pairs.first[k] >= pairs.second[k] || (k > 0 && pairs.first[k] < pairs.first[k - 1]))
            return "neighbour pair " + std::to_string(k) + " is out of order (lower index first, sorted by it)";
    if (s.neighbors.position_at_build.size() != held) return "the positions at the last neighbour build do not match";
    if (shared && (s.slabs.cuts.size() != static_cast<std::size_t>(s.ranks) + 1 ||
                   !std::is_sorted(s.slabs.cuts.begin(), s.slabs.cuts.end())))
        return "its slab cuts are missing or out of order";
    for (int side = 0; side < 2; ++side) {
        const auto sd = static_cast<std::size_t>(side);
        for (std::uint32_t i : s.slabs.send[sd])
            if (i >= s.owned) return "a ghost it sends is not one of its own particles";
        if (s.slabs.receive_begin[sd] + s.slabs.receive_count[sd] > held ||
            (s.slabs.receive_count[sd] > 0 && s.slabs.receive_begin[sd] < s.owned))
            return "the ghosts it receives lie outside its store";
    }
    if (s.step < 0 || s.time != static_cast<double>(s.step) * s.dt) return "its time is not its step times its dt";
    return "";
}

}  // namespace

void Simulation::restore(SimulationState state) {
    const int ranks = slabs_ ? mpi::size() : 1;
    // A one-rank state shared out among the ranks, or the whole state made
    // of several ranks' (whole_state()): the list is found anew.
    const bool onto_ranks = (slabs_ && state.ranks == 1) || state.list_from_histories;
    std::string why = state.ranks != ranks && !onto_ranks
                          ? "it was captured on " + std::to_string(state.ranks) + " ranks, this run has " +
                                std::to_string(ranks) + " (a state of several ranks restores only on as many)"
                          : state_problem(state, make_particle_store(scenario_), state.ranks > 1);
    if (why.empty() && state.dt != dt_) {
        std::ostringstream text;
        text.precision(17);
        text << "its time step " << state.dt << " s differs from the scenario's " << dt_ << " s";
        why = text.str();
    }
    if (why.empty() && (state.wall_history.size() != wall_history_.size() ||
                        state.wall_feature.size() != wall_feature_.size()))
        why = "its wall-contact history does not match the domain's walls and the scenario's";
    for (std::size_t f = 0; why.empty() && f < state.wall_feature.size(); ++f) {
        const std::size_t slot = f % wall_slots();
        const std::uint32_t code = state.wall_feature[f];
        if (code == 0) continue;
        const auto after = static_cast<std::size_t>(std::upper_bound(wall_slot_.begin(), wall_slot_.end(), slot) - wall_slot_.begin());
        const std::size_t k = after - 1;  // the wall the slot belongs to (none when after is 0)
        if (after == 0 || walls_[k].shape != WallShape::mesh || !valid_feature(mesh_walls_[mesh_wall_[k]].topology, code))
            why = "its wall-contact history names a mesh feature that the scenario's walls do not have";
    }
    if (why.empty() && state.motions.size() != motions_.size()) why = "its number of prescribed motions differs";
    if (why.empty() && state.inserted.size() != inserted_.size()) why = "its number of insertions differs";
    for (std::size_t q = 0; why.empty() && q < state.inserted.size(); ++q)
        if (state.inserted[q] < 0 || state.inserted[q] > scenario_.insertions[q].count)
            why = "insertion " + std::to_string(q) + " has poured in more spheres than its count, or fewer than none";
    if (!why.empty()) throw Error("restoring a simulation state: " + why);
    particles_ = std::move(state.particles);
    particles_.half_kick.assign(particles_.size(), Vec3{});  // 0 between steps
    chunk_force_.clear();  // the chunks' sums anew for this store (prepare_chunks())
    chunk_torque_.clear();
    wall_history_ = std::move(state.wall_history);
    wall_feature_ = std::move(state.wall_feature);
    wall_history_set_.assign(wall_history_.size(), 1);  // any record may be set
    wall_list_ = WallList{};  // found anew at the next step
    mesh_list_ = MeshList{};
    motions_ = std::move(state.motions);
    inserted_ = std::move(state.inserted);
    for (std::size_t k = 0; k < motions_.size(); ++k) scenario_.motions[k] = motions_[k].motion;
    time_ = state.time;
    step_ = state.step;
    if (onto_ranks) {  // the rank's slab of the whole state, its ghosts and list anew
        histories_ = keyed_histories(particles_, state.neighbors.pairs);
        if (slabs_) slabs_->keep_own(particles_);
        owned_ = particles_.size();
        neighbors_.restore({{}, {}, state.neighbors.builds});
        prepare_chunks();
        run_in_team(chunks(), [&](Team& team) {
            rebuild(team, true);
            locate_kinds(team);
        });
        note_build(time_);
        return;
    }
    list_time_.reset();  // the state does not say when its list was built
    owned_ = state.owned;
    if (slabs_) slabs_->restore(std::move(state.slabs));
    neighbors_.restore(std::move(state.neighbors));
    prepare_chunks();
    run_in_team(chunks(), [&](Team& team) { locate_kinds(team); });
}

SimulationState whole_state(const std::vector<SimulationState>& ranks) {
    if (ranks.empty()) throw Error("whole_state: no states");
    const SimulationState& first = ranks.front();
    SimulationState whole;
    whole.dt = first.dt;
    whole.time = first.time;
    whole.step = first.step;
    whole.motions = first.motions;
    whole.inserted = first.inserted;
    whole.neighbors.builds = first.neighbors.builds;
    whole.wall_history.assign(first.wall_history.size(), ContactHistory{});
    whole.wall_feature.assign(first.wall_history.size(), 0);
    whole.list_from_histories = true;
    // Every rank's own spheres, by global id.
    std::vector<std::pair<std::int64_t, std::pair<std::size_t, std::size_t>>> own;  // id, (rank, index)
    for (std::size_t r = 0; r < ranks.size(); ++r) {
        const SimulationState& s = ranks[r];
        if (s.step != first.step || s.dt != first.dt || s.wall_history.size() != first.wall_history.size() ||
            s.wall_feature.size() != s.wall_history.size() ||
            s.owned > s.particles.size())
            throw Error("whole_state: the ranks' states are not of one run at one step");
        for (std::size_t i = 0; i < s.owned; ++i) own.push_back({s.particles.id[i], {r, i}});
    }
    std::sort(own.begin(), own.end());
    std::int64_t largest = -1;  // ids are 0 .. N-1; own.size() below marks an id no rank owns
    for (const auto& [id, where] : own) largest = std::max(largest, id);
    std::vector<std::size_t> index_of_id(static_cast<std::size_t>(largest + 1), own.size());
    const std::size_t slots = whole.wall_history.size() / index_of_id.size();  // wall histories per sphere
    for (const auto& [id, where] : own) {
        const auto [r, i] = where;
        if (index_of_id[static_cast<std::size_t>(id)] != own.size())
            throw Error("whole_state: sphere " + std::to_string(id) + " is owned by two ranks");
        index_of_id[static_cast<std::size_t>(id)] = whole.particles.size();
        whole.particles.append(ranks[r].particles, i);
        if (!whole.wall_history.empty())
            for (std::size_t f = slots * static_cast<std::size_t>(id); f < slots * static_cast<std::size_t>(id + 1); ++f) {
                whole.wall_history[f] = ranks[r].wall_history[f];
                whole.wall_feature[f] = ranks[r].wall_feature[f];
            }
    }
    whole.owned = whole.particles.size();
    whole.neighbors.position_at_build = whole.particles.position;
    // The histories of the touching pairs (a pair across a cut is in two
    // ranks' lists: the first rank's record is kept), as pairs of the whole.
    std::vector<std::tuple<std::uint32_t, std::uint32_t, ContactHistory>> pairs;
    for (const SimulationState& s : ranks)
        for (const KeyedHistory& h : keyed_histories(s.particles, s.neighbors.pairs)) {
            const auto lo = static_cast<std::size_t>(h.lo), hi = static_cast<std::size_t>(h.hi);
            if (hi >= index_of_id.size() || index_of_id[lo] == own.size() || index_of_id[hi] == own.size())
                throw Error("whole_state: a contact of sphere " + std::to_string(h.lo) + " with a sphere no rank owns");
            const std::size_t a = index_of_id[lo], b = index_of_id[hi];
            pairs.emplace_back(static_cast<std::uint32_t>(std::min(a, b)), static_cast<std::uint32_t>(std::max(a, b)),
                               a < b ? h.history : h.history.swapped());
        }
    std::stable_sort(pairs.begin(), pairs.end(), [](const auto& x, const auto& y) {
        return std::get<0>(x) != std::get<0>(y) ? std::get<0>(x) < std::get<0>(y) : std::get<1>(x) < std::get<1>(y);
    });
    for (std::size_t k = 0; k < pairs.size(); ++k) {
        const auto& [i, j, h] = pairs[k];
        if (k > 0 && std::get<0>(pairs[k - 1]) == i && std::get<1>(pairs[k - 1]) == j) continue;  // the same pair again
        whole.neighbors.pairs.add(i, j, 0);
        whole.neighbors.pairs.set_history(whole.neighbors.pairs.size() - 1, h);
    }
    return whole;
}

Observables Simulation::observe() const {
    const ParticleStore& p = particles_;
    Observables o;
    o.time = time_;
    o.step = step_;
    o.neighbor_builds = neighbors_.builds();
    o.per_material.resize(scenario_.materials.size());
    for (std::size_t i = 0; i < owned_; ++i) {
        if (p.is_kinematic(i)) continue;
        MaterialEnergies& e = o.per_material[static_cast<std::size_t>(p.material[i])];
        const double translational = 0.5 * p.mass[i] * norm2(p.velocity[i]);
        const double rotational = 0.5 * 0.4 * p.mass[i] * p.radius[i] * p.radius[i] * norm2(p.angular_velocity[i]);
        ++e.particles;
        e.kinetic_translational += translational;
        e.kinetic_rotational += rotational;
        o.kinetic_translational += translational;
        o.kinetic_rotational += rotational;
    }
    const PairList& pairs = neighbors_.pairs();
    for (std::size_t k = 0; k < pairs.size(); ++k) {
        const std::uint32_t i = pairs.first[k], j = pairs.second[k];
        if (!counts_pair(i, j)) continue;
        const double distance = norm(p.position[i] - p.position[j] + neighbors_.images()[pairs.image[k]]);
        const double overlap = p.radius[i] + p.radius[j] - distance;
        if (overlap <= 0.0) continue;
        const PairCoefficients& c = pair_table_(p.material[i], p.material[j]);
        const double a = std::sqrt(p.radius[i] * p.radius[j] / (p.radius[i] + p.radius[j]) * overlap);
        ++o.contacts;
        o.max_overlap_ratio = std::max(o.max_overlap_ratio, overlap / std::min(p.radius[i], p.radius[j]));
        if (scenario_.model.elastic) o.contact_energy += hertz_energy(c.E_star, a, overlap);
        if (scenario_.model.attraction) o.contact_energy += attraction_energy(c.attraction, a, overlap);
    }
    std::vector<PlacedWall> walls;
    const std::vector<MotionNow> now = motions_now(time_);
    for (const Wall& w : walls_) walls.push_back(place_wall(w, w.motion >= 0 ? &now[static_cast<std::size_t>(w.motion)] : nullptr));
    for (std::size_t i = 0; i < owned_; ++i)
        for (const PlacedWall& w : walls) {
            if (p.is_kinematic(i)) continue;
            const WallTouch t = wall_contact(w, p.position[i]).touch;
            const double overlap = p.radius[i] - t.distance;
            if (overlap <= 0.0) continue;
            const PairCoefficients& c = pair_table_(p.material[i], w.wall->material);
            const double a = std::sqrt(wall_contact_radius(p.radius[i], t.curvature) * overlap);
            ++o.contacts;
            o.max_overlap_ratio = std::max(o.max_overlap_ratio, overlap / p.radius[i]);
            if (scenario_.model.elastic) o.contact_energy += hertz_energy(c.E_star, a, overlap);
            if (scenario_.model.attraction) o.contact_energy += attraction_energy(c.attraction, a, overlap);
        }
    o.wall_loads = wall_loads();  // collective when shared
    if (slabs_) {  // the sums of every rank's own spheres and pairs
        std::vector<double> sums;
        for (const MaterialEnergies& e : o.per_material)
            sums.insert(sums.end(), {static_cast<double>(e.particles), e.kinetic_translational, e.kinetic_rotational});
        sums.insert(sums.end(), {o.kinetic_translational, o.kinetic_rotational, o.contact_energy});
        mpi::sum(sums);
        for (std::size_t m = 0; m < o.per_material.size(); ++m)
            o.per_material[m] = {static_cast<std::size_t>(sums[3 * m]), sums[3 * m + 1], sums[3 * m + 2]};
        const std::size_t t = 3 * o.per_material.size();
        o.kinetic_translational = sums[t];
        o.kinetic_rotational = sums[t + 1];
        o.contact_energy = sums[t + 2];
        o.contacts = static_cast<std::size_t>(mpi::sum(static_cast<std::int64_t>(o.contacts)));
        o.max_overlap_ratio = mpi::max(o.max_overlap_ratio);
    }
    return o;
}

}  // namespace tumble
