// Scene files: a TOML description of one run (the model, the solver settings, the output
// settings), read with toml++. Every key is declared once with its unit, default and allowed
// range (a model's keys beside its parameters in models/, the scene's own settings in
// scene/scene_schema.hpp, and the methods' options for [solver]); docs/scenes.md's key tables
// are generated from those declarations. Every key is validated and unknown keys are errors.
// A scene is also a value: a SceneTable built in code (or from a Python dict) is checked and
// built exactly as a file is.
//
// Errors throw std::invalid_argument with "<file>:<line>:<col>: <key>: <what is allowed>"
// (for a value set by an override: "<file>: <key> (override): <what is allowed>").
#pragma once

#include "integrators/run.hpp"
#include "integrators/system.hpp"
#include "models/bridge_design.hpp"
#include "models/excitation_scaling.hpp"
#include "scene/scene_schema.hpp"

#include <toml++/toml.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace nsb::scene {

// The value an override sets: a boolean, an integer, a number, a string, or an array of
// numbers (a vector3 key such as model.decks.0.initial_position).
using OverrideValue = std::variant<bool, std::int64_t, double, std::string, std::vector<double>>;

// One override: the key path "section.key" (array elements by 0-based index,
// "model.bents.0.height") and its typed value.
struct Override {
  std::string key;
  OverrideValue value;
};

// The override of the text "section.key=value": the value is parsed as a TOML value, and if
// it is not one, taken as a string ("solver.method=event_driven"), as load_scene does.
// Applying it gives the same scene as applying the text. Throws std::invalid_argument for a
// text without "=" or a key part, or a TOML value of another type (a table, a date, an array
// of non-numbers).
Override parse_override(std::string_view text);

// The text form "section.key=value" of an override, its value written as TOML; parse_override
// reads it back to the same override.
std::string to_string(const Override& o);

// Where a scene comes from: the name that stands for its file in messages and the folder its
// record files are looked up from (then ../data/ beside it, then ./data/).
struct SceneOrigin {
  std::string name;
  std::filesystem::path folder = ".";
};

// A scene as a value, before it is built: its TOML table (overrides applied), its origin and
// the key paths overrides set (their errors say "(override)" in place of a line and column).
// A table built in code has no source positions; its errors name the key only.
struct SceneTable {
  toml::table table;
  SceneOrigin origin;
  std::set<std::string> overridden;  // e.g. "model.bents[0].height"
};

// The scene file's table; a missing file or a TOML syntax error throws std::invalid_argument
// naming the file (with line and column).
SceneTable read_scene_table(const std::filesystem::path& file);

// Applies overrides in order, before any value is checked, so that an overridden value is
// checked like any other. Tables on the way are created, arrays indexed by 0-based position.
// A key the schema does not know is reported when the scene is built.
void apply_overrides(SceneTable& scene, const std::vector<Override>& overrides);
// The same from "section.key=value" texts (parse_override's rule).
void apply_overrides(SceneTable& scene, const std::vector<std::string>& overrides);

// The scene's TOML text: read back (read_scene_table, or toml::parse and a SceneTable with the
// same origin) it builds the same scene. Numbers are written as toml++ writes them, with enough
// digits to read back to the same double (up to 17 significant digits: 2e-4 is written
// 0.00020000000000000001).
std::string to_toml(const SceneTable& scene);

struct Scene {
  std::string name;                   // file stem (for a table: the stem of its origin's name)
  std::string kind;                   // [model] kind
  std::filesystem::path path;         // the file (for a table: its origin's name)
  std::unique_ptr<integrators::System> system;
  // The design of a bridge of one deck ([model] kind = "bridge" with [model.deck]) or of a
  // free deck (kind = "rigid_deck"), as built into `system` (models/bridge_design.hpp): what
  // the figures, claims and checks read of the bridge. Empty for the other kinds and for a
  // bridge in segments.
  std::optional<models::BridgeDesign> design;
  integrators::RunConfig run;          // the [solver] table: the options of its method
  EstimateSettings estimate;           // [solver] error_estimate and accuracy
  OutputSettings output;
  double record_step = 0.0;            // shortest sampling interval of the scene's ground-motion
                                       //   records after time scaling [s]; 0 without a record
  models::InputMotion input;           // PGA, PSA and factor of each excitation component
                                       //   (summary.json "input"); empty without a record
  SceneTable table;                    // what it was built from (to_toml(scene.table))
};

// Validates a scene's table and builds the scene: every key is checked against the schema
// with the same checks and messages as a scene file's ("<origin name>:<line>:<col>: <key>:
// ..." for a table with source positions, "<origin name>: <key>: ..." without).
Scene build_scene(const SceneTable& scene);

// Reads, validates and builds a scene: read_scene_table, apply_overrides, build_scene.
// overrides: "section.key=value" strings (e.g. "solver.step=1e-5",
// "model.excitation.target_pga=0.5", "model.bents.0.height=2.0"). Overriding a key the scene
// schema does not know is an error. Record files are looked up relative to the scene file's
// folder, then in ../data/ beside it, then in ./data/. Typed overrides: read_scene_table,
// apply_overrides and build_scene.
Scene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});

}  // namespace nsb::scene
