// SPDX-License-Identifier: MIT
// A running simulation: owns the particles, the neighbour list with the
// contact history, and the clock. step() is the whole time step.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tumble/sim/time_step.hpp"
#include "tumble/materials/pair_table.hpp"
#include "tumble/neighbor/verlet_list.hpp"
#include "tumble/core/parallel.hpp"
#include "tumble/particles/particle_store.hpp"
#include "tumble/particles/rigid_motion.hpp"
#include "tumble/sim/pair_loop.hpp"
#include "tumble/sim/scenario.hpp"
#include "tumble/sim/simulation_state.hpp"
#include "tumble/sim/slabs.hpp"
#include "tumble/sim/step_clock.hpp"
#include "tumble/sim/wall_loop.hpp"
#include "tumble/walls/clearance.hpp"
#include "tumble/walls/facet_grid.hpp"
#include "tumble/walls/mesh.hpp"

namespace tumble {

// Per-material sums over the free particles.
struct MaterialEnergies {
    std::size_t particles = 0;
    double kinetic_translational = 0.0;  // J
    double kinetic_rotational = 0.0;     // J
};

struct Observables {
    double time = 0.0;        // s
    std::int64_t step = 0;
    std::vector<MaterialEnergies> per_material;
    double kinetic_translational = 0.0;  // J, all free particles
    double kinetic_rotational = 0.0;     // J
    double contact_energy = 0.0;         // J, elastic + attraction energy stored in contacts
    std::size_t contacts = 0;
    double max_overlap_ratio = 0.0;      // largest h / min(R_i, R_j)
    std::int64_t neighbor_builds = 0;
    std::vector<WallLoad> wall_loads;    // per wall of Scenario::walls (Simulation::wall_loads())
};

// The id that stands for a wall in a ContactRecord: number = 2 axis + (0
// at lo, 1 at hi) for the box's flat walls, 6 + k for Scenario::walls[k].
constexpr std::int64_t wall_id(std::size_t number) { return -1 - static_cast<std::int64_t>(number); }

// The contact history slots per sphere a mesh wall has: its S deepest
// contacts (docs/MODEL.md, "Walls").
inline constexpr std::size_t mesh_wall_slots = 4;

// The feature of a mesh a history slot follows, as one number (0: none):
// 1 + id + 2^30 kind, ids below 2^30 - 1 (scenario_problem checks the meshes).
constexpr std::uint32_t mesh_feature_code(MeshFeature kind, std::uint32_t id) {
    return 1u + id + (static_cast<std::uint32_t>(kind) << 30);
}


// Where a simulation runs: on this process alone, or shared among the ranks
// of the MPI world, a slab of the domain each (sim/slabs.hpp; with one rank
// in the world the same as `one`).
enum class Ranks { one, world };

class Simulation {
public:
    // Checks the scenario (throws tumble::Error with the reason), chooses or
    // checks the time step, builds the neighbour list and the initial forces.
    // `threads` as in set_threads().
    // With Ranks::world every rank of the world constructs it, and then makes
    // the same calls in the same order: step() and advance() exchange the
    // ghosts, observe(), gathered(), capture() and restore() are collective.
    explicit Simulation(Scenario scenario, int threads = 1, Ranks ranks = Ranks::one);

    // Threads for the time step (1 to max_threads; tumble::Error otherwise). The same
    // thread count gives the same numbers bitwise on every run; another count
    // sums each particle's contact forces in another order, so results differ
    // by round-off (docs/BENCHMARKS.md "Threads"). Without OpenMP the work is
    // still split this way but runs on one thread.
    static constexpr int max_threads = 1024;
    void set_threads(int threads);
    int threads() const { return threads_; }

    // One time step; `steps` of them. advance() runs its steps in one
    // parallel region, so on several threads advance(n) costs less than n
    // calls of step().
    void step();
    void advance(std::int64_t steps);

    double time() const { return time_; }
    double dt() const { return dt_; }
    std::int64_t step_count() const { return step_; }
    const Scenario& scenario() const { return scenario_; }
    // The spheres this process holds: on one rank every sphere; shared among
    // ranks, the rank's own spheres [0, owned()) and after them the ghosts.
    const ParticleStore& particles() const { return particles_; }
    std::size_t owned() const { return owned_; }
    // Whether this rank counts pair (i, j) of its list (array indices, i < j)
    // in sums over the pairs: a pair of an own sphere and a ghost is in the
    // lists of both ranks, and counts on the rank of the lower global id.
    bool counts_pair(std::uint32_t i, std::uint32_t j) const {
        return j < owned_ || particles_.id[i] < particles_.id[j];
    }
    bool shared() const { return slabs_ != nullptr; }
    const Slabs* slabs() const { return slabs_.get(); }
    // Every sphere: on one rank particles(); shared among ranks, the own
    // spheres of every rank on rank 0 in the order of their global ids
    // (empty on the other ranks). Collective.
    ParticleStore gathered() const;
    const TimeStepReport& time_step_report() const { return time_step_report_; }
    const VerletList& neighbors() const { return neighbors_; }
    Observables observe() const;

    // The state of the run (simulation_state.hpp), and its restoration into
    // a Simulation built from the same scenario: afterwards the run goes on
    // exactly as the captured one did. restore() checks that the state fits
    // the scenario (particle count, ids, indices, time step) and throws
    // tumble::Error with the reason if not.
    // Shared among ranks, each rank captures and restores its own part. A
    // state captured on one rank may be restored into a simulation shared
    // among ranks (every rank gets the whole state, keeps its slab and finds
    // the ghosts; the histories go by global id): a run continued on more
    // ranks. A state of several ranks restores only on as many.
    SimulationState capture() const;
    void restore(SimulationState state);

    // Per insertion of the scenario (Scenario::insertions), the spheres it
    // has poured in so far. advance() pours each batch at the start of the
    // step its time falls on (insertion_steps()), before that step.
    const std::vector<std::int64_t>& inserted() const { return inserted_; }

    // Where prescribed motion k has carried its spheres and walls at time().
    MotionNow motion_now(std::size_t k) const { return motions_now(time_).at(k); }

    // Replace prescribed motion k from now on; its particles continue from
    // where they are.
    void set_motion(std::size_t k, const RigidMotion& motion);

    // The loads on the walls of Scenario::walls, in their order, from the
    // forces of the last step (or of the set-up): the sums over each chunk's
    // grains, in chunk order. Shared among ranks, the sums over the ranks
    // (collective).
    std::vector<WallLoad> wall_loads() const;

    // When on, every step keeps a record of each contact (for tests and
    // diagnostics; slows the force loop).
    void set_contact_recording(bool on) { recording_ = on; }
    const std::vector<ContactRecord>& contact_records() const { return records_; }

    // This process's time in the phases of the steps taken since it was
    // built or reset (sim/step_clock.hpp); not part of the state.
    const StepTimes& step_times() const { return clock_.times(); }
    void reset_step_times() { clock_.reset(); }

private:
    int chunks() const { return recording_ ? 1 : threads_; }
    void prepare_chunks();
    // Which particles' force sums compute_forces() completes: the free ones
    // only (within an advance(), where nothing reads a kinematic sphere's),
    // or the kinematic ones too (where the state is seen: after the last
    // step of an advance(), after the set-up).
    enum class Sums { free, all };
    // The forces at `time` (where `now` has the motions then).
    template <class Then>
    void compute_forces(Team& team, Sums sums, double time, const std::vector<MotionNow>& now, Then&& then);
    void clear_chunk_sums(IndexRange r);
    void add_wall_forces(IndexRange r, const std::vector<PlacedWall>& walls, int c);
    // The contacts of sphere i with mesh wall k (an index into walls_),
    // each matched with its history slot (the slots' features set, the
    // slots no contact took cleared), into `out`; their number. From its
    // centre x in the mesh's frame at the start of its motion and the faces
    // it may touch (every one within its radius of x, and maybe more).
    struct MeshTouch {
        std::size_t record;              // the history's, in wall_history_
        Vec3 n;                          // lab frame, unit, from the mesh to the centre
        double distance;                 // of the centre from the mesh, m
        Vec3 velocity, angular_velocity; // the mesh's surface motion at the contact
    };
    std::size_t mesh_touches(std::size_t i, std::size_t k, const PlacedWall& wall, int c, const Vec3& x,
                             std::span<const std::uint32_t> faces, std::array<MeshTouch, mesh_wall_slots>& out);
    // One contact of sphere i with wall k: its geometry from the normal n
    // (lab frame, from the wall to the centre), the distance of the centre
    // from the wall, the Hertz radius and the wall's surface motion there.
    void add_wall_contact(std::size_t i, std::size_t k, const PlacedWall& wall, const Vec3& n, double distance,
                          double contact_radius, const Vec3& wall_velocity, const Vec3& wall_angular_velocity,
                          ContactHistory& history, int c);
    // The history slots per sphere: the box's six faces, then per wall of
    // the scenario one, or mesh_wall_slots for a mesh (wall_history_ at
    // slots x id + slot).
    std::size_t wall_slots() const { return wall_slots_; }
    // Where each prescribed motion is at a time (for move_kinematic()).
    std::vector<MotionNow> motions_now(double time) const;
    // What follows a step in its team: another step, or the end of the
    // team (then the step ends at v(t + dt)).
    enum class After { step, stop };
    void step(Team& team, std::int64_t next, bool drifted, After after);
    void locate_kinds(Team& team);
    // The neighbour list anew (shared among ranks: migration and ghosts too).
    // `keep_histories`: histories_ already holds the histories (a state
    // restored onto ranks, or made of several ranks'), not the list; the
    // list is then found with them by global id, on one rank too.
    void rebuild(Team& team, bool keep_histories = false);
    // The part of range r where free (kinematic) particles can be; chunk
    // c's own particles in a step's per-particle phases.
    IndexRange free_part(IndexRange r) const;
    IndexRange kinematic_part(IndexRange r) const;
    std::array<IndexRange, 2> own_parts(const Team& team, int c) const;
    std::size_t free_boundary(int c, int chunks, std::size_t split) const;
    std::size_t kinematic_split() const;
    // The batches due at step_ poured in (collective; nothing when none is
    // due), and the next step at which one is due after step_ (none: the
    // largest step there is).
    void insert_due();
    std::int64_t next_insertion_step() const;
    // The list built from the positions at `time`: each motion's reach
    // noted for walls_within_limit().
    void note_build(double time);
    // Whether at `time` no wall sphere can be near half the skin from where
    // the list saw it, by its motion's bound alone (then step() does not
    // look at each).
    bool walls_within_limit(double time) const;

    Scenario scenario_;
    PairTable pair_table_;
    ParticleStore particles_;
    VerletList neighbors_;
    TimeStepReport time_step_report_;
    std::vector<MotionClock> motions_;
    double dt_ = 0.0;
    double time_ = 0.0;
    std::int64_t step_ = 0;
    bool recording_ = false;
    std::vector<ContactRecord> records_;
    int threads_ = 1;
    // Contact forces and torques summed by chunks 1, 2, ... (chunk 0 sums
    // into the particles' own arrays): (chunks - 1) x N each, zero between
    // advance() calls (within one, their sums on kinematic particles wait
    // for its last step: compute_forces()); per chunk, the first particle its part of
    // the pairs touches, whether a particle of its part of the particles
    // moved far enough for a rebuild, and how many of its free particles
    // the drift at the end of a step took that far (for the next step).
    std::vector<Vec3> chunk_force_, chunk_torque_;
    std::vector<std::size_t> touched_from_;
    std::vector<char> moved_;
    std::vector<std::size_t> drifted_far_;
    // The free particles lie below free_end_, the kinematic ones from
    // kinematic_begin_ on (with the store in cell order, the kinematic ones
    // after all the free ones: the ranges do not overlap), so that the
    // per-particle loops of a step pass over the wall spheres only to move
    // them, and over the grains only to move those. Per chunk while they are
    // worked out (locate_kinds()).
    std::size_t free_end_ = 0, kinematic_begin_ = 0;
    std::vector<IndexRange> chunk_kinds_;
    // Where chunk c's share of the kinematic particles begins (the chunk
    // count + 1 entries, the last owned_): at the first wall sphere its part
    // of the pairs touches, so that a thread moves the wall spheres its
    // pairs read; per chunk, that sphere while it is worked out.
    std::vector<std::size_t> wall_from_, chunk_first_wall_;
    // The time of the positions the list was built from (none after a
    // restore without a rebuild, or a new motion: every wall sphere is then
    // checked until the next build), and per motion the farthest of its own
    // spheres from its axis.
    std::optional<double> list_time_;
    std::vector<double> motion_reach_;
    // The walls in force: the box's flat walls as infinite planes, then the
    // scenario's, each with its history slot. History of the contacts with
    // them at wall_slots() id + slot (ids are dense, 0 .. N-1); empty when
    // there are no walls. Per chunk the loads on the scenario's walls
    // (chunks x walls).
    // wall_slot_: each wall's first history slot; wall_number_: its number
    // (wall_id()); mesh_wall_: for a mesh, its index into mesh_walls_.
    // wall_feature_: per slot the mesh feature it follows (SimulationState).
    std::vector<Wall> walls_;
    std::vector<std::size_t> wall_slot_, wall_number_, mesh_wall_;
    std::size_t wall_slots_ = 6;
    std::vector<ContactHistory> wall_history_;
    std::vector<std::uint32_t> wall_feature_;
    // The meshes of the mesh walls in their frame at the start of their
    // motion, with their facet grids (built once: a mesh moves rigidly, and
    // a centre is carried into that frame), and per chunk the contacts of
    // the sphere at hand.
    struct MeshWall {
        MeshTopology topology;
        FacetGrid grid;
    };
    std::vector<MeshWall> mesh_walls_;
    std::vector<std::vector<MeshContact>> mesh_contacts_;
    // Per record of wall_history_: 0 where the record is zero (1: it may
    // not be); for a mesh wall the byte of its first slot speaks for all its
    // slots (mesh_touches()). Derived, not state: restore() and
    // migrations set every byte.
    std::vector<std::uint8_t> wall_history_set_;
    // While every wall stays put, the pairs of a sphere and a wall that may
    // touch before the next rebuild, with their histories (sim/wall_loop.hpp;
    // its histories go back into wall_history_ at a rebuild, when a wall
    // would move, and for the contacts' records).
    WallList wall_list_;
    void build_wall_list(const std::vector<PlacedWall>& walls);
    void flush_wall_list();
    // Per free own sphere near a mesh wall, the faces it may touch until
    // the list is found anew: those within its radius plus the skin of
    // where the neighbour list saw it, in the mesh's frame when the list was
    // made (`time`). The sphere stays within half the skin of that place
    // (the neighbour list's rule), and while the mesh's motion carries
    // none of the own spheres' places (within `reach` of its axis) farther
    // than 0.9 of the other half, no face left out comes within the
    // sphere's radius (mesh_list_holds()). The spheres left out held no
    // mesh contact once it was made, and are not looked at. Entry e: sphere
    // sphere[e] (its place in the store, in increasing order) against
    // wall[e], its faces faces[start[e]] to faces[start[e + 1] - 1].
    // Found anew at a rebuild (the store re-sorted), a restore or a new
    // motion; not made where the contacts are recorded (the facet grid's
    // path is then taken, with the same contacts).
    struct MeshList {
        bool valid = false;
        double time = 0.0;          // s
        std::vector<double> reach;  // per wall of walls_ (0 unless a moving mesh), m
        std::vector<std::uint32_t> sphere, wall, start{0}, faces;
    };
    MeshList mesh_list_;
    void build_mesh_list(const std::vector<PlacedWall>& walls, double time);
    bool mesh_list_holds(double time) const;
    std::vector<WallLoad> chunk_wall_load_;
    // Shared among ranks: the slabs, the spheres this rank owns (the first
    // owned_ of the store; all of them on one rank), the keyed histories of
    // a rebuild, and whether a sphere of any rank moved far enough for one.
    std::unique_ptr<Slabs> slabs_;
    std::size_t owned_ = 0;
    std::vector<KeyedHistory> histories_;
    HistoryTable history_table_;
    bool rebuild_now_ = false;
    StepClock clock_;
    // Per insertion, the spheres poured in so far (state), and the walls
    // they are placed clear of (with insertions and walls only).
    std::vector<std::int64_t> inserted_;
    std::optional<WallDistances> insertion_walls_;
};

// The whole state of a run shared among ranks, from the states its ranks
// captured at one step (each rank's, in rank order): every rank's own spheres
// in the order of their global ids, their flat-wall histories, and the
// histories of every pair; the list is left to be found anew when it is
// restored (list_from_histories), on any number of ranks.
SimulationState whole_state(const std::vector<SimulationState>& ranks);

}  // namespace tumble
