// Scene files: a TOML description of one run (the model, the solver settings, the output
// settings), read with toml++. Every key is declared once with its unit, default and allowed
// range (models/scene_schema.hpp, and the methods' options for [solver]); docs/scenes.md's
// key tables are generated from those declarations. Every key is validated and unknown keys
// are errors.
//
// Errors throw std::invalid_argument with "<file>:<line>:<col>: <key>: <what is allowed>"
// (for a value set by an override: "<file>: <key> (override): <what is allowed>").
#pragma once

#include "integrators/run.hpp"
#include "integrators/system.hpp"
#include "models/bridge_design.hpp"
#include "models/excitation_scaling.hpp"
#include "models/scene_schema.hpp"

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace nsb::models {

struct Scene {
  std::string name;                   // file stem
  std::string kind;                   // [model] kind
  std::filesystem::path path;
  std::unique_ptr<integrators::System> system;
  // The design of a bridge of one deck ([model] kind = "bridge" with [model.deck]) or of a
  // free deck (kind = "rigid_deck"), as built into `system` (models/bridge_design.hpp): what
  // the figures, claims and checks read of the bridge. Empty for the other kinds and for a
  // bridge in segments.
  std::optional<BridgeDesign> design;
  integrators::RunConfig run;          // the [solver] table: the options of its method
  OutputSettings output;
  double record_step = 0.0;            // shortest sampling interval of the scene's ground-motion
                                       //   records after time scaling [s]; 0 without a record
  InputMotion input;                   // PGA, PSA and factor of each excitation component
                                       //   (summary.json "input"); empty without a record
};

// Reads, validates and builds a scene. overrides: "section.key=value" strings (e.g.
// "solver.step=1e-5", "model.excitation.target_pga=0.5", "model.bents.0.height=2.0"; array
// elements by 0-based index), applied before validation. The value is parsed as a TOML value;
// if it is not one, it is taken as a string ("solver.method=event_driven"). Overriding a key
// the scene schema does not know is an error. Record files are looked up relative to the scene
// file's folder, then in ../data/ beside it, then in ./data/.
Scene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});

}  // namespace nsb::models
