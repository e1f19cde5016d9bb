// SPDX-License-Identifier: MIT
// tumble._core: the compiled part of the Python module (bindings.hpp).
#include "bindings.hpp"
#include "experiments/run_control.hpp"
#include "tumble/core/error.hpp"

PYBIND11_MODULE(_core, m) {
    namespace py = pybind11;
    using namespace tumble::python;
    m.doc() = "tumble's engine, readers, drum protocol, sweep and analysis (import tumble, not this)";
    m.attr("version") = TUMBLE_VERSION;
    const auto& error = py::register_exception<tumble::Error>(m, "Error", PyExc_RuntimeError);
    error.attr("__doc__") =
        "Bad input or a failed run: the message gives the reason, and the file and key where there is one";
    py::register_exception<tumble::experiments::BlewUp>(m, "BlewUp", error.ptr()).attr("__doc__") =
        "A run that became unphysical: the message is the diagnostic; its last checkpoint, written before, stays "
        "good (docs/CHECKPOINTS.md, \"Blow-up detection\")";
    m.def("set_program_name", &tumble::experiments::set_program_name, py::arg("name"),
          "The tumble program that messages name in the commands they suggest (tumble resume DIR)");
    bind_scenario(m);
    bind_simulation(m);
    bind_drum(m);
    bind_sweep(m);
    bind_analysis(m);
}
