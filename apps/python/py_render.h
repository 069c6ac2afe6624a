#pragma once
// nxrender.render: the command line's render from Python, with the GIL released while the
// worker threads trace, Ctrl-C (KeyboardInterrupt) stopping it, and a progress callback.

#include <pybind11/pybind11.h>

namespace nxpy {

namespace py = pybind11;

/// Registers render.
void bindRender(py::module_& m);

} // namespace nxpy
