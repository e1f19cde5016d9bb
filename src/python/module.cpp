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
    // Bad input and failed runs (the reason, naming the file and key where
    // there is one); a run that became unphysical (the diagnostic).
    const auto& error = py::register_exception<tumble::Error>(m, "Error", PyExc_RuntimeError);
    py::register_exception<tumble::experiments::BlewUp>(m, "BlewUp", error.ptr());
    m.def("set_program_name", &tumble::experiments::set_program_name, py::arg("name"),
          "The tumble program that messages name in the commands they suggest (tumble resume DIR)");
    bind_scenario(m);
    bind_simulation(m);
    bind_drum(m);
    bind_sweep(m);
    bind_analysis(m);
}
