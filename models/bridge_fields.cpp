// The keys of the bridge's deck, gaps, damping and seats and of a deck body: key, unit, range
// and meaning, declared once (models/bridge_fields.hpp).
#include "models/bridge_fields.hpp"

namespace nsb::models {

std::span<const config::Field<BridgeDesign>> bridge_deck_fields() {
  namespace c = config;
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
      c::number<&P::deck, &D::radius>("radius", "m", c::non_negative(),
                                      "R of a horizontally curved deck's centreline (length: "
                                      "its arc length; radial ends, docs/bridge.md); 0: "
                                      "straight"),
      c::vector3<&P::initial_position>("initial_position", "m, m, rad",
                                       "absolute (x, y, θ) at t = 0; no corner may penetrate"),
      c::vector3<&P::initial_velocity>("initial_velocity", "m/s, m/s, rad/s", "(vx, vy, ω)"),
  };
  return f;
}

std::span<const config::Field<BridgeDesign>> bridge_gap_fields() {
  namespace c = config;
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

std::span<const config::Field<BridgeDesign>> bridge_damping_fields() {
  namespace c = config;
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

std::span<const config::Field<BridgeDesign>> bridge_seat_fields() {
  namespace c = config;
  using P = BridgeDesign;
  static const c::Field<P> f[] = {
      c::number<&P::restitution>("restitution", "-", c::closed(0, 1),
                                 "all four deck-corner contacts (paper: 0)"),
      c::number<&P::friction>("friction", "-", c::non_negative(),
                              "all four deck-corner contacts (paper: 0.5)"),
      c::number<&P::compliance_stiffness>("compliance_stiffness", "kN/m^1.5", c::non_negative(),
                                          "Hertz k of eq. (9) for the four deck-corner contacts "
                                          "under the compliance method; 0: the default, "
                                          "solver.contact_stiffness scaled to the deck's mass "
                                          "(solver.reference_mass)"),
  };
  return f;
}

std::span<const config::Field<BridgeDesign>> rigid_deck_fields() {
  namespace c = config;
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

std::span<const config::Field<parts::RigidBody>> segment_fields() {
  namespace c = config;
  using P = parts::RigidBody;
  static const c::Field<P> f[] = {
      c::number<&P::mass>("mass", "t", c::positive(), "mass of the body (required)"),
      c::number<&P::inertia>("inertia", "t m^2", c::positive(),
                             "rotational inertia about its centre (required)"),
      c::number<&P::length>("length", "m", c::positive(), "L along the axis (required)"),
      c::number<&P::width>("width", "m", c::positive(),
                           "W (required); neighbours may differ (each corner meets the other's finite face)"),
      c::vector3<&P::initial_position>("initial_position", "m, m, rad",
                                       "(x, y, θ) at t = 0 from the rest layout; no corner "
                                       "may penetrate"),
      c::vector3<&P::initial_velocity>("initial_velocity", "m/s, m/s, rad/s", "(vx, vy, ω)"),
  };
  return f;
}

}  // namespace nsb::models
