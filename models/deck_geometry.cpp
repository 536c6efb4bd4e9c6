#include "models/deck_geometry.hpp"
#include "models/field_checks.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

namespace nsb::models {

namespace {

double radians(double deg) { return deg * std::numbers::pi / 180.0; }
double degrees(double rad) { return rad * 180.0 / std::numbers::pi; }

// The centroid's offset from the axis's midpoint of a straight deck whose end angles differ
// (docs/bridge.md, "Faces with their own angles"): over the trapezoid
// -L/2 + y tan(a_l) <= x <= L/2 + y tan(a_r), |y| <= W/2, of area L W,
//   xbar = (1 / (L W)) int (tan^2 a_r - tan^2 a_l) y^2 / 2 dy = W^2 (tan^2 a_r - tan^2 a_l) / (24 L),
//   ybar = (1 / (L W)) int (tan a_r - tan a_l) y^2 dy       = W^2 (tan a_r - tan a_l) / (12 L).
// Equal angles give exactly 0 (the parallelogram), and no arithmetic is done then.
Eigen::Vector2d centroid_offset(const DeckGeometry& g) {
  const double al = g.end_skew_deg(0), ar = g.end_skew_deg(1);
  if (al == ar) return Eigen::Vector2d::Zero();
  const double tl = std::tan(radians(al)), tr = std::tan(radians(ar));
  const double w2 = g.width * g.width;
  return {w2 * (tr * tr - tl * tl) / (24.0 * g.length), w2 * (tr - tl) / (12.0 * g.length)};
}

}  // namespace

AnnularSector annular_sector(double radius, double width, double angle_rad) {
  require(std::isfinite(width) && width > 0, "width", "must be > 0 [m]");
  require(std::isfinite(radius) && radius > 0.5 * width, "radius",
          "must exceed half the width, R > W/2 [m]");
  require(std::isfinite(angle_rad) && angle_rad > 0 && angle_rad <= 2.0 * std::numbers::pi,
          "angle", "must be in (0, 360] degrees");
  const double ro = radius + 0.5 * width, ri = radius - 0.5 * width;
  AnnularSector s;
  s.area = angle_rad * radius * width;
  s.centroid_radius = 4.0 * std::sin(0.5 * angle_rad) * (ro * ro * ro - ri * ri * ri) /
                      (3.0 * angle_rad * (ro * ro - ri * ri));
  s.inertia_per_mass = 0.5 * (ro * ro + ri * ri) - s.centroid_radius * s.centroid_radius;
  return s;
}

void DeckGeometry::validate(const std::string& prefix) const {
  require(std::isfinite(length) && length > 0, prefix + "length", "must be > 0 [m]");
  require(std::isfinite(width) && width > 0, prefix + "width", "must be > 0 [m]");
  // Beyond 80 degrees the corners run off to infinity (tan alpha) and the model is meaningless.
  require(std::isfinite(skew_deg) && std::abs(skew_deg) < 80.0, prefix + "skew_deg",
          "must be in (-80, 80) [deg]");
  for (const auto& [angle, key] : {std::pair{skew_left_deg, "skew_left_deg"},
                                   std::pair{skew_right_deg, "skew_right_deg"}}) {
    if (angle) {
      require(std::isfinite(*angle) && std::abs(*angle) < 80.0, prefix + key,
              "must be in (-80, 80) [deg]");
    }
  }
  require(std::isfinite(gap_right) && gap_right >= 0, prefix + "gap_right", "must be >= 0 [m]");
  require(std::isfinite(gap_left) && gap_left >= 0, prefix + "gap_left", "must be >= 0 [m]");
  require(std::isfinite(radius) && radius >= 0, prefix + "radius",
          "must be >= 0 [m] (0: a straight deck)");
  if (curved()) {
    require(radius > 0.5 * width, prefix + "radius", "must exceed half the width, R > W/2 [m]");
    // The arc of length L on the radius R subtends L / R; from 180 degrees on the sector
    // overlaps itself, so the radius cannot hold the deck.
    if (subtended_angle() >= std::numbers::pi) {
      char text[200];
      std::snprintf(text, sizeof text,
                    "R = %.6g m cannot hold an arc of L = %.6g m: it would subtend %.6g deg, "
                    "180 or more (L / R >= pi); R > L / pi = %.6g m",
                    radius, length, subtended_angle() * 180.0 / std::numbers::pi,
                    length / std::numbers::pi);
      require(false, prefix + "radius", text);
    }
    // Below 1e-3 rad the sector's inertia about its centroid, (Ro^2 + Ri^2)/2 - rbar^2, is a
    // difference of numbers ~R^2 that cancel to ~L^2/12 and loses its digits; such a deck is
    // straight for every purpose.
    require(subtended_angle() >= 1e-3, prefix + "radius",
            "gives a subtended angle L / R below 0.001 rad (0.057 deg): give radius = 0, a "
            "straight deck");
    require(skew_deg == 0.0 && !skew_left_deg && !skew_right_deg, prefix + "skew_deg",
            "must be 0: a curved deck's end faces are radial");
  }
}

double DeckGeometry::end_skew_deg(int end) const {
  if (curved()) return (end == 0 ? -0.5 : 0.5) * degrees(subtended_angle());
  const std::optional<double>& own = end == 0 ? skew_left_deg : skew_right_deg;
  return own ? *own : skew_deg;
}

Eigen::Vector2d DeckGeometry::corner(int contact) const {
  if (contact < 0 || contact > 3) {
    throw std::invalid_argument("DeckGeometry::corner: contact must be 0, 1, 2 or 3");
  }
  const int a = abutment_of(contact);
  const double end = a == 0 ? -1.0 : 1.0;              // left, right
  const double side = contact % 2 == 0 ? 1.0 : -1.0;  // +W/2, -W/2
  const double yb = side * 0.5 * width;
  if (curved()) {
    // The corner at radius R + y_b on the radial end at psi = -+phi/2.
    const double psi = end * 0.5 * subtended_angle();
    const double rho = radius + yb;
    const double rbar = annular_sector(radius, width, subtended_angle()).centroid_radius;
    return {rho * std::sin(psi), rho * std::cos(psi) - rbar};
  }
  const double ta = std::tan(radians(end_skew_deg(a)));
  // End line x_b = +-L/2 + y_b tan(alpha), from the axis's midpoint.
  Eigen::Vector2d p(end * 0.5 * length + yb * ta, yb);
  if (const Eigen::Vector2d c = centroid_offset(*this); !c.isZero(0.0)) p -= c;
  return p;
}

Eigen::Vector2d DeckGeometry::face_normal(int contact) const {
  const double alpha = radians(end_skew_deg(abutment_of(contact)));
  // The faces run along (sin a, cos a); their normals point from each abutment to the deck.
  const Eigen::Vector2d n_left(std::cos(alpha), -std::sin(alpha));
  return abutment_of(contact) == 0 ? n_left : Eigen::Vector2d(-n_left);
}

Eigen::Vector2d DeckGeometry::end_point(int end) const {
  const double sign = end == 0 ? -1.0 : 1.0;
  if (curved()) {
    const double psi = sign * 0.5 * subtended_angle();
    const double rbar = annular_sector(radius, width, subtended_angle()).centroid_radius;
    return {radius * std::sin(psi), radius * std::cos(psi) - rbar};
  }
  Eigen::Vector2d p(sign * 0.5 * length, 0.0);
  if (const Eigen::Vector2d c = centroid_offset(*this); !c.isZero(0.0)) p -= c;
  return p;
}

Eigen::Vector2d DeckGeometry::axis_centre() const {
  if (curved()) {
    return {0.0, radius - annular_sector(radius, width, subtended_angle()).centroid_radius};
  }
  return -centroid_offset(*this);
}

std::array<Eigen::Vector2d, 2> DeckGeometry::face_points() const {
  if (curved()) {
    // Each abutment face point lies its gap beyond the end, along the centreline's outward
    // tangent there, end * (cos psi, -sin psi).
    std::array<Eigen::Vector2d, 2> f;
    for (int e = 0; e < 2; ++e) {
      const double sign = e == 0 ? -1.0 : 1.0;
      const double psi = sign * 0.5 * subtended_angle();
      const double gap = e == 0 ? gap_left : gap_right;
      f[static_cast<std::size_t>(e)] =
          end_point(e) + sign * gap * Eigen::Vector2d(std::cos(psi), -std::sin(psi));
    }
    return f;
  }
  std::array<Eigen::Vector2d, 2> f{Eigen::Vector2d(-0.5 * length - gap_left, 0.0),
                                   Eigen::Vector2d(0.5 * length + gap_right, 0.0)};
  if (const Eigen::Vector2d c = centroid_offset(*this); !c.isZero(0.0)) {
    for (auto& p : f) p -= c;
  }
  return f;
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

DeckGeometry::BentSite DeckGeometry::bent_site(double position,
                                               const std::vector<double>& column_offsets,
                                               double skew_deg_of_bent,
                                               double rest_rotation) const {
  const Eigen::Vector2d centre = axis_centre();
  if (!curved() && rest_rotation == 0.0 && centre.isZero(0.0)) {
    // A parallelogram: the bent's line already has the parts' form.
    return {position, column_offsets, skew_deg_of_bent};
  }
  // The bent's line: through the axis point A at the angle gamma from the deck frame's y axis
  // (straight: beta; curved: psi + beta, psi = s / R the radial direction); its columns at
  // A + (e_c / cos beta) (sin gamma, cos gamma), so that e_c is the offset along the normal of
  // the axis (radially when curved) as for a straight bent.
  const double beta = radians(skew_deg_of_bent);
  Eigen::Vector2d a;
  double gamma = beta;
  if (curved()) {
    const double psi = position / radius;
    const double rbar = annular_sector(radius, width, subtended_angle()).centroid_radius;
    a = Eigen::Vector2d(radius * std::sin(psi), radius * std::cos(psi) - rbar);
    gamma = psi + beta;
  } else {
    a = centre + Eigen::Vector2d(position, 0.0);
  }
  // Turned by the rest rotation: the bent's kinematics (models/parts.hpp, Bent) take its
  // points and directions in axes parallel to the global ones.
  const Eigen::Rotation2Dd turn(rest_rotation);
  a = turn * a;
  Eigen::Vector2d d = turn * Eigen::Vector2d(std::sin(gamma), std::cos(gamma));
  if (d.y() < 0) d = -d;
  const std::vector<double> offsets = column_offsets.empty() ? std::vector<double>{0.0}
                                                             : column_offsets;
  BentSite b;
  b.skew_deg = degrees(std::atan2(d.x(), d.y()));
  b.position = a.x() - a.y() * d.x() / d.y();  // where the line crosses y = 0
  const double sign = (turn * Eigen::Vector2d(std::sin(gamma), std::cos(gamma))).y() < 0 ? -1.0
                                                                                        : 1.0;
  for (const double e : offsets) {
    b.column_offsets.push_back(a.y() + sign * e / std::cos(beta) * d.y());
  }
  return b;
}

}  // namespace nsb::models
