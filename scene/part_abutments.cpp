// Abutments (docs/bridge.md, "Connectors"; the backfill's law: models::connectors::Law,
// hyperbolic gap): `[model.abutments]`. A prescribed seat moves with the ground (as
// [model.seats]); a backfill seat is a backwall body on the hyperbolic backfill and its piles,
// tied to the ground in y and theta, against whose face the deck's end corners then pound.
// The table also holds the abutments' restrainer (scene/part_restrainers.cpp) and their seat
// length, a limit state's (scene/bridge_limits_scene.cpp).
#include "scene/bridge_part_kinds.hpp"

#include "scene/scene_schema.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace nsb::scene {

using namespace models;  // the systems and parts a scene builds

namespace {

namespace c = config;

// What an abutment seat is.
enum class SeatKind { kPrescribed, kBackfill };
constexpr std::array<config::Name<SeatKind>, 2> kSeatKindNames{
    {{"prescribed", SeatKind::kPrescribed}, {"backfill", SeatKind::kBackfill}}};

// [model.abutments]: the seats of both abutments and their backfill. The backfill defaults
// are OpenSees HyperbolicGapMaterial's recommended values (Wilson & Elgamal's calibration of
// the UCSD large-scale backwall tests, a 1.68 m backwall, per metre of wall width).
struct AbutmentSettings {
  SeatKind seat = SeatKind::kPrescribed;
  double mass = 10.0;            // backwall + participating soil, each abutment [t]
  double thickness = 0.3;        // backwall thickness along the deck axis [m]
  double width = 0.0;            // wall width [m]; 0: the deck's width
  double stiffness_per_width = 20300.0;   // K_max [kN/m per m]
  double ultimate_force_per_width = 326.0;  // F_ult [kN per m]
  double failure_ratio = 0.7;               // R_f
  double unloading_stiffness_per_width = 20300.0;  // K_ur [kN/m per m]
  double pile_stiffness = 7000.0;  // linear x spring in parallel [kN/m]
  double tie_frequency = 20.0;     // y and theta ties' frequency on the wall's mass [Hz]
  static std::span<const config::Field<AbutmentSettings>> fields();
};

std::span<const c::Field<AbutmentSettings>> AbutmentSettings::fields() {
  using S = AbutmentSettings;
  static const c::Field<S> f[] = {
      c::choice<&kSeatKindNames, &S::seat>(
          "seat", "\"prescribed\": the seats move with the ground (as [model.seats]); "
                  "\"backfill\": each seat is a backwall body on the hyperbolic backfill"),
      c::number<&S::mass>("mass", "t", c::positive(),
                          "backfill: backwall and participating soil of one abutment"),
      c::number<&S::thickness>("thickness", "m", c::positive(),
                               "backfill: backwall thickness along the deck axis"),
      c::number<&S::width>("width", "m", c::non_negative(),
                           "backfill: wall width w; 0: the deck's width"),
      c::number<&S::stiffness_per_width>("stiffness_per_width", "kN/m per m", c::positive(),
                                         "backfill: initial stiffness K_max / w (1.68 m wall)"),
      c::number<&S::ultimate_force_per_width>("ultimate_force_per_width", "kN per m",
                                              c::positive(),
                                              "backfill: F_ult / w (1.68 m wall)"),
      c::number<&S::failure_ratio>("failure_ratio", "-", c::open_closed(0, 1),
                                   "backfill: R_f, the asymptote is F_ult / R_f"),
      c::number<&S::unloading_stiffness_per_width>(
          "unloading_stiffness_per_width", "kN/m per m", c::positive(),
          "backfill: unloading-reloading slope K_ur / w, >= stiffness_per_width"),
      c::number<&S::pile_stiffness>("pile_stiffness", "kN/m", c::positive(),
                                    "backfill: linear x spring of the wall's piles, in "
                                    "parallel with the backfill (assumed)"),
      c::number<&S::tie_frequency>("tie_frequency", "Hz", c::positive(),
                                   "backfill: the wall's y and θ ties to the ground, as "
                                   "frequencies on its mass and inertia (far above the "
                                   "bridge's)"),
  };
  return f;
}

std::any read_abutments(const Section& m, const PartShape&) {
  const toml::table* t = m.subtable("abutments");
  if (t == nullptr) return {};
  Section s(m.context(), *t, m.key_path("abutments"));
  std::vector<std::string_view> keys = keys_of(AbutmentSettings::fields());
  keys.push_back("restrainer");
  for (std::string_view k : keys_of(SeatLengthSettings::fields())) keys.push_back(k);
  for (std::string_view k : keys_of(AbutmentSkewSettings::fields())) keys.push_back(k);
  // seat_length: a limit state's (read_bridge_limits); the skews: the deck's geometry's
  // (scene/bridge_scene.cpp).
  s.only(keys);
  AbutmentSettings a;
  s.read_all(AbutmentSettings::fields(), a);
  if (a.unloading_stiffness_per_width < a.stiffness_per_width) {
    s.fail("unloading_stiffness_per_width", "must be >= stiffness_per_width (a load-unload "
                                            "cycle must not create energy)");
  }
  return a;
}

// The backwall body of abutment a (0 left, 1 right) on its backfill, pile and ties; the
// deck-corner contacts of that end move from the prescribed seat to its face.
int add_backfill_seat(const AbutmentSettings& s, const BridgeDesign& p, std::size_t a,
                      const std::array<parts::Motion, 2>& ground, Assembly::Parts& parts) {
  const double side = a == 0 ? -1.0 : 1.0;  // the backfill lies beyond the wall on this side
  // The wall's default width: the deck end it faces (of a bridge in segments, the end
  // segment's own width).
  double deck_width = p.deck.width;
  for (const auto& contact : parts.contacts) {
    if (contact.obstacle == parts::Obstacle::kPrescribed &&
        contact.obstacle_index == static_cast<int>(a)) {
      deck_width = parts.bodies[static_cast<std::size_t>(contact.body)].width;
    }
  }
  const double w = s.width > 0 ? s.width : deck_width;
  const double t = s.thickness;
  parts::RigidBody wall{.mass = s.mass, .inertia = s.mass * (w * w + t * t) / 12.0,
                        .length = t, .width = w,
                        .skew_deg = p.deck.end_skew_deg(static_cast<int>(a))};
  wall.rest = Eigen::Vector3d(parts.prescribed[a].reference.x() + side * 0.5 * t,
                              parts.prescribed[a].reference.y(), 0.0);
  const int index = static_cast<int>(parts.bodies.size());
  parts.bodies.push_back(wall);
  // Ties: each of the two y springs at s = -+t/2 is stiff enough that the wall's y and theta
  // frequencies are at least tie_frequency: k >= m w^2 / 2 and k >= 2 I w^2 / t^2.
  const double omega2 = std::pow(2.0 * std::numbers::pi * s.tie_frequency, 2);
  const double k_tie = std::max(0.5 * s.mass * omega2, 2.0 * wall.inertia * omega2 / (t * t));
  using connectors::LawParameters;
  const LawParameters backfill = LawParameters::hyperbolic_gap(
      w * s.stiffness_per_width, w * s.ultimate_force_per_width, s.failure_ratio,
      w * s.unloading_stiffness_per_width, side);
  parts.links.push_back({.body = index, .position = side * 0.5 * t, .longitudinal = backfill,
                         .transverse = LawParameters::linear(k_tie),
                         .ground_longitudinal = ground[0], .ground_transverse = ground[1]});
  parts.links.push_back({.body = index, .position = -side * 0.5 * t,
                         .longitudinal = LawParameters::linear(s.pile_stiffness),
                         .transverse = LawParameters::linear(k_tie),
                         .ground_longitudinal = ground[0], .ground_transverse = ground[1]});
  const parts::Face face = parts::end_face(wall, a == 0 ? parts::End::kRight : parts::End::kLeft);
  for (auto& contact : parts.contacts) {
    if (contact.obstacle != parts::Obstacle::kPrescribed ||
        contact.obstacle_index != static_cast<int>(a)) {
      continue;
    }
    contact.obstacle = parts::Obstacle::kBody;
    contact.obstacle_index = index;
    contact.face = face;
  }
  return index;
}

void add_abutments(const std::any& settings, PartSite& site, Assembly::Parts& parts) {
  const auto& s = std::any_cast<const AbutmentSettings&>(settings);
  if (s.seat != SeatKind::kBackfill) return;
  for (std::size_t a = 0; a < 2; ++a) {
    site.seat_body[a] = add_backfill_seat(s, site.design, a, site.ground, parts);
  }
}

// The table of docs/scenes.md, with the seat length of the limit states.
void abutment_docs(std::vector<DocTable>& out) {
  using namespace doc_tables;
  out.push_back({"model.abutments",
                 kHeader + rows(AbutmentSettings::fields(), AbutmentSettings{}) +
                     rows(SeatLengthSettings::fields(), SeatLengthSettings{},
                          {{"seat_length", "none"}}) +
                     rows(AbutmentSkewSettings::fields(), AbutmentSkewSettings{},
                          {{"skew_left_deg", "skew_deg"}, {"skew_right_deg", "skew_deg"}}),
                 joined(joined(keys(AbutmentSettings::fields()), keys(SeatLengthSettings::fields())),
                        keys(AbutmentSkewSettings::fields()))});
}

}  // namespace

BridgePartKind abutments_part() {
  return {"abutments", read_abutments, add_abutments, abutment_docs};
}

}  // namespace nsb::scene
