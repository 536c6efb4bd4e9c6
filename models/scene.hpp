// Scene files: a TOML description of one run (the model, the solver settings, the output
// settings), read with toml++. Every key is documented in docs/scenes.md with its unit,
// default and allowed range; every key is validated and unknown keys are errors.
//
// Errors throw std::invalid_argument with "<file>:<line>:<col>: <key>: <what is allowed>"
// (for a value set by an override: "<file>: <key> (override): <what is allowed>").
#pragma once

#include "integrators/run.hpp"
#include "integrators/system.hpp"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace nsb::models {

struct SolverSettings {
  std::string method = "moreau";      // "moreau" | "event_driven" | "compliance"
  double end_time = 1.0;              // [s], > 0
  double step = 1e-4;                 // Moreau–Jean time step h [s], in (0, end_time]
  double theta = 0.5;                 // Moreau–Jean theta in [0.5, 1]
  double tolerance = 1e-8;            // event-driven / compliance error tolerance (abs and rel), > 0
  std::string lcp_solver = "lemke";   // "lemke" | "pgs" | "nfb" | "enum"
  double stiffness_factor = 1.0;      // compliance: multiplies contact_stiffness, > 0
  double contact_stiffness = 2.747e7; // compliance: Hertz k [kN/m^1.5] (868.7 kN/mm^1.5,
                                      //   Muthukumar & DesRoches 2006), > 0
  std::string damping_law = "hertzdamp"; // compliance: "hertzdamp" (Lankarani–Nikravesh /
                                      //   Muthukumar–DesRoches), "flores", "hunt_crossley_exact"
  double stick_slip_velocity = 1e-3;  // compliance: eps_v of eq. (10) [m/s], > 0
  void validate() const;              // throws std::invalid_argument naming the field
};

struct OutputSettings {
  double sample_dt = 0.0;  // [s], >= 0; 0 = every step
  void validate() const;   // throws std::invalid_argument naming the field
};

struct Scene {
  std::string name;                   // file stem
  std::string kind;                   // [model] kind
  std::filesystem::path path;
  std::unique_ptr<integrators::System> system;
  SolverSettings solver;               // the [solver] keys as read (after overrides)
  integrators::RunConfig run;          // the typed configuration built from them, once
  OutputSettings output;
  double record_step = 0.0;            // shortest sampling interval of the scene's ground-motion
                                       //   records after time scaling [s]; 0 without a record
};

// The typed run configuration of validated solver settings: the options struct of
// settings.method with the scene's values. Throws std::invalid_argument naming the key.
integrators::RunConfig make_run_config(const SolverSettings& settings);

// The model kinds a scene may name in [model] kind.
const std::vector<std::string>& scene_kinds();

// Reads, validates and builds a scene. overrides: "section.key=value" strings (e.g.
// "solver.step=1e-5", "model.excitation.target_pga=0.5", "model.bents.0.height=2.0"; array
// elements by 0-based index), applied before validation. The value is parsed as a TOML value;
// if it is not one, it is taken as a string ("solver.method=event_driven"). Overriding a key
// the scene schema does not know is an error. Record files are looked up relative to the scene
// file's folder, then in ../data/ beside it, then in ./data/.
Scene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});

}  // namespace nsb::models
