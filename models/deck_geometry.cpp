#include "models/deck_geometry.hpp"
#include "models/field_checks.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace nsb::models {

namespace {

double radians(double deg) { return deg * std::numbers::pi / 180.0; }

}  // namespace

void DeckGeometry::validate(const std::string& prefix) const {
  require(std::isfinite(length) && length > 0, prefix + "length", "must be > 0 [m]");
  require(std::isfinite(width) && width > 0, prefix + "width", "must be > 0 [m]");
  // Beyond 80 degrees the corners run off to infinity (tan alpha) and the model is meaningless.
  require(std::isfinite(skew_deg) && std::abs(skew_deg) < 80.0, prefix + "skew_deg",
          "must be in (-80, 80) [deg]");
  require(std::isfinite(gap_right) && gap_right >= 0, prefix + "gap_right", "must be >= 0 [m]");
  require(std::isfinite(gap_left) && gap_left >= 0, prefix + "gap_left", "must be >= 0 [m]");
}

Eigen::Vector2d DeckGeometry::corner(int contact) const {
  if (contact < 0 || contact > 3) {
    throw std::invalid_argument("DeckGeometry::corner: contact must be 0, 1, 2 or 3");
  }
  const double ta = std::tan(radians(skew_deg));
  const double end = abutment_of(contact) == 0 ? -1.0 : 1.0;  // left, right
  const double side = contact % 2 == 0 ? 1.0 : -1.0;          // +W/2, -W/2
  const double yb = side * 0.5 * width;
  // End line x_b = +-L/2 + y_b tan(alpha).
  return {end * 0.5 * length + yb * ta, yb};
}

Eigen::Vector2d DeckGeometry::face_normal(int contact) const {
  const double alpha = radians(skew_deg);
  // The faces run along (sin a, cos a); their normals point from each abutment to the deck.
  const Eigen::Vector2d n_left(std::cos(alpha), -std::sin(alpha));
  return abutment_of(contact) == 0 ? n_left : Eigen::Vector2d(-n_left);
}

std::array<Eigen::Vector2d, 2> DeckGeometry::face_points() const {
  return {Eigen::Vector2d(-0.5 * length - gap_left, 0.0),
          Eigen::Vector2d(0.5 * length + gap_right, 0.0)};
}

std::array<CornerFace, 4> DeckGeometry::corner_faces() const {
  std::array<CornerFace, 4> c;
  for (int i = 0; i < 4; ++i) {
    auto& ci = c[static_cast<std::size_t>(i)];
    ci.body_point = corner(i);
    ci.face_point = Eigen::Vector2d::Zero();  // abutment-frame origin
    ci.face_normal = face_normal(i);
  }
  return c;
}

}  // namespace nsb::models
