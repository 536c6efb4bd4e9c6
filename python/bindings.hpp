// The parts of the extension module, one function each (python/module.cpp calls them).
#pragma once

#include "models/deck_geometry.hpp"

#include <pybind11/pybind11.h>

namespace nsb::python {

// nsbridge.lcp: solve(M, q, solver, **options), frictional_problem(...); nsbridge.criterion.
void bind_lcp(pybind11::module_& m);
// The dict of `nsbridge criterion --json` for a plan: eta of each end at the friction mu
// (models::analytic::plan_criterion); nsbridge.end_criterion and nsbridge.scene_criterion.
pybind11::dict plan_criterion_dict(const models::DeckGeometry& plan, double friction);
// nsbridge.load_scene, run, Scene, Result.
void bind_runs(pybind11::module_& m);
// nsbridge.sweep, build_info, __version__.
void bind_sweep(pybind11::module_& m);

}  // namespace nsb::python
