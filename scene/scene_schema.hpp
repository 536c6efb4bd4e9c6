// The schema of scene files beyond the models' own keys: every key of every table is declared
// once as a config::Field (key, member, unit, range, meaning; the default is the member's
// initializer, or the benchmark's value for the bridge). A model's keys are declared beside
// its parameters struct in models/ (simple_systems.hpp, deck_chain.hpp, shear_keys.hpp,
// bridge_fields.hpp); the keys that a model's parameters struct cannot hold
// (delays, record names, target PGAs) are members of the settings structs below. The scene
// reader reads each table by looping over these declarations and docs/scenes.md's key tables
// are generated from them (scene/scene_docs.hpp).
#pragma once

#include "config/schema.hpp"
#include "models/bridge_design.hpp"

#include <array>
#include <span>
#include <string>
#include <vector>

namespace nsb::scene {

// The top level and [model]: the free description and the model kind.
struct SceneHeader {
  std::string description;
  std::string kind;
  static std::span<const config::Field<SceneHeader>> fields();  // description, kind
};

// [solver] method: the integrator whose options the other [solver] keys set.
struct MethodSetting {
  std::string method = "moreau";
  static std::span<const config::Field<MethodSetting>> fields();
};

// [solver] error_estimate, accuracy, adapt: the numerical error estimate of every peak of a run and
// the accuracy it is judged against (runs/estimate.hpp, docs/error-estimates.md). Keys of
// every method, read by the run pipeline, not by an integrator.
struct EstimateSettings {
  bool error_estimate = true;  // estimate each peak's error by a companion run
  double accuracy = 1e-2;      // relative accuracy target of the coordinates' peaks, in (0, 1)
  bool adapt = false;          // refine solver.step or solver.tolerance until accuracy is met
  static std::span<const config::Field<EstimateSettings>> fields();
  void validate() const;       // throws std::invalid_argument naming the key
};

// [output]
struct OutputSettings {
  double sample_dt = 0.0;  // sampling interval of the history [s], >= 0; 0 = every step
  // The optional output groups (integrators::kOutputGroupNames), comma-separated in the order
  // of that list; empty: the default files (docs/outputs.md, "Optional groups").
  std::string groups;
  static std::span<const config::Field<OutputSettings>> fields();
  void validate() const;   // throws std::invalid_argument naming the key
};

// One [[model.bents]] element: its position, the column design its springs are derived from
// (models/bridge_design.hpp, BentDesign), explicit spring values that replace the derived ones (0:
// derived) and the wave-passage delay of its ground motion.
struct BentSettings {
  double position = 0.0;                  // s_j along the deck axis from the centre [m]
  models::BentDesign design;
  double stiffness_longitudinal = 0.0;    // [kN/m], 0: design.stiffness()
  double yield_force_longitudinal = 0.0;  // [kN], 0: design.yield_force()
  double stiffness_transverse = 0.0;
  double yield_force_transverse = 0.0;
  double delay = 0.0;                     // [s]
  int segment = 0;                        // 0-based [[model.segments]] index it carries
  std::vector<double> column_offsets;     // [m], one per column; empty: the bent on the axis
  double skew_deg = 0.0;                  // the bent's own skew [deg]
  static std::span<const config::Field<BentSettings>> fields();
};

// [model.seats] beyond the contact law: how the two seats move.
struct SeatMotionSettings {
  bool transverse = false;            // the seats follow the transverse record too
  double delay_left = 0.0;            // wave-passage delay of each seat [s]
  double delay_right = 0.0;
  std::string rotation_record_left;   // angular acceleration record of each seat ("" none)
  std::string rotation_record_right;
  double rotation_unit = 1.0;         // [rad/s^2 per file unit]
  double rotation_dt = 0.0;           // [s] step of a rotation file of values only; 0: none
  double rotation_scale = 1.0;        // factor on the rotation records
  static std::span<const config::Field<SeatMotionSettings>> fields();
};

// How [model.excitation] scales its records: to a peak ground acceleration, or to a 5 %-damped
// (sa_damping) pseudo-spectral acceleration at a period (docs/bridge.md, "Target spectral
// accelerations").
enum class ScaleTo { kPga, kSa };
inline constexpr std::array<config::Name<ScaleTo>, 2> kScaleToNames{
    {{"pga", ScaleTo::kPga}, {"sa", ScaleTo::kSa}}};

// [model.excitation]: the two records, their scaling and the shared options.
struct ExcitationSettings {
  std::string longitudinal_record;  // record file of the x component ("" none)
  std::string transverse_record;    // record file of the y component ("" none)
  double record_unit = 1.0;         // [m/s^2 per file unit]
  double record_dt = 0.0;           // [s] step of a record file of values only; 0: none
  double target_pga = 0.0;          // [g], 0: as recorded
  double longitudinal_pga = 0.0;    // [g], 0: the factor of target_pga
  double scale = 1.0;
  double time_scale = 1.0;
  bool baseline_correction = true;
  ScaleTo scale_to = ScaleTo::kPga;
  double target_sa = 0.0;           // [g], scale_to = "sa": PSA of the transverse record
  double longitudinal_sa = 0.0;     // [g], scale_to = "sa": of the longitudinal one; 0: same factor
  double sa_period = 0.0;           // [s], > 0; absent: the bridge's first (longest) period
  double sa_damping = 0.05;         // zeta of the oscillator, in [0, 1)
  static std::span<const config::Field<ExcitationSettings>> fields();
};

// [[model.excitation.sequence]]: a sequence of records (a mainshock and its aftershocks), each
// entry with the record keys of [model.excitation] (all but time_scale and
// baseline_correction, which the sequence shares) and the rest after it (docs/ground-motions.md,
// "Sequences").
struct SequenceSettings {
  double rest = 0.0;  // [s], >= 0: zero ground acceleration after the record
  static std::span<const config::Field<SequenceSettings>> fields();
};

// The keys of [model.excitation] that a sequence shares; its other keys belong to the entries.
inline constexpr std::array<std::string_view, 2> kSequenceSharedKeys{"time_scale",
                                                                     "baseline_correction"};

// [model] keys of a deck in several bodies (a bridge in [[model.segments]], a deck chain):
// the skew of every end face.
struct LayoutSettings {
  double skew_deg = 0.0;  // alpha [deg], |alpha| < 80
  static std::span<const config::Field<LayoutSettings>> fields();
};

// A joint's own angle (docs/bridge.md, "Faces with their own angles"): [[model.hinges]]
// skew_deg sets both faces of that hinge; [model.abutments] skew_left_deg / skew_right_deg
// each abutment's face and the deck end on it. Absent: the bridge's skew_deg.
struct HingeSkewSettings {
  double skew_deg = 0.0;  // [deg], |alpha| < 80
  static std::span<const config::Field<HingeSkewSettings>> fields();
};
struct AbutmentSkewSettings {
  double skew_left_deg = 0.0;   // [deg], |alpha| < 80
  double skew_right_deg = 0.0;  // [deg], |alpha| < 80
  static std::span<const config::Field<AbutmentSkewSettings>> fields();
};

// [model.deck] angle_deg: a curved deck's subtended angle, instead of its length (docs/bridge.md,
// "Curved decks").
struct CurvedDeckSettings {
  double angle_deg = 0.0;  // phi [deg], in (0, 180); length = radius phi
  static std::span<const config::Field<CurvedDeckSettings>> fields();
};

// The seat a deck end rests on, of [model.abutments] (both abutments) and of each
// [[model.hinges]] element: its length along the axis, from the backwall (abutment) or from
// the other frame's end face (hinge) to the seat's edge (docs/limit-states.md, "Unseating").
struct SeatLengthSettings {
  double seat_length = 0.0;  // [m], > 0; absent: unseating is not watched
  static std::span<const config::Field<SeatLengthSettings>> fields();
};

// [model.limit_states]: the limits of the bents' drift ratio and the deck's residual rotation
// (docs/limit-states.md); absent keys are not watched.
struct LimitStateSettings {
  double drift_ratio = 0.0;        // [-], > 0
  double residual_rotation = 0.0;  // [rad], > 0
  static std::span<const config::Field<LimitStateSettings>> fields();
};

// The model kinds a scene may name in [model] kind.
const std::vector<std::string>& scene_kinds();

}  // namespace nsb::scene
