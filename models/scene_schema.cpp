// The scene keys of the models and of the scene itself: key, unit, range and meaning, declared
// once (docs/scenes.md is generated from these; units kN, t, m, s, rad unless the unit says).
#include "models/scene_schema.hpp"

#include "integrators/run.hpp"

namespace nsb::models {

namespace c = config;

namespace {

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

std::span<const c::Field<OutputSettings>> OutputSettings::fields() {
  using S = OutputSettings;
  static const c::Field<S> f[] = {
      c::number<&S::sample_dt>("sample_dt", "s", c::non_negative(),
                               "sampling interval of history.csv; 0 records every step"),
  };
  return f;
}

void OutputSettings::validate() const { c::validate_fields<OutputSettings>(*this, fields(), "output."); }

std::span<const c::Field<BouncingBall::Parameters>> bouncing_ball_fields() {
  using P = BouncingBall::Parameters;
  static const c::Field<P> f[] = {
      c::number<&P::mass>("mass", "t", c::positive(), "mass m"),
      c::number<&P::height>("height", "m", c::non_negative(),
                            "initial height = the initial gap (< 0 would penetrate)"),
      c::number<&P::velocity>("velocity", "m/s", c::any(), "initial velocity, upward positive"),
      c::number<&P::restitution>("restitution", "-", c::closed(0, 1), "Newton's coefficient e"),
      c::number<&P::gravity>("gravity", "m/s^2", c::non_negative(), "g"),
  };
  return f;
}

std::span<const c::Field<ImpactOscillator::Parameters>> impact_oscillator_fields() {
  using P = ImpactOscillator::Parameters;
  static const c::Field<P> f[] = {
      c::number<&P::mass>("mass", "t", c::positive(), "mass m"),
      c::number<&P::stiffness>("stiffness", "kN/m", c::non_negative(), "spring k"),
      c::number<&P::damping_ratio>("damping_ratio", "-", c::non_negative(),
                                   "ζ; c = 2ζ√(km)"),
      c::number<&P::gap>("gap", "m", c::any(), "position of the stop"),
      c::number<&P::restitution>("restitution", "-", c::closed(0, 1), "Newton's coefficient e"),
      c::number<&P::initial_position>("initial_position", "m", c::any(),
                                      "x₀; at most gap (else an initial penetration)"),
      c::number<&P::initial_velocity>("initial_velocity", "m/s", c::any(), "v₀"),
      c::number<&P::force_amplitude>("force_amplitude", "kN", c::any(), "F₀ of F₀ sin(2π f t)"),
      c::number<&P::force_frequency>("force_frequency", "Hz", c::non_negative(), "f"),
  };
  return f;
}

std::span<const c::Field<SlidingBlock::Parameters>> sliding_block_fields() {
  using P = SlidingBlock::Parameters;
  static const c::Field<P> f[] = {
      c::number<&P::mass>("mass", "t", c::positive(), "mass m"),
      c::number<&P::friction>("friction", "-", c::non_negative(), "Coulomb μ"),
      c::number<&P::gravity>("gravity", "m/s^2", c::non_negative(), "g"),
      c::number<&P::initial_velocity>("initial_velocity", "m/s", c::any(), "v₀ along x"),
      c::number<&P::force>("force", "kN", c::any(), "constant driving force along x"),
      c::number<&P::force_amplitude>("force_amplitude", "kN", c::any(),
                                     "F₀ of F₀ sin(2π f t) along x"),
      c::number<&P::force_frequency>("force_frequency", "Hz", c::non_negative(), "f"),
      c::number<&P::incline_deg>("incline_deg", "deg", c::open(-90, 90), "slope angle β"),
  };
  return f;
}

std::span<const c::Field<BridgeDesign>> rigid_deck_fields() {
  using P = BridgeDesign;
  using D = DeckGeometry;
  static const c::Field<P> f[] = {
      c::number<&P::mass>("mass", "t", c::positive(), "deck mass (required)"),
      c::number<&P::inertia>("inertia", "t m^2", c::positive(),
                             "rotational inertia about the centre (required)"),
      c::number<&P::deck, &D::length>("length", "m", c::positive(), "L, along the axis (required)"),
      c::number<&P::deck, &D::width>("width", "m", c::positive(), "W (required)"),
      c::number<&P::deck, &D::skew_deg>("skew_deg", "deg", c::open(-80, 80), "skew angle α"),
      c::number<&P::deck, &D::gap_right>("gap_right", "m", c::non_negative(),
                                         "clear distance along the axis at x = y = θ = 0"),
      c::number<&P::deck, &D::gap_left>("gap_left", "m", c::non_negative(),
                                        "clear distance along the axis at x = y = θ = 0"),
      c::number<&P::restitution>("restitution", "-", c::closed(0, 1), "all four contacts"),
      c::number<&P::friction>("friction", "-", c::non_negative(), "all four contacts"),
      c::vector3<&P::initial_position>("initial_position", "m, m, rad",
                                       "(x, y, θ); no corner may penetrate"),
      c::vector3<&P::initial_velocity>("initial_velocity", "m/s, m/s, rad/s", "(vx, vy, ω)"),
  };
  return f;
}

std::span<const c::Field<BridgeDesign>> bridge_deck_fields() {
  using P = BridgeDesign;
  using D = DeckGeometry;
  static const c::Field<P> f[] = {
      c::number<&P::mass>("mass", "t", c::positive(), "deck mass m_d (paper, sec. 3)"),
      c::number<&P::inertia>("inertia", "t m^2", c::positive(),
                             "deck inertia I_d about the centre (paper, sec. 3)"),
      c::number<&P::deck, &D::length>("length", "m", c::positive(),
                                      "L = 110 ft (Saiidi, Vosooghi & Nelson 2013)"),
      c::number<&P::deck, &D::width>("width", "m", c::positive(), "W (assumed, docs/bridge.md)"),
      c::number<&P::deck, &D::skew_deg>("skew_deg", "deg", c::open(-80, 80), "skew angle α"),
      c::vector3<&P::initial_position>("initial_position", "m, m, rad",
                                       "absolute (x, y, θ) at t = 0; no corner may penetrate"),
      c::vector3<&P::initial_velocity>("initial_velocity", "m/s, m/s, rad/s", "(vx, vy, ω)"),
  };
  return f;
}

std::span<const c::Field<BridgeDesign>> bridge_gap_fields() {
  using P = BridgeDesign;
  using D = DeckGeometry;
  static const c::Field<P> f[] = {
      c::number<&P::deck, &D::gap_left>("left", "m", c::non_negative(),
                                        "clear distance along the deck axis at rest, left end"),
      c::number<&P::deck, &D::gap_right>("right", "m", c::non_negative(),
                                         "clear distance along the deck axis at rest, right end"),
  };
  return f;
}

std::span<const c::Field<ShearKeyParameters>> shear_key_fields() {
  using K = ShearKeyParameters;
  static const c::Field<K> f[] = {
      c::number<&K::gap>("gap", "m", c::non_negative(),
                         "clear transverse gap between the deck's side and each key at rest"),
      c::number<&K::restitution>("restitution", "-", c::closed(0, 1),
                                 "Newton's coefficient e of the key contacts"),
      c::number<&K::friction>("friction", "-", c::non_negative(),
                              "Coulomb's coefficient mu of the key contacts"),
      c::number<&K::capacity>("capacity", "kN", c::non_negative(),
                              "mean contact force of a step that breaks a key; 0: unbreakable"),
  };
  return f;
}

std::span<const c::Field<BridgeDesign>> bridge_damping_fields() {
  using P = BridgeDesign;
  static const c::Field<P> f[] = {
      c::number<&P::damping_ratio_i>("ratio_i", "-", c::closed_open(0, 1),
                                     "Rayleigh ratio of mode_i (paper: 8 %)"),
      c::number<&P::damping_ratio_j>("ratio_j", "-", c::closed_open(0, 1),
                                     "Rayleigh ratio of mode_j (paper: 8 %)"),
      c::integer<&P::damping_mode_i>("mode_i", c::closed(1, 3), "1-based mode of ratio_i"),
      c::integer<&P::damping_mode_j>("mode_j", c::closed(1, 3),
                                     "1-based mode of ratio_j; differs from mode_i"),
  };
  return f;
}

std::span<const c::Field<BridgeDesign>> bridge_seat_fields() {
  using P = BridgeDesign;
  static const c::Field<P> f[] = {
      c::number<&P::restitution>("restitution", "-", c::closed(0, 1),
                                 "all four deck-corner contacts (paper: 0)"),
      c::number<&P::friction>("friction", "-", c::non_negative(),
                              "all four deck-corner contacts (paper: 0.5)"),
  };
  return f;
}

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
      c::number<&S::rotation_scale>("rotation_scale", "-", c::any(),
                                    "factor on the rotation records"),
      c::number<&S::rotation_unit>("rotation_unit", "rad/s^2 per file unit", c::positive(),
                                   "unit of the rotation records' values"),
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
      c::number<&S::record_unit>("record_unit", "m/s^2 per file unit", c::positive(),
                                 "unit of two-column and CSV records (.AT2 files are in g)"),
      c::number<&S::target_pga>("target_pga", "g", c::non_negative(),
                                "PGA of the transverse record (or of the longitudinal one when "
                                "it is alone); without longitudinal_pga the other component "
                                "takes the same factor; 0 keeps the recorded amplitude"),
      c::number<&S::longitudinal_pga>("longitudinal_pga", "g", c::non_negative(),
                                      "PGA of the longitudinal record on its own (needs "
                                      "longitudinal_record); 0: the factor of target_pga"),
      c::number<&S::scale>("scale", "-", c::any(), "an extra factor on both components"),
      c::number<&S::time_scale>("time_scale", "-", c::positive(),
                                "t → time_scale · t (0.5 for the 1/4-scale similitude)"),
      c::boolean<&S::baseline_correction>("baseline_correction",
                                          "remove the drift of velocity and displacement"),
      c::choice<&kScaleToNames, &S::scale_to>(
          "scale_to", "what target_pga / target_sa set: \"pga\" the peak ground acceleration, "
                      "\"sa\" the pseudo-spectral acceleration PSA(sa_period, sa_damping)"),
      c::number<&S::target_sa>("target_sa", "g", c::non_negative(),
                               "scale_to = \"sa\": PSA of the transverse record (or of the "
                               "longitudinal one when it is alone); without longitudinal_pga "
                               "or longitudinal_sa the other component takes the same factor; "
                               "0 keeps the recorded amplitude"),
      c::number<&S::longitudinal_sa>("longitudinal_sa", "g", c::non_negative(),
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

std::span<const c::Field<LayoutSettings>> LayoutSettings::fields() {
  using S = LayoutSettings;
  static const c::Field<S> f[] = {
      c::number<&S::skew_deg>("skew_deg", "deg", c::open(-80, 80),
                              "skew angle α of every end face and abutment face"),
  };
  return f;
}

std::span<const c::Field<parts::RigidBody>> segment_fields() {
  using P = parts::RigidBody;
  static const c::Field<P> f[] = {
      c::number<&P::mass>("mass", "t", c::positive(), "mass of the body (required)"),
      c::number<&P::inertia>("inertia", "t m^2", c::positive(),
                             "rotational inertia about its centre (required)"),
      c::number<&P::length>("length", "m", c::positive(), "L along the axis (required)"),
      c::number<&P::width>("width", "m", c::positive(),
                           "W (required); every body of a scene has the same width"),
      c::vector3<&P::initial_position>("initial_position", "m, m, rad",
                                       "(x, y, θ) at t = 0 from the rest layout; no corner "
                                       "may penetrate"),
      c::vector3<&P::initial_velocity>("initial_velocity", "m/s, m/s, rad/s", "(vx, vy, ω)"),
  };
  return f;
}

std::span<const c::Field<DeckChain::Joint>> joint_fields() {
  using P = DeckChain::Joint;
  static const c::Field<P> f[] = {
      c::number<&P::gap>("gap", "m", c::non_negative(),
                         "clear distance along the axis between the two faces at rest"),
      c::number<&P::restitution>("restitution", "-", c::closed(0, 1),
                                 "Newton's ε_N of the joint's two corner contacts"),
      c::number<&P::friction>("friction", "-", c::non_negative(),
                              "Coulomb's μ of the joint's two corner contacts"),
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

}  // namespace nsb::models
