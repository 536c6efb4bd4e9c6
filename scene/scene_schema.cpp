// The scene keys of the models and of the scene itself: key, unit, range and meaning, declared
// once (docs/scenes.md is generated from these; units kN, t, m, s, rad unless the unit says).
#include "scene/scene_schema.hpp"

#include "integrators/run.hpp"

namespace nsb::scene {

using namespace models;  // the systems and parts a scene builds

namespace c = config;

namespace {

// Bounds of the excitation's scaling keys (docs/scenes.md, "Plausible values"): a target
// acceleration beyond 20 g is five times the largest recorded (about 4 g), and a factor or
// unit beyond 1000 (or a time scale below 1/1000) takes a record's amplitude or duration
// past any motion a bridge meets; past them the scaled record overflows or its duration
// exceeds the work a run may take.
constexpr double kMaxTarget = 20.0;    // [g]
constexpr double kMaxFactor = 1000.0;  // [-]
// A rest between records of a sequence beyond a day is no aftershock sequence a run models
// (the damping has long brought the bridge to rest), and it bounds the run's length.
constexpr double kMaxRest = 86400.0;   // [s]

// A choice among names known at run time (a std::string member), for lists that are not enums.
template <class S>
c::Field<S> name_choice(std::string_view key, const std::vector<std::string_view>& names,
                        std::string_view meaning, c::Value (*get)(const S&),
                        void (*set)(S&, const c::Value&)) {
  c::Field<S> f;
  f.key = key;
  f.kind = c::Kind::kChoice;
  f.choices = names;
  f.meaning = meaning;
  f.get = get;
  f.set = set;
  return f;
}

std::vector<std::string_view> kind_names() {
  std::vector<std::string_view> out;
  for (const auto& k : scene_kinds()) out.push_back(k);
  return out;
}

}  // namespace

const std::vector<std::string>& scene_kinds() {
  static const std::vector<std::string> k{"bridge",        "deck_chain",        "rigid_deck",
                                          "bouncing_ball", "impact_oscillator", "sliding_block"};
  return k;
}

std::span<const c::Field<SceneHeader>> SceneHeader::fields() {
  using S = SceneHeader;
  static const c::Field<S> f[] = {
      c::text<&S::description>("description", "free text"),
      name_choice<S>(
          "kind", kind_names(), "the model ([model] kind)",
          [](const S& s) -> c::Value { return s.kind; },
          [](S& s, const c::Value& v) { s.kind = std::get<std::string>(v); }),
  };
  return f;
}

std::span<const c::Field<MethodSetting>> MethodSetting::fields() {
  using S = MethodSetting;
  static const c::Field<S> f[] = {
      name_choice<S>(
          "method", integrators::method_names(),
          "integrator: selects the options struct the other [solver] keys set",
          [](const S& s) -> c::Value { return s.method; },
          [](S& s, const c::Value& v) { s.method = std::get<std::string>(v); }),
  };
  return f;
}

std::span<const c::Field<EstimateSettings>> EstimateSettings::fields() {
  using S = EstimateSettings;
  static const c::Field<S> f[] = {
      c::boolean<&S::error_estimate>(
          "error_estimate",
          "estimate the numerical error of every peak, the impact count and the first impact's "
          "time by a companion run (Moreau–Jean at twice solver.step, or at 10 times "
          "solver.local_tolerance with adaptive steps, the adaptive methods at "
          "100 times solver.tolerance) extrapolated at the method's measured order "
          "(docs/error-estimates.md); "
          "false: no estimate, the run alone"),
      c::number<&S::accuracy>(
          "accuracy", "-", c::open(0.0, 1.0),
          "relative accuracy target: a run whose estimated error of a coordinate's peak exceeds "
          "accuracy times the peak warns \"accuracy: ...\" (exit 1 under --strict)"),
      c::boolean<&S::adapt>(
          "adapt",
          "choose the steps (Moreau–Jean: adaptive steps at solver.local_tolerance, 0.01 × "
          "accuracy unless given) or the tolerance (event-driven, compliance; event-driven "
          "starts no looser than 1e-8) to meet "
          "accuracy: refined while the estimate exceeds accuracy, at most 6 "
          "runs (docs/error-estimates.md, \"Choosing the step\"); needs error_estimate"),
  };
  return f;
}

void EstimateSettings::validate() const {
  c::validate_fields<EstimateSettings>(*this, fields(), "solver.");
}

std::span<const c::Field<OutputSettings>> OutputSettings::fields() {
  using S = OutputSettings;
  static const c::Field<S> f[] = {
      c::number<&S::sample_dt>("sample_dt", "s", c::non_negative(),
                               "sampling interval of history.csv; 0 records every step"),
      c::text<&S::groups>("groups",
                          "optional column groups, an array of names: bents, relative, ground, "
                          "energy, forces, impulses (docs/outputs.md); [] the default files"),
  };
  return f;
}

void OutputSettings::validate() const { c::validate_fields<OutputSettings>(*this, fields(), "output."); }

std::span<const c::Field<BentSettings>> BentSettings::fields() {
  using S = BentSettings;
  using B = BentDesign;
  static const c::Field<S> f[] = {
      c::number<&S::position>("position", "m", c::any(),
                              "along the deck axis from the centre; |position| <= length / 2 "
                              "(required)"),
      c::number<&S::design, &B::height>("height", "m", c::positive(),
                                        "clear column height H (required unless both "
                                        "stiffness_* and yield_force_* are given)"),
      c::number<&S::design, &B::column_diameter>("column_diameter", "m", c::positive(),
                                                 "column diameter d"),
      c::integer<&S::design, &B::columns>("columns", c::closed(1, 100), "columns per bent"),
      c::number<&S::design, &B::elastic_modulus>("elastic_modulus", "kPa", c::positive(),
                                                 "E_c (30 GPa)"),
      c::number<&S::design, &B::cracked_ratio>("cracked_ratio", "-", c::open_closed(0, 1),
                                               "EI_eff / EI_gross"),
      c::number<&S::design, &B::yield_strain>("yield_strain", "-", c::positive(),
                                              "ε_y of the reinforcement"),
      c::number<&S::design, &B::post_yield_ratio>("post_yield_ratio", "-", c::closed_open(0, 1),
                                                  "Takeda post-yield / yield stiffness"),
      c::number<&S::design, &B::unloading_exponent>("unloading_exponent", "-", c::closed(0, 1),
                                                    "Takeda unloading exponent α"),
      c::number<&S::stiffness_longitudinal>("stiffness_longitudinal", "kN/m", c::positive(),
                                            "whole bent along x (default: from the design)"),
      c::number<&S::yield_force_longitudinal>("yield_force_longitudinal", "kN", c::positive(),
                                              "whole bent along x (default: from the design)"),
      c::number<&S::stiffness_transverse>("stiffness_transverse", "kN/m", c::positive(),
                                          "whole bent along y (default: from the design)"),
      c::number<&S::yield_force_transverse>("yield_force_transverse", "kN", c::positive(),
                                            "whole bent along y (default: from the design)"),
      c::number<&S::delay>("delay", "s", c::non_negative(),
                           "wave-passage delay of this bent's ground motion"),
      c::integer<&S::segment>("segment", c::non_negative(),
                              "0-based index of the [[model.segments]] element the bent "
                              "carries (0 with [model.deck]); position is measured on it"),
      c::numbers<&S::column_offsets>("column_offsets", "m", c::any(),
                                     "the columns' transverse positions from the deck axis, "
                                     "one per column (as many as columns), each with 1/columns "
                                     "of both springs; default: the whole bent on the axis"),
      c::number<&S::skew_deg>("skew_deg", "deg", c::open(-80, 80),
                              "the bent's own skew β: its line through (position, 0) at β "
                              "from the transverse axis, springs along its normal and along it"),
  };
  return f;
}

std::span<const c::Field<SeatMotionSettings>> SeatMotionSettings::fields() {
  using S = SeatMotionSettings;
  static const c::Field<S> f[] = {
      c::boolean<&S::transverse>("transverse",
                                 "true: the seats also follow the transverse ground motion"),
      c::number<&S::delay_left>("delay_left", "s", c::non_negative(),
                                "wave-passage delay of the left seat"),
      c::number<&S::delay_right>("delay_right", "s", c::non_negative(),
                                 "wave-passage delay of the right seat"),
      c::number<&S::rotation_scale>("rotation_scale", "-", c::closed(-kMaxFactor, kMaxFactor),
                                    "factor on the rotation records"),
      c::number<&S::rotation_unit>("rotation_unit", "rad/s^2 per file unit",
                                   c::open_closed(0, kMaxFactor),
                                   "unit of the rotation records' values"),
      c::number<&S::rotation_dt>("rotation_dt", "s", c::positive(),
                                 "sample step of a rotation record file that holds values "
                                 "only (no time column); absent: the file gives its times"),
      c::text<&S::rotation_record_left>("rotation_record_left",
                                        "record file of the left seat's angular acceleration "
                                        "(rad/s² × rotation_unit, two-column or CSV); the seat "
                                        "rotates about its face point on the deck axis"),
      c::text<&S::rotation_record_right>("rotation_record_right",
                                         "the same for the right seat"),
  };
  return f;
}

std::span<const c::Field<ExcitationSettings>> ExcitationSettings::fields() {
  using S = ExcitationSettings;
  static const c::Field<S> f[] = {
      c::text<&S::longitudinal_record>("longitudinal_record", "record file of the x component"),
      c::text<&S::transverse_record>("transverse_record", "record file of the y component"),
      c::number<&S::record_unit>("record_unit", "m/s^2 per file unit",
                                 c::open_closed(0, kMaxFactor),
                                 "unit of the values of text and CSV records whose file names "
                                 "no unit; given, it must agree with a unit the file names "
                                 "(.AT2 files are in g)"),
      c::number<&S::record_dt>("record_dt", "s", c::positive(),
                               "sample step of a record file that holds acceleration values "
                               "only (one or several per line, no time column); absent: the "
                               "file gives its times (docs/ground-motions.md)"),
      c::number<&S::target_pga>("target_pga", "g", c::closed(0, kMaxTarget),
                                "PGA of the transverse record (or of the longitudinal one when "
                                "it is alone); without longitudinal_pga the other component "
                                "takes the same factor; 0 keeps the recorded amplitude"),
      c::number<&S::longitudinal_pga>("longitudinal_pga", "g", c::closed(0, kMaxTarget),
                                      "PGA of the longitudinal record on its own (needs "
                                      "longitudinal_record); 0: the factor of target_pga"),
      c::number<&S::scale>("scale", "-", c::closed(-kMaxFactor, kMaxFactor),
                           "an extra factor on both components"),
      c::number<&S::time_scale>("time_scale", "-", c::closed(1.0 / kMaxFactor, kMaxFactor),
                                "t → time_scale · t (0.5 for the 1/4-scale similitude)"),
      c::boolean<&S::baseline_correction>("baseline_correction",
                                          "remove the drift of velocity and displacement"),
      c::choice<&kScaleToNames, &S::scale_to>(
          "scale_to", "what target_pga / target_sa set: \"pga\" the peak ground acceleration, "
                      "\"sa\" the pseudo-spectral acceleration PSA(sa_period, sa_damping)"),
      c::number<&S::target_sa>("target_sa", "g", c::closed(0, kMaxTarget),
                               "scale_to = \"sa\": PSA of the transverse record (or of the "
                               "longitudinal one when it is alone); without longitudinal_pga "
                               "or longitudinal_sa the other component takes the same factor; "
                               "0 keeps the recorded amplitude"),
      c::number<&S::longitudinal_sa>("longitudinal_sa", "g", c::closed(0, kMaxTarget),
                                     "scale_to = \"sa\": PSA of the longitudinal record on its "
                                     "own (needs longitudinal_record); 0: the common factor"),
      c::number<&S::sa_period>("sa_period", "s", c::positive(),
                               "oscillator period of target_sa and of the reported Sa; "
                               "absent: the bridge's first natural period (K₀ φ = ω² M φ)"),
      c::number<&S::sa_damping>("sa_damping", "-", c::closed_open(0, 1),
                                "oscillator damping ratio ζ of target_sa and the reported Sa"),
  };
  return f;
}

std::span<const c::Field<SequenceSettings>> SequenceSettings::fields() {
  using S = SequenceSettings;
  static const c::Field<S> f[] = {
      c::number<&S::rest>("rest", "s", c::closed(0, kMaxRest),
                          "rest interval after the record: zero ground acceleration, the bridge "
                          "moving freely; the next record starts this long after the last "
                          "sample of this one (after the last record, the run goes on this "
                          "long by default)"),
  };
  return f;
}

std::span<const c::Field<LayoutSettings>> LayoutSettings::fields() {
  using S = LayoutSettings;
  static const c::Field<S> f[] = {
      c::number<&S::skew_deg>("skew_deg", "deg", c::open(-80, 80),
                              "skew angle α of every end face and abutment face"),
  };
  return f;
}

std::span<const c::Field<HingeSkewSettings>> HingeSkewSettings::fields() {
  using S = HingeSkewSettings;
  static const c::Field<S> f[] = {
      c::number<&S::skew_deg>("skew_deg", "deg", c::open(-80, 80),
                              "this hinge's own angle α (both its faces); absent: [model] "
                              "skew_deg"),
  };
  return f;
}

std::span<const c::Field<AbutmentSkewSettings>> AbutmentSkewSettings::fields() {
  using S = AbutmentSkewSettings;
  static const c::Field<S> f[] = {
      c::number<&S::skew_left_deg>("skew_left_deg", "deg", c::open(-80, 80),
                                   "the left abutment's own angle α (its face and the deck end "
                                   "on it); absent: the deck's skew_deg"),
      c::number<&S::skew_right_deg>("skew_right_deg", "deg", c::open(-80, 80),
                                    "the right abutment's own angle α; absent: the deck's "
                                    "skew_deg"),
  };
  return f;
}

std::span<const c::Field<CurvedDeckSettings>> CurvedDeckSettings::fields() {
  using S = CurvedDeckSettings;
  static const c::Field<S> f[] = {
      c::number<&S::angle_deg>("angle_deg", "deg", c::open(0, 180),
                               "a curved deck's subtended angle φ, instead of length "
                               "(length = radius φ)"),
  };
  return f;
}

std::span<const c::Field<SeatLengthSettings>> SeatLengthSettings::fields() {
  using S = SeatLengthSettings;
  static const c::Field<S> f[] = {
      c::number<&S::seat_length>("seat_length", "m", c::positive(),
                                 "seat length N from the backwall (abutment) or from the other "
                                 "frame's end face (hinge) to the seat's edge; given: "
                                 "unseating is watched and a lost seat stops the run"),
  };
  return f;
}

std::span<const c::Field<LimitStateSettings>> LimitStateSettings::fields() {
  using S = LimitStateSettings;
  static const c::Field<S> f[] = {
      c::number<&S::drift_ratio>("drift_ratio", "-", c::positive(),
                                 "limit of every bent's drift ratio |Δ| / H (needs every "
                                 "bent's height); absent: not watched"),
      c::number<&S::residual_rotation>("residual_rotation", "rad", c::positive(),
                                       "limit of |θ| of each deck segment at the end of the "
                                       "run; absent: not watched"),
  };
  return f;
}

}  // namespace nsb::scene
