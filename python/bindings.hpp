// The parts of the extension module, one function each (python/module.cpp calls them).
#pragma once

#include <pybind11/pybind11.h>

namespace nsb::python {

// nsbridge.lcp: solve(M, q, solver, **options), frictional_problem(...); nsbridge.criterion.
void bind_lcp(pybind11::module_& m);
// nsbridge.load_scene, run, Scene, Result.
void bind_runs(pybind11::module_& m);
// nsbridge.sweep, build_info, __version__.
void bind_sweep(pybind11::module_& m);

}  // namespace nsb::python
