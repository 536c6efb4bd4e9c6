// The parts of load_scene (scene/scene.hpp): the [solver] table read into the typed run
// configuration, the simple systems and the bridge built from their [model] tables.
#pragma once

#include "integrators/run.hpp"
#include "integrators/system.hpp"
#include "models/bridge_parts.hpp"
#include "models/deck_chain.hpp"
#include "models/excitation_scaling.hpp"
#include "models/parts.hpp"
#include "scene/scene_reader.hpp"
#include "scene/scene_schema.hpp"

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace nsb::scene {

// [solver]: `method` selects the options struct (integrators::default_config); every other
// key is read into the chosen method's field of that key with that field's range. A key only
// other methods declare is accepted when one of them accepts its value (a scene may carry the
// settings of several methods; --method switches between them); a key no method declares is
// unknown.
// solver.error_estimate and solver.accuracy (every method's keys) go into `estimate`.
integrators::RunConfig read_solver(Section& s, EstimateSettings& estimate);

// The chosen method's own checks across fields (Moreau–Jean: step <= end_time), reported at
// the [solver] key they name.
void check_solver(const Section& s, const integrators::RunConfig& config);

// A rigid deck body's mass [t] and inertia [t m^2] against its plan L x W [m], refused at the
// key most likely wrong when off by a unit factor (docs/scenes.md, "Plausible values"): the
// mass per area within [1e-6, 100] t/m^2 (a concrete deck weighs 1 to 2 t/m^2, a mass in kg
// a thousand times that), the inertia within [1e-6, 100] times that of the mass spread
// uniformly, m (L^2 + W^2) / 12 (all of it at the ends is 3 times).
void check_body(const Section& s, double mass, double inertia, double length, double width);

// The bound on the work of a run (integrators/work_bounds.hpp): the steps and history rows of
// config over [t0, end_time] with the history sampled every sample_dt, refused at the key of
// [solver] or [output] that makes them too many.
void check_work(const Section& solver, const Section& output,
                const integrators::RunConfig& config, double t0, double sample_dt);

// bouncing_ball, impact_oscillator or sliding_block from the [model] table.
std::unique_ptr<integrators::System> build_simple_system(const std::string& kind, Section& m);

// The bridge of [model] kind = "bridge" (an assembly of parts), its design (one deck: the
// bridge as built, before the parts the scene adds; a bridge in segments has none), the end
// of its longest bent support motion [s] (0 without an excitation), the time scale of its
// records and their scaling.
struct BridgeScene {
  std::unique_ptr<integrators::System> system;
  std::optional<models::BridgeDesign> design;
  models::InputMotion input;  // the scaling of each excitation component
  double motion_end = 0.0;
  double time_scale = 1.0;
};
BridgeScene build_bridge(Section& m);

// The free deck of [model] kind = "rigid_deck": a design without bents, built as an assembly
// of one body against two fixed seats (models/bridge_parts.hpp); no excitation.
BridgeScene build_rigid_deck(Section& m);

// The deck bodies of [[model.<key>]] (models/bridge_fields.hpp, segment_fields): at least one,
// mass, inertia, length and width required (neighbours may differ in width).
std::vector<models::parts::RigidBody> read_bodies(const Section& m, std::string_view key);

// A model's "initial penetration" error of a deck in bodies (the arrays of tables `bodies` and
// `joints` of m) rethrown at the first body's initial_position given, naming every initial
// position and gap given; returns for another error or when no initial position is given.
void rethrow_penetration(const Section& m, std::string_view bodies, std::string_view joints,
                         const std::invalid_argument& e);
// Exactly `count` [[model.<key>]] joints (joint_fields; gap required); `rule` says why.
// `extra`: further keys an element may hold, read by the caller (seat_length, restrainer).
std::vector<models::DeckChain::Joint> read_joints(const Section& m, std::string_view key,
                                          std::size_t count, const std::string& rule,
                                          const std::vector<std::string_view>& extra = {});

// The limit-state keys of a bridge's [model] (docs/limit-states.md): [model.abutments]
// seat_length, [[model.hinges]] seat_length (one entry per element, inf where absent) and
// [model.limit_states]; the bents' heights are the caller's. `requested`: a seat length or a
// limit of [model.limit_states] is given.
struct BridgeLimitKeys {
  models::BridgeLimits limits;
  bool requested = false;
};
BridgeLimitKeys read_bridge_limits(const Section& m);

// The deck chain of [model] kind = "deck_chain" (models/deck_chain.hpp).
std::unique_ptr<integrators::System> build_deck_chain(Section& m);

}  // namespace nsb::scene
