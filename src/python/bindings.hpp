// SPDX-License-Identifier: MIT
// The Python module tumble._core (pybind11): the engine's Simulation, the
// scenario and drum readers, the drum protocol, the sweep and the analysis,
// bound for the pure-Python package src/python/tumble, which is what users
// import.
// One file per part; this header holds what they share.
#pragma once

#include <csignal>
#include <cstdint>
#include <filesystem>
#include <string>
#include <type_traits>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <toml++/toml.h>

#include "experiments/run_control.hpp"
#include "tumble/core/vec3.hpp"
#include "tumble/particles/particle_store.hpp"

namespace tumble::python {

namespace py = pybind11;

void bind_scenario(py::module_& m);
void bind_simulation(py::module_& m);
void bind_drum(py::module_& m);
void bind_sweep(py::module_& m);
void bind_analysis(py::module_& m);

// The TOML table of a Python dict (a scenario or drum settings given as a
// dict, in the layout of the file): tables from dicts, arrays from lists,
// tuples and numpy arrays; bool, int, float and str values. `name` stands
// for the file in messages (io::ConfigError).
toml::table toml_from_dict(const py::dict& d, const std::filesystem::path& name);

// A memory limit given to a Python function (max_memory_gib, GiB; 0: half
// the machine's memory), checked as the command line checks --max-memory:
// tumble::Error naming it otherwise.
void need_memory_limit(double max_memory_gib);

// While a protocol runs, tumble's SIGINT and SIGTERM handlers (Ctrl-C
// writes a checkpoint and stops the run, run_control.hpp); Python's again
// afterwards.
class StopSignals {
public:
    StopSignals() {
        sigaction(SIGINT, nullptr, &interrupt_);
        sigaction(SIGTERM, nullptr, &terminate_);
    }
    ~StopSignals() {
        sigaction(SIGINT, &interrupt_, nullptr);
        sigaction(SIGTERM, &terminate_, nullptr);
        experiments::clear_stop_signal();
    }

private:
    struct sigaction interrupt_ {}, terminate_ {};
};

// work() (a protocol of experiments/, which takes the GIL for any call into
// Python) without the GIL and under StopSignals; its result, or, if a
// signal stopped it, KeyboardInterrupt with stopped_message(result) (how to
// continue).
template <class Work, class Message>
auto run_stoppable(Work&& work, Message&& stopped_message) {
    decltype(work()) result;
    bool interrupted = false;
    {
        const StopSignals signals;
        py::gil_scoped_release released;
        result = work();
        interrupted = experiments::stop_signalled();
    }
    if (interrupted) {
        PyErr_SetString(PyExc_KeyboardInterrupt, std::string(stopped_message(result)).c_str());
        throw py::error_already_set();
    }
    return result;
}

// A numpy array of `values`: a Vec3 field becomes N x 3. With an owner, a
// read-only view of the vector's memory that keeps the owner alive (no
// copy); without (py::handle()), a copy.
template <class T>
py::array array_of(const std::vector<T>& values, py::handle owner) {
    py::array a;
    if constexpr (std::is_same_v<T, Vec3>) {
        static_assert(sizeof(Vec3) == 3 * sizeof(double) && std::is_standard_layout_v<Vec3>);
        a = py::array(py::dtype::of<double>(), {values.size(), std::size_t{3}}, {sizeof(Vec3), sizeof(double)},
                      reinterpret_cast<const double*>(values.data()), owner);
    } else {
        a = py::array(py::dtype::of<T>(), {values.size()}, {sizeof(T)}, values.data(), owner);
    }
    if (owner) a.attr("setflags")(py::arg("write") = false);
    return a;
}

// The per-particle arrays shown to Python, in the store's order, by name:
// f(name, member pointer, doc).
template <class F>
void for_each_particle_field(F&& f) {
    f("ids", &ParticleStore::id, "global id (int64): the particle's index in the scenario, never changes");
    f("positions", &ParticleStore::position, "positions, m (N x 3)");
    f("velocities", &ParticleStore::velocity, "velocities, m/s (N x 3)");
    f("angular_velocities", &ParticleStore::angular_velocity, "spins, rad/s (N x 3)");
    f("forces", &ParticleStore::force,
      "force of the contacts and flat walls on each particle at the last step, N (N x 3; gravity not included; "
      "on a kinematic particle, the load of the grains on it)");
    f("torques", &ParticleStore::torque, "torque of the contacts on each particle at the last step, N m (N x 3)");
    f("radii", &ParticleStore::radius, "radii, m");
    f("masses", &ParticleStore::mass, "masses, kg");
    f("materials", &ParticleStore::material, "material index (int32) into material_names");
    f("motions", &ParticleStore::motion, "prescribed motion (int32): -1 free, else the motion's index (kinematic)");
    f("tags", &ParticleStore::tag, "the scenario's tag (int32), e.g. the half a drum grain started in");
}

}  // namespace tumble::python
