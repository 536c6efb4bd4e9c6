#include "models/bridge_parts.hpp"

#include <sstream>
#include <stdexcept>

namespace nsb::models {

Assembly::Parts bridge_parts(const Bridge::Parameters& p, const Bridge::Excitation& excitation) {
  p.validate();
  if (!excitation.bents.empty() && excitation.bents.size() != p.bents.size()) {
    std::ostringstream s;
    s << "excitation.bents: " << excitation.bents.size() << " motions for " << p.bents.size()
      << " bents; give none or one per bent";
    throw std::invalid_argument(s.str());
  }
  Assembly::Parts parts;
  parts.bodies.push_back({.mass = p.mass, .inertia = p.inertia, .length = p.deck.length,
                          .width = p.deck.width, .skew_deg = p.deck.skew_deg,
                          .initial_position = p.initial_position,
                          .initial_velocity = p.initial_velocity});
  // Seat a: its frame origin is the reference face point, its face passes through it.
  const auto faces = p.deck.face_points();
  for (std::size_t a = 0; a < 2; ++a) {
    const auto& m = excitation.seats[a];
    parts.prescribed.push_back({.reference = faces[a], .longitudinal = m.longitudinal,
                                .transverse = m.transverse, .rotation = m.rotation});
  }
  for (std::size_t j = 0; j < p.bents.size(); ++j) {
    parts::Bent b{.body = 0, .position = p.bents[j].position,
                  .longitudinal = p.bents[j].longitudinal, .transverse = p.bents[j].transverse,
                  .ground_longitudinal = nullptr, .ground_transverse = nullptr};
    if (!excitation.bents.empty()) {
      b.ground_longitudinal = excitation.bents[j].longitudinal;
      b.ground_transverse = excitation.bents[j].transverse;
    }
    parts.bents.push_back(b);
  }
  parts.damping = parts::RayleighParts{.ratio_i = p.damping_ratio_i, .ratio_j = p.damping_ratio_j,
                                       .mode_i = p.damping_mode_i, .mode_j = p.damping_mode_j};
  const auto corners = p.deck.corner_faces();
  for (int i = 0; i < 4; ++i) {
    const auto& c = corners[static_cast<std::size_t>(i)];
    parts.contacts.push_back({.body = 0, .corner = i, .obstacle = parts::Obstacle::kPrescribed,
                              .obstacle_index = DeckGeometry::abutment_of(i),
                              .face = {.point = c.face_point, .normal = c.face_normal},
                              .restitution = p.restitution, .friction = p.friction});
  }
  return parts;
}

}  // namespace nsb::models
