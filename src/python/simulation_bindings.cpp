// SPDX-License-Identifier: MIT
// tumble.Scenario (a scenario read and checked, io/config.hpp) and
// tumble.Simulation (the engine, sim/simulation.hpp) with its particles as
// numpy views of the structure-of-arrays store.
#include <array>
#include <optional>
#include <string>
#include <string_view>

#include <fmt/format.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "experiments/drum_setup.hpp"
#include "experiments/limits.hpp"
#include "experiments/machine.hpp"
#include "experiments/run_control.hpp"
#include "io/config.hpp"
#include "io/output.hpp"
#include "io/snapshot_data.hpp"
#include "io/toml_reader.hpp"
#include "tumble/analysis/simulation_fields.hpp"
#include "tumble/sim/contact_network.hpp"
#include "tumble/sim/health.hpp"
#include "tumble/sim/simulation.hpp"
#include "tumble/walls/wall_surface.hpp"

namespace tumble::python {

namespace fs = std::filesystem;

namespace {

Vec3 vec3(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

py::dict observables(const Observables& o) {
    py::list per_material;
    for (const MaterialEnergies& e : o.per_material)
        per_material.append(py::dict(py::arg("particles") = e.particles,
                                     py::arg("kinetic_translational") = e.kinetic_translational,
                                     py::arg("kinetic_rotational") = e.kinetic_rotational));
    return py::dict(py::arg("time") = o.time, py::arg("step") = o.step, py::arg("per_material") = per_material,
                    py::arg("kinetic_translational") = o.kinetic_translational,
                    py::arg("kinetic_rotational") = o.kinetic_rotational, py::arg("contact_energy") = o.contact_energy,
                    py::arg("contacts") = o.contacts, py::arg("max_overlap_ratio") = o.max_overlap_ratio,
                    py::arg("neighbor_builds") = o.neighbor_builds);
}

// The contact network (sim/contact_network.hpp) as columns.
py::dict contacts(const Simulation& sim) {
    const std::vector<ContactLink> links = contact_network(sim);
    std::vector<std::int64_t> id_i, id_j;
    std::vector<Vec3> point, normal, slip;
    std::vector<double> overlap, normal_force, angular_slip;
    for (const ContactLink& c : links) {
        id_i.push_back(c.id_i);
        id_j.push_back(c.id_j);
        point.push_back(c.point);
        normal.push_back(c.n);
        overlap.push_back(c.overlap);
        normal_force.push_back(c.normal_force);
        slip.push_back(c.history.slip);
        angular_slip.push_back(c.history.angular_slip);
    }
    const py::handle copy;
    return py::dict(py::arg("id_i") = array_of(id_i, copy), py::arg("id_j") = array_of(id_j, copy),
                    py::arg("point") = array_of(point, copy), py::arg("normal") = array_of(normal, copy),
                    py::arg("overlap") = array_of(overlap, copy), py::arg("normal_force") = array_of(normal_force, copy),
                    py::arg("slip") = array_of(slip, copy), py::arg("angular_slip") = array_of(angular_slip, copy));
}

// The smooth walls (Scenario::walls) where their motions have carried them:
// per wall its name, its surface as vertices (m, N x 3) and triangles
// (vertex indices, M x 3), its load from the last step (force, N; torque
// about where its point is, N m).
py::list walls(const Simulation& sim) {
    const std::vector<WallSurface> drawn = io::wall_surfaces(sim);
    const std::vector<WallLoad> loads = sim.wall_loads();
    py::list out;
    const py::handle copy;
    for (std::size_t k = 0; k < drawn.size(); ++k) {
        const WallSurface& s = drawn[k];
        std::vector<std::int64_t> flat;
        for (const auto& t : s.triangles) flat.insert(flat.end(), t.begin(), t.end());
        py::array triangles = array_of(flat, copy);
        triangles = triangles.attr("reshape")(static_cast<py::ssize_t>(s.triangles.size()), 3);
        out.append(py::dict(py::arg("name") = sim.scenario().walls[k].name, py::arg("vertices") = array_of(s.vertices, copy),
                            py::arg("triangles") = triangles,
                            py::arg("force") = array_of(std::vector<Vec3>{loads[k].force}, copy).attr("reshape")(3),
                            py::arg("torque") = array_of(std::vector<Vec3>{loads[k].torque}, copy).attr("reshape")(3)));
    }
    return out;
}

// The contacts the last step recorded (Simulation::set_contact_recording),
// with their forces, as columns.
py::dict contact_records(const Simulation& sim) {
    std::vector<std::int64_t> id_i, id_j;
    std::vector<Vec3> normal, force, torque_i, torque_j, slip;
    std::vector<double> overlap, normal_force, twisting_couple, angular_slip;
    for (const ContactRecord& c : sim.contact_records()) {
        id_i.push_back(c.id_i);
        id_j.push_back(c.id_j);
        normal.push_back(c.geometry.n);
        overlap.push_back(c.geometry.overlap);
        force.push_back(c.forces.force_i);
        torque_i.push_back(c.forces.torque_i);
        torque_j.push_back(c.forces.torque_j);
        normal_force.push_back(c.forces.normal_force);
        twisting_couple.push_back(c.forces.twisting_couple);
        slip.push_back(c.history.slip);
        angular_slip.push_back(c.history.angular_slip);
    }
    const py::handle copy;
    return py::dict(py::arg("id_i") = array_of(id_i, copy), py::arg("id_j") = array_of(id_j, copy),
                    py::arg("normal") = array_of(normal, copy), py::arg("overlap") = array_of(overlap, copy),
                    py::arg("force") = array_of(force, copy), py::arg("torque_i") = array_of(torque_i, copy),
                    py::arg("torque_j") = array_of(torque_j, copy), py::arg("normal_force") = array_of(normal_force, copy),
                    py::arg("twisting_couple") = array_of(twisting_couple, copy), py::arg("slip") = array_of(slip, copy),
                    py::arg("angular_slip") = array_of(angular_slip, copy));
}

// The free grains and the recorded contacts of the last step
// (analysis::grain_state) as tumble.coarse_grain takes them.
py::dict grain_state(const Simulation& sim) {
    const analysis::GrainState s = analysis::grain_state(sim);
    std::vector<std::int64_t> i, j;
    std::vector<Vec3> force, branch;
    for (const analysis::CgContact& c : s.contacts) {
        i.push_back(static_cast<std::int64_t>(c.i));
        j.push_back(c.j == analysis::CgContact::wall ? -1 : static_cast<std::int64_t>(c.j));
        force.push_back(c.force);
        branch.push_back(c.branch);
    }
    const py::handle copy;
    const py::dict contacts(py::arg("i") = array_of(i, copy), py::arg("j") = array_of(j, copy),
                            py::arg("force") = array_of(force, copy), py::arg("branch") = array_of(branch, copy));
    return py::dict(py::arg("positions") = array_of(s.position, copy),
                    py::arg("velocities") = array_of(s.velocity, copy), py::arg("masses") = array_of(s.mass, copy),
                    py::arg("radii") = array_of(s.radius, copy), py::arg("contacts") = contacts);
}

// Runs `sim` for `total` steps, asking until(sim) every check_every steps
// whether to stop; the GIL is free while the engine works, and Ctrl-C stops
// the loop (KeyboardInterrupt) between two checks. Returns the steps done.
// A step count from the caller: 0 is nothing to do, a negative one an error
// (it would otherwise do nothing without a word).
// More than any run can take is refused as tumble run refuses such a
// duration (experiments::max_steps).
void need_steps(std::int64_t steps, const char* what) {
    if (steps < 0) throw Error(fmt::format("{}: need a count >= 0, got {}", what, steps));
    if (static_cast<double>(steps) > experiments::max_steps)
        throw Error(fmt::format("{}: {} steps, more than any run can take (at most {:g})", what, steps,
                                experiments::max_steps));
}

// The blow-up check of tumble run (sim/health.hpp): in full (with every
// contact's overlap, which costs about a force evaluation) every
// experiments::health_check_steps steps of the simulation, as tumble run
// makes it; the particles' part (non-finite values, speeds, the region)
// after every call as well, which costs little. A state that failed
// raises, naming the step that made it: the steps of the call since its
// last check are taken again one by one from the state captured there
// (the same numbers: they are deterministic); an error of the engine on
// the way (a non-finite position in the neighbour search) is found so too.
using HealthCheck = std::string (*)(const Simulation&, const HealthLimits&);

[[noreturn]] void blew_up(const std::string& problem) {
    throw Error("the simulation blew up at " + problem + ". Check the time step (docs/MODEL.md) and the input");
}

void find_the_bad_step(Simulation& sim, const SimulationState& before, const HealthLimits& limits, std::int64_t end,
                       HealthCheck check) {
    sim.restore(before);
    while (sim.step_count() < end) {
        try {
            sim.advance(1);
        } catch (const Error& e) {
            throw Error(fmt::format("the simulation blew up at step {}: {}", sim.step_count() + 1, e.what()));
        }
        if (const std::string problem = check(sim, limits); !problem.empty()) blew_up(problem);
    }
}

// `steps` steps without the GIL, checked as above.
void advance_checked(Simulation& sim, std::int64_t steps) {
    const HealthLimits limits = default_health_limits(sim.scenario());
    for (std::int64_t done = 0; done < steps;) {
        const std::int64_t n = std::min(experiments::health_check_steps, steps - done);
        const std::int64_t start = sim.step_count(), end = start + n;
        const bool full = end / experiments::health_check_steps != start / experiments::health_check_steps;
        const HealthCheck check = full ? health_problem : particle_health_problem;
        std::optional<SimulationState> before;  // one step needs no search
        if (n > 1) before = sim.capture();
        std::string problem;
        try {
            py::gil_scoped_release engine_works;
            sim.advance(n);
            problem = check(sim, limits);
        } catch (const Error& e) {
            if (!before) throw Error(fmt::format("the simulation blew up at step {}: {}", end, e.what()));
            problem = e.what();
        }
        if (!problem.empty()) {
            if (before) find_the_bad_step(sim, *before, limits, end, check);
            blew_up(problem);
        }
        done += n;
    }
}

// A thread count as the command line's --threads is checked, naming `what`.
void need_threads(int threads, const char* what) {
    if (const std::string why = experiments::thread_count_problem(threads, std::to_string(threads)); !why.empty())
        throw Error(std::string(what) + ": " + why);
}

std::int64_t run(py::object self, std::int64_t total, const py::object& until, std::int64_t check_every) {
    Simulation& sim = self.cast<Simulation&>();
    if (check_every < 1) throw Error("check_every must be >= 1, got " + std::to_string(check_every));
    std::int64_t done = 0;
    while (done < total) {
        const std::int64_t n = std::min(check_every, total - done);
        advance_checked(sim, n);
        done += n;
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        if (!until.is_none() && py::bool_(until(self))) break;
    }
    return done;
}

// The reader's check of the memory a run of the scenario will need, made
// before any sphere is made, as tumble run makes it (on a Simulation's
// default one thread).
io::ParticleCheck memory_check(double max_memory_gib) {
    need_memory_limit(max_memory_gib);
    return experiments::scenario_memory_check(1, experiments::memory_limit_bytes(max_memory_gib), "max_memory_gib");
}

}  // namespace

void need_memory_limit(double max_memory_gib) {
    if (max_memory_gib == 0.0) return;
    if (const std::string why = experiments::finite_positive_problem(max_memory_gib, fmt::format("{}", max_memory_gib));
        !why.empty())
        throw Error("max_memory_gib: " + why + " (0: half the machine's memory)");
}

void bind_scenario(py::module_& m) {
    py::class_<io::RunConfig>(m, "Scenario", "A scenario, read and checked (docs/SCENARIO.md); build with from_file, "
                                             "from_toml, from_dict or drum")
        .def_static(
            "from_file",
            [](const fs::path& path, double max_memory_gib) {
                return io::load_run_config(path, memory_check(max_memory_gib));
            },
            py::arg("path"), py::arg("max_memory_gib") = 0.0,
            "Reads a scenario file (TOML). max_memory_gib: refuse, before any sphere is made, a scenario whose "
            "run is estimated to need more (tumble run --max-memory; 0: half the machine's memory)")
        .def_static(
            "from_toml",
            [](std::string_view text, const fs::path& name, const fs::path& base_dir, double max_memory_gib) {
                return io::parse_run_config(text, name, base_dir, memory_check(max_memory_gib));
            },
            py::arg("text"), py::arg("name") = "<toml>", py::arg("base_dir") = fs::path("."),
            py::arg("max_memory_gib") = 0.0,
            "Reads scenario text; `name` stands for the file in messages, `base_dir` resolves CSV files; "
            "max_memory_gib as from_file's")
        .def_static(
            "from_dict",
            [](const py::dict& d, const fs::path& name, const fs::path& base_dir, double max_memory_gib) {
                return io::read_run_config(toml_from_dict(d, name), name, base_dir, memory_check(max_memory_gib));
            },
            py::arg("scenario"), py::arg("name") = "<dict>", py::arg("base_dir") = fs::path("."),
            py::arg("max_memory_gib") = 0.0,
            "A scenario from a dict laid out as the file: {'simulation': {...}, 'material': [{...}], ...}; "
            "max_memory_gib as from_file's")
        .def_static(
            "drum",
            [](const io::DrumSettings& s, bool allow_unsafe_dt) {
                io::RunConfig c;
                c.scenario = experiments::build_drum(s, allow_unsafe_dt).scenario;
                c.seed = s.seed;
                c.output.directory = s.output;
                c.source = "drum";
                return c;
            },
            py::arg("settings"), py::arg("allow_unsafe_dt") = false,
            "The paper's drum of the settings (tumble.drum_settings), at rest: its wall is motion 0 "
            "(Simulation.set_motion turns it); duration 0, the protocol (tumble.run_drum) decides")
        .def_readonly("duration", &io::RunConfig::duration, "simulated time of the file, s")
        .def_readonly("seed", &io::RunConfig::seed, "the random seed")
        .def_property_readonly("output_directory", [](const io::RunConfig& c) { return c.output.directory; },
                               "[output] directory: where tumble run writes")
        .def_property_readonly("time_series_interval", [](const io::RunConfig& c) { return c.output.time_series_interval; },
                               "s between rows of time_series.csv")
        .def_property_readonly("snapshot_interval", [](const io::RunConfig& c) { return c.output.snapshot_interval; },
                               "s between particle snapshots (0: none)")
        .def_readonly("source", &io::RunConfig::source, "the scenario file, or the name it was given")
        .def_property_readonly("particle_count", [](const io::RunConfig& c) { return c.scenario.particles.size(); },
                               "particles at the start (those poured in later by [[insert]] not counted)")
        .def_property_readonly("material_names", [](const io::RunConfig& c) {
            std::vector<std::string> names;
            for (const Material& mat : c.scenario.materials) names.push_back(mat.name);
            return names;
        }, "the materials' names, in the order of their indices");
}

void bind_simulation(py::module_& m) {
    py::class_<Simulation> sim(m, "Simulation", R"(A running simulation of a Scenario.

The particle arrays (positions, velocities, ...) are read-only numpy views of
the engine's memory, without a copy, that keep the simulation alive. The
particles are stored in an order that changes when the engine re-sorts them
in space (at neighbour-list rebuilds): follow grains by `ids`, and read an
array again after stepping rather than keeping an old view (a re-sort moves
the store to other memory).)");
    sim.def(py::init([](const io::RunConfig& scenario, int threads) {
                need_threads(threads, "threads");
                return std::make_unique<Simulation>(scenario.scenario, experiments::resolve_threads(threads));
            }),
            py::arg("scenario"), py::arg("threads") = 1,
            "threads: of the time step (0: every core); the same count gives the same numbers bit for bit")
        .def(
            "step", [](Simulation& s) { advance_checked(s, 1); },
            "One time step; tumble.Error if it made the state non-finite or unphysical (tumble run's blow-up check)")
        .def(
            "advance",
            [](Simulation& s, std::int64_t steps) {
                need_steps(steps, "advance: steps");
                advance_checked(s, steps);
            },
            py::arg("steps"),
            "`steps` time steps in one go (the same numbers as one step at a time); tumble.Error naming the step "
            "that made the state non-finite or unphysical (tumble run's blow-up check)")
        .def(
            "run",
            [](py::object self, std::optional<std::int64_t> steps, std::optional<double> duration,
               const py::object& until, std::int64_t check_every) {
                const Simulation& s = self.cast<const Simulation&>();
                if (steps.has_value() == duration.has_value()) throw Error("run: give steps or duration (one)");
                if (steps) need_steps(*steps, "run: steps");
                if (duration && !(*duration >= 0.0))
                    throw Error(fmt::format("run: duration: need a time >= 0 s, got {}", *duration));
                const std::int64_t total = steps ? *steps : experiments::step_count(*duration, s.dt(), "run: duration");
                return run(self, total, until, check_every);
            },
            py::arg("steps") = py::none(), py::arg("duration") = py::none(), py::arg("until") = py::none(),
            py::arg("check_every") = 100,
            "Runs `steps` steps (or `duration` seconds), stopping early when until(sim) is true, asked every "
            "check_every steps; returns the steps done")
        .def_property_readonly(
            "step_times",
            [](const Simulation& s) {
                py::dict times;
                for (std::size_t k = 0; k < step_phase_count; ++k)
                    times[py::str(std::string(step_phase_names[k]))] = s.step_times().seconds[k];
                times["steps"] = s.step_times().steps;
                return times;
            },
            "Seconds of wall-clock time in each phase of the steps taken since the simulation was built or "
            "reset_step_times(): motion, exchange (MPI ranks), neighbours, forces; and the steps")
        .def("reset_step_times", &Simulation::reset_step_times, "Starts step_times from zero")
        .def_property_readonly("time", &Simulation::time, "s")
        .def_property_readonly("dt", &Simulation::dt, "time step, s")
        .def_property_readonly("step_count", &Simulation::step_count, "time steps taken")
        .def_property_readonly("inserted", &Simulation::inserted,
                               "Per [[insert]] of the scenario, the spheres it has poured in so far")
        .def_property("threads", &Simulation::threads, &Simulation::set_threads,
                      "threads of the time step; another count changes the results by round-off")
        .def_property_readonly("size", [](const Simulation& s) { return s.particles().size(); },
                               "particles, the kinematic ones included")
        .def_property_readonly("free_count", [](const Simulation& s) { return s.particles().free_count(); },
                               "particles that move by the forces (no prescribed motion)")
        .def_property_readonly("material_names",
                               [](const Simulation& s) {
                                   std::vector<std::string> names;
                                   for (const Material& mat : s.scenario().materials) names.push_back(mat.name);
                                   return names;
                               },
                               "the materials' names: the array materials indexes them")
        .def_property_readonly(
            "by_id",
            [](const Simulation& s) {
                const ParticleStore& p = s.particles();
                std::vector<std::int64_t> index(p.size());
                for (std::size_t i = 0; i < p.size(); ++i) index[static_cast<std::size_t>(p.id[i])] = static_cast<std::int64_t>(i);
                return array_of(index, py::handle());
            },
            "indices that put the arrays in global-id order: sim.positions[sim.by_id] (a copy)")
        .def("observe", [](const Simulation& s) { return observables(s.observe()); },
             "energies, contact count, largest overlap: a row of time_series.csv")
        .def("contacts", &contacts,
             "the touching pairs, lower id first, as columns (copies): id_i, id_j, point (m), normal (unit, from "
             "j to i), overlap (m), normal_force (N, > 0 pushes apart), and their history: slip (the tangential "
             "displacement of i relative to j, m; eq. 8) and angular_slip (rad; eq. 9). Flat-wall contacts are "
             "not listed")
        .def("walls", &walls,
             "the smooth walls ([[wall]]) where their motions have carried them, one dict each: name, vertices "
             "(m, N x 3) and triangles (vertex indices, M x 3) of its surface (infinite planes and cylinders cut to "
             "the domain box), and the load of the last step: force (N, on the wall) and torque (N m, about where "
             "its point is). Collective when shared among MPI ranks")
        .def("set_contact_recording", &Simulation::set_contact_recording, py::arg("on"),
             "Keep a record of every contact of each step, with its forces (contact_records); slows the force "
             "loop, which then runs on one thread")
        .def("contact_records", &contact_records,
             "The contacts of the last step as recorded (set_contact_recording), as columns (copies): id_i, id_j "
             "(a wall is -1 - slot: slot = 2 axis + (0 at lo, 1 at hi) for the box's flat walls, 6 + k for the "
             "k-th [[wall]]), normal (j to i), overlap (m), force "
             "(on i; j feels -force, N), torque_i, torque_j (N m), normal_force (N), twisting_couple (N m), slip, "
             "angular_slip (the history after the step)")
        .def("grain_state", &grain_state,
             "The free grains in the order of their ids and every contact of the last step, recorded "
             "(set_contact_recording(True) before it), as tumble.coarse_grain takes them: a dict of positions, "
             "velocities, masses, radii and contacts (i, j: the grains' rows, -1 for a wall or a wall sphere; "
             "force on i, N; branch from j's centre or the contact point to i's centre, m), so that "
             "tumble.coarse_grain(**sim.grain_state(), width=...) gives the fields of the state (docs/FIELDS.md)")
        .def(
            "set_motion",
            [](Simulation& s, std::size_t k, double angular_velocity, const std::array<double, 3>& axis_point,
               const std::array<double, 3>& axis_direction, const std::array<double, 3>& velocity) {
                if (k >= s.scenario().motions.size()) throw Error("set_motion: no motion " + std::to_string(k));
                s.set_motion(k, RigidMotion{vec3(axis_point), vec3(axis_direction), angular_velocity, vec3(velocity)});
            },
            py::arg("motion"), py::arg("angular_velocity"), py::arg("axis_point") = std::array<double, 3>{},
            py::arg("axis_direction") = std::array<double, 3>{0.0, 0.0, 1.0},
            py::arg("velocity") = std::array<double, 3>{},
            "Replaces prescribed motion k from now on (rad/s about the axis, m/s); its particles go on from "
            "where they are. Refused (tumble.Error) where its spheres or walls would move faster than the health "
            "check allows (100 x the time step's reference impact speed), as a scenario's motions are")
        .def(
            "write_snapshot",
            [](const Simulation& s, const fs::path& directory, int number) {
                return io::write_snapshot(directory, number, s);
            },
            py::arg("directory"), py::arg("number"), "Writes DIRECTORY/snapshots/NNNNNN.csv as tumble run does");
    for_each_particle_field([&](const char* name, auto field, const char* doc) {
        sim.def_property_readonly(
            name, [field](py::object self) { return array_of(self.cast<const Simulation&>().particles().*field, self); },
            doc);
    });
}

}  // namespace tumble::python
