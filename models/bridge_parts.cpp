#include "models/bridge_parts.hpp"
#include "models/field_checks.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace nsb::models {

namespace {

// The outputs' name of deck corner i (0..3, models/deck_geometry.hpp): its end and side.
std::string corner_name(int i) {
  return std::string(DeckGeometry::abutment_of(i) == 0 ? "left" : "right") +
         (i % 2 == 0 ? " +W/2" : " -W/2");
}

// The parts of p without its checks: the deck, seats, bents, damping and contacts.
Assembly::Parts deck_parts(const BridgeDesign& p) {
  const BridgeDesign::Excitation& excitation = p.excitation;
  Assembly::Parts parts;
  parts.bodies.push_back({.mass = p.mass, .inertia = p.inertia, .length = p.deck.length,
                          .width = p.deck.width, .skew_deg = p.deck.skew_deg,
                          .skew_left_deg = p.deck.skew_left_deg,
                          .skew_right_deg = p.deck.skew_right_deg, .radius = p.deck.radius,
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
    // The bent's line on the deck's plan (a curved deck's bents stand along its arc).
    const DeckGeometry::BentSite site = p.deck.bent_site(
        p.bents[j].position, p.bents[j].column_offsets, p.bents[j].skew_deg);
    parts::Bent b{.body = 0, .position = site.position,
                  .longitudinal = p.bents[j].longitudinal, .transverse = p.bents[j].transverse,
                  .ground_longitudinal = nullptr, .ground_transverse = nullptr,
                  .column_offsets = site.column_offsets, .skew_deg = site.skew_deg};
    if (!excitation.bents.empty()) {
      b.ground_longitudinal = excitation.bents[j].longitudinal;
      b.ground_transverse = excitation.bents[j].transverse;
    }
    parts.bents.push_back(b);
  }
  // Rayleigh damping needs the bents' stiffness K0; a free deck has none.
  if (!p.bents.empty()) {
    parts.damping = parts::RayleighParts{.ratio_i = p.damping_ratio_i,
                                         .ratio_j = p.damping_ratio_j,
                                         .mode_i = p.damping_mode_i, .mode_j = p.damping_mode_j};
  }
  const auto corners = p.deck.corner_faces();
  for (int i = 0; i < 4; ++i) {
    const auto& c = corners[static_cast<std::size_t>(i)];
    parts.contacts.push_back({.body = 0, .corner = i, .obstacle = parts::Obstacle::kPrescribed,
                              .obstacle_index = DeckGeometry::abutment_of(i),
                              .face = {.point = c.face_point, .normal = c.face_normal},
                              .restitution = p.restitution, .friction = p.friction,
                              .stiffness = p.compliance_stiffness,
                              .family = "abutment", .name = corner_name(i)});
  }
  return parts;
}

}  // namespace

Assembly::Parts bridge_parts(const BridgeDesign& p) {
  p.validate();
  return deck_parts(p);
}

namespace {

// The plan of a segment (its gaps play no part here).
DeckGeometry segment_plan(const parts::RigidBody& b) {
  return {.length = b.length, .width = b.width, .skew_deg = b.skew_deg, .gap_right = 0.0,
          .gap_left = 0.0, .skew_left_deg = b.skew_left_deg, .skew_right_deg = b.skew_right_deg,
          .radius = b.radius};
}

double total_length(const SegmentedDeck& d) {
  double l = 0.0;
  for (std::size_t i = 0; i < d.segments.size(); ++i) {
    l += d.segments[i].length + (i == 0 ? 0.0 : d.hinges[i - 1].gap);
  }
  return l;
}

}  // namespace

double SegmentedDeck::rest_position(std::size_t i) const {
  double x = -0.5 * total_length(*this);  // the left end of segment 0
  for (std::size_t k = 0; k < i; ++k) x += segments[k].length + hinges[k].gap;
  return x + 0.5 * segments[i].length;
}

double SegmentedDeck::hinge_skew_deg(std::size_t k, const DeckGeometry& deck) const {
  return k < hinge_skews_deg.size() && hinge_skews_deg[k] ? *hinge_skews_deg[k] : deck.skew_deg;
}

void SegmentedDeck::validate(const std::vector<BridgeDesign::Bent>& bents) const {
  require(!segments.empty(), "segments", "at least one segment is needed");
  require(hinges.size() + 1 == segments.size(), "hinges",
          "one fewer than the segments (hinge k joins segments k and k + 1)");
  require(hinge_skews_deg.empty() || hinge_skews_deg.size() == hinges.size(), "hinge_skews_deg",
          "none, or one (or none) per hinge");
  for (std::size_t k = 0; k < hinge_skews_deg.size(); ++k) {
    if (!hinge_skews_deg[k]) continue;
    require(std::isfinite(*hinge_skews_deg[k]) && std::abs(*hinge_skews_deg[k]) < 80.0,
            "hinges[" + std::to_string(k) + "].skew_deg", "must be in (-80, 80) [deg]");
  }
  for (const auto& s : segments) {
    require(s.radius == 0.0, "segments", "a curved deck is one [model.deck]; segments are straight");
  }
  require(bent_segment.size() == bents.size(), "bent_segment", "one segment index per bent");
  for (std::size_t j = 0; j < bent_segment.size(); ++j) {
    const std::string field = "bent_segment[" + std::to_string(j) + "]";
    require(bent_segment[j] >= 0 && static_cast<std::size_t>(bent_segment[j]) < segments.size(),
            field, "must name one of the segments");
    const double half = 0.5 * segments[static_cast<std::size_t>(bent_segment[j])].length;
    require(std::abs(bents[j].position) <= half, "bents[" + std::to_string(j) + "].position",
            "must lie on its segment, |s| <= length / 2 [m]");
  }
  for (std::size_t i = 0; i < segments.size(); ++i) {
    require(torsionally_restrained(bents, bent_segment, static_cast<int>(i)),
            "segments[" + std::to_string(i) + "]", kTwoBents);
  }
}

bool torsionally_restrained(const std::vector<BridgeDesign::Bent>& bents,
                            const std::vector<int>& bent_segment, int segment) {
  const double* first = nullptr;
  for (std::size_t j = 0; j < bents.size() && j < bent_segment.size(); ++j) {
    if (bent_segment[j] != segment) continue;
    if (first == nullptr) {
      first = &bents[j].position;
    } else if (bents[j].position != *first) {
      return true;
    }
  }
  return false;
}

Assembly::Parts bridge_parts(const BridgeDesign& p, const SegmentedDeck& deck) {
  deck.validate(p.bents);
  BridgeDesign one = p;  // the one-segment design gives seats, bents and damping
  one.mass = deck.segments[0].mass;
  one.inertia = deck.segments[0].inertia;
  one.deck.length = total_length(deck);
  one.deck.width = deck.segments[0].width;
  // The segments carry their own initial states (checked by RigidBody::validate and, for
  // penetration, by the assembly at each segment's pose).
  one.initial_position.setZero();
  one.initial_velocity.setZero();
  one.validate();
  Assembly::Parts parts = deck_parts(one);
  const std::size_t n = deck.segments.size();
  // The seats' reference points from the whole deck's axis midpoint, the segments' origin
  // (deck_parts measures them from the one deck's centroid, which differs where the two
  // abutments' angles differ).
  if (const Eigen::Vector2d shift = one.deck.axis_centre(); !shift.isZero(0.0)) {
    for (auto& seat : parts.prescribed) seat.reference -= shift;
  }
  parts.bodies.clear();
  for (std::size_t i = 0; i < n; ++i) {
    parts::RigidBody b = deck.segments[i];
    // Each end face at the angle of its joint: an abutment's, or a hinge's own.
    b.skew_deg = p.deck.skew_deg;
    b.skew_left_deg = i == 0 ? p.deck.end_skew_deg(0) : deck.hinge_skew_deg(i - 1, p.deck);
    b.skew_right_deg = i + 1 == n ? p.deck.end_skew_deg(1) : deck.hinge_skew_deg(i, p.deck);
    b.rest = Eigen::Vector3d(deck.rest_position(i), 0.0, 0.0);
    // The rest centre is the segment's centroid (off the axis's midpoint when its two angles
    // differ, models/deck_geometry.hpp).
    if (const Eigen::Vector2d shift = segment_plan(b).axis_centre(); !shift.isZero(0.0)) {
      b.rest.head<2>() -= shift;
    }
    parts.bodies.push_back(b);
  }
  for (std::size_t j = 0; j < parts.bents.size(); ++j) {
    const auto body = static_cast<std::size_t>(deck.bent_segment[j]);
    const DeckGeometry::BentSite site = segment_plan(parts.bodies[body]).bent_site(
        p.bents[j].position, p.bents[j].column_offsets, p.bents[j].skew_deg);
    parts.bents[j].body = deck.bent_segment[j];
    parts.bents[j].position = site.position;
    parts.bents[j].column_offsets = site.column_offsets;
    parts.bents[j].skew_deg = site.skew_deg;
  }
  // Seat contacts 0, 1 stay on segment 0; 2, 3 go to the last segment, after the hinges.
  std::vector<parts::CornerContact> contacts(parts.contacts.begin(), parts.contacts.begin() + 2);
  for (std::size_t k = 1; k < n; ++k) {
    // Each side of the hinge: segment k's left corner on segment k - 1's right end face, or
    // segment k - 1's right corner (2, 3) on segment k's left end face (parts::CornerContact).
    const parts::Face face = parts::bounded_end_face(parts.bodies[k - 1], parts::End::kRight);
    const parts::Face partner_face = parts::bounded_end_face(parts.bodies[k], parts::End::kLeft);
    for (int corner : {0, 1}) {
      contacts.push_back({.body = static_cast<int>(k), .corner = corner,
                          .obstacle = parts::Obstacle::kBody,
                          .obstacle_index = static_cast<int>(k - 1), .face = face,
                          .restitution = deck.hinges[k - 1].restitution,
                          .friction = deck.hinges[k - 1].friction,
                          .stiffness = deck.hinges[k - 1].compliance_stiffness,
                          .family = "hinge",
                          .name = "hinge " + std::to_string(k) +
                                  (corner == 0 ? " +W/2" : " -W/2"),
                          .partner_corner = corner + 2, .partner_face = partner_face});
    }
  }
  for (std::size_t i = 2; i < 4; ++i) {
    contacts.push_back(parts.contacts[i]);
    contacts.back().body = static_cast<int>(n - 1);
  }
  parts.contacts = std::move(contacts);
  return parts;
}

LimitSpec bridge_limit_spec(const BridgeLimits& limits, std::size_t segments) {
  LimitSpec spec;
  const auto joint = [&](std::string name, std::size_t first, double seat) {
    spec.joints.push_back({.name = std::move(name),
                           .contacts = {static_cast<int>(first), static_cast<int>(first + 1)},
                           .seat_length = seat, .closure = true});
  };
  joint("left", 0, limits.abutment_seat);
  for (std::size_t k = 1; k < segments; ++k) {
    const double seat = k - 1 < limits.hinge_seats.size()
                            ? limits.hinge_seats[k - 1]
                            : std::numeric_limits<double>::infinity();
    joint("hinge_" + std::to_string(k), 2 * k, seat);
  }
  joint("right", 2 * segments, limits.abutment_seat);
  spec.bent_heights = limits.bent_heights;
  spec.drift_ratio = limits.drift_ratio;
  spec.residual_rotation = limits.residual_rotation;
  spec.deck_bodies = static_cast<int>(segments);
  return spec;
}

}  // namespace nsb::models
