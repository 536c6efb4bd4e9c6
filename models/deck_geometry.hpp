// The deck's plan geometry, one type for every model of the deck: the bridge and the free
// rigid deck (models/bridge_design.hpp) and the closed-form impact and rotation-criterion
// references (models/analytic.hpp).
//
// Geometry (docs/bridge.md): deck centre (x, y), rotation theta (counter-clockwise), axis along
// global x at theta = 0; length L along the axis, width W across it; skew angle alpha. The deck
// ends and the abutment faces are the lines x_b = +-L/2 + y_b tan(alpha), so the corners are
// (+-L/2 +- (W/2) tan(alpha), +-W/2). Contacts (paper, Figure 2), 0-based index i here:
//   i = 0: left end, y_b = +W/2;  i = 1: left end, y_b = -W/2;
//   i = 2: right end, y_b = +W/2; i = 3: right end, y_b = -W/2.
// The face normal n points from the abutment towards the deck: n = (cos a, -sin a) at the
// left end, (-cos a, sin a) at the right end; the tangent is n rotated +90 degrees.
// gap_right / gap_left: clear distance along the deck axis at x = y = theta = 0 (the normal
// gap is gap cos(alpha)).
//
// Units: m, deg.
#pragma once

#include "models/contact_geometry.hpp"

#include <Eigen/Dense>

#include <array>
#include <string>

namespace nsb::models {

struct DeckGeometry {
  double length = 0.0;     // L [m], > 0
  double width = 0.0;      // W [m], > 0
  double skew_deg = 0.0;   // alpha [deg], |alpha| < 80
  double gap_right = 0.0;  // clear gap along the axis at the right end [m], >= 0
  double gap_left = 0.0;   // clear gap along the axis at the left end [m], >= 0
  // Throws std::invalid_argument naming the field (prefix is prepended to the field name).
  void validate(const std::string& prefix = "") const;
  // Corner of contact i (0..3) in the deck frame (theta = 0) [m].
  Eigen::Vector2d corner(int contact) const;
  // Face normal of contact i (0..3), from its abutment towards the deck, at rest.
  Eigen::Vector2d face_normal(int contact) const;
  // Corner-face pairs for contacts 0..3. Each face point is the origin of its abutment
  // frame: the abutment pose is (reference_face_point, 0) plus the abutment motion.
  std::array<CornerFace, 4> corner_faces() const;
  // Reference position (at rest) of the left (0) and right (1) face point on the deck axis.
  std::array<Eigen::Vector2d, 2> face_points() const;
  // Abutment (0 = left, 1 = right) of contact i (0-based).
  static int abutment_of(int contact) { return contact < 2 ? 0 : 1; }
};

}  // namespace nsb::models
