// The connectors of a bridge scene added to its parts (scene/connector_scene.hpp).
#include "scene/connector_scene.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace nsb::scene {

using namespace models;  // the systems and parts a scene builds

namespace {

// Anchor offset from a joint face along the axis: half the cable's excess over the gap.
double anchor_inset(const RestrainerSettings& r, double gap, const std::string& key) {
  if (!(r.length > gap)) {
    throw std::invalid_argument(key + ".length: must exceed the joint's gap (" +
                                std::to_string(gap) + " m)");
  }
  return 0.5 * (r.length - gap);
}

void add_hinge_restrainers(const BridgeConnectors& c, const std::vector<double>& gaps,
                           Assembly::Parts& parts) {
  for (std::size_t k = 0; k < c.hinge_restrainers.size() && k < gaps.size(); ++k) {
    if (!c.hinge_restrainers[k]) continue;
    const RestrainerSettings& r = *c.hinge_restrainers[k];
    const double inset =
        anchor_inset(r, gaps[k], "hinges[" + std::to_string(k) + "].restrainer");
    const double la = parts.bodies[k].length, lb = parts.bodies[k + 1].length;
    parts.restrainers.push_back({.body = static_cast<int>(k),
                                 .anchor = Eigen::Vector2d(0.5 * la - inset, 0.0),
                                 .other = parts::Obstacle::kBody,
                                 .other_index = static_cast<int>(k + 1),
                                 .other_anchor = Eigen::Vector2d(-0.5 * lb + inset, 0.0),
                                 .cable = r.cable});
  }
}

// The backwall body of abutment a (0 left, 1 right) on its backfill, pile and ties; the
// deck-corner contacts of that end move from the prescribed seat to its face.
int add_backfill_seat(const AbutmentSettings& s, const BridgeDesign& p, std::size_t a,
                      const std::array<parts::Motion, 2>& ground, Assembly::Parts& parts) {
  const double side = a == 0 ? -1.0 : 1.0;  // the backfill lies beyond the wall on this side
  const double w = s.width > 0 ? s.width : p.deck.width;
  const double t = s.thickness;
  parts::RigidBody wall{.mass = s.mass, .inertia = s.mass * (w * w + t * t) / 12.0,
                        .length = t, .width = w, .skew_deg = p.deck.skew_deg};
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

// One cable per abutment from the deck end (body 0, or the last deck body) to its seat:
// the prescribed seat or the backwall body seat_body[a] (>= 0).
void add_abutment_restrainers(const RestrainerSettings& r, const BridgeDesign& p,
                              std::size_t deck_bodies, const std::array<int, 2>& seat_body,
                              Assembly::Parts& parts) {
  const double gaps[2] = {p.deck.gap_left, p.deck.gap_right};
  for (std::size_t a = 0; a < 2; ++a) {
    const double side = a == 0 ? -1.0 : 1.0;
    const double inset = anchor_inset(r, gaps[a], "abutments.restrainer");
    const std::size_t deck = a == 0 ? 0 : deck_bodies - 1;
    parts::Restrainer cable{.body = static_cast<int>(deck), .cable = r.cable};
    cable.anchor = Eigen::Vector2d(side * (0.5 * parts.bodies[deck].length - inset), 0.0);
    if (seat_body[a] >= 0) {
      // The backwall's face towards the deck is at -side t/2 in its frame.
      const double t = parts.bodies[static_cast<std::size_t>(seat_body[a])].length;
      cable.other = parts::Obstacle::kBody;
      cable.other_index = seat_body[a];
      cable.other_anchor = Eigen::Vector2d(-side * 0.5 * t + side * inset, 0.0);
    } else {
      // The prescribed seat's frame origin is its face point.
      cable.other = parts::Obstacle::kPrescribed;
      cable.other_index = static_cast<int>(a);
      cable.other_anchor = Eigen::Vector2d(side * inset, 0.0);
    }
    parts.restrainers.push_back(cable);
  }
}

}  // namespace

void add_connectors(const BridgeConnectors& c, const BridgeDesign& p,
                    const std::vector<double>& hinge_gaps,
                    const std::array<parts::Motion, 2>& ground, Assembly::Parts& parts) {
  const std::size_t deck_bodies = parts.bodies.size();
  add_hinge_restrainers(c, hinge_gaps, parts);
  for (const auto& b : c.bearings) {
    const auto law = b.yield_force > 0
                         ? connectors::LawParameters::bilinear(b.stiffness, b.yield_force,
                                                               b.post_yield_ratio)
                         : connectors::LawParameters::linear(b.stiffness);
    parts.links.push_back({.body = b.segment, .position = b.position, .longitudinal = law,
                           .transverse = law, .ground_longitudinal = ground[0],
                           .ground_transverse = ground[1]});
  }
  std::array<int, 2> seat_body{-1, -1};
  if (c.abutments && c.abutments->seat == SeatKind::kBackfill) {
    for (std::size_t a = 0; a < 2; ++a) {
      seat_body[a] = add_backfill_seat(*c.abutments, p, a, ground, parts);
    }
  }
  if (c.abutment_restrainer) {
    add_abutment_restrainers(*c.abutment_restrainer, p, deck_bodies, seat_body, parts);
  }
}

}  // namespace nsb::scene
