// The deck's plan geometry, one type for every model of the deck: the bridge and the free
// rigid deck (models/bridge_design.hpp), the segments of a bridge in parts (models/parts.hpp)
// and the closed-form impact and rotation-criterion references (models/analytic.hpp,
// models/criterion.hpp).
//
// Geometry (docs/bridge.md): deck centre (x, y), rotation theta (counter-clockwise), axis along
// global x at theta = 0; length L along the axis, width W across it.
//
// A straight deck: each end face its own skew angle, alpha_l at the left end and alpha_r at
// the right end (both alpha = skew_deg unless skew_left_deg / skew_right_deg say otherwise).
// Measured from the midpoint of the axis, the end faces are the lines
// x_b = -L/2 + y_b tan(alpha_l) and x_b = +L/2 + y_b tan(alpha_r), so the corners are
// (-+L/2 + (+-W/2) tan(alpha_l,r), +-W/2). The plan is a trapezoid whose centroid lies at
// (xbar, ybar) = (W^2 (tan^2 alpha_r - tan^2 alpha_l) / (24 L), W^2 (tan alpha_r - tan alpha_l)
// / (12 L)) from the midpoint (0 for equal angles: the parallelogram); the body frame's origin
// is the centroid, the deck's centre of mass (docs/bridge.md, "Faces with their own angles").
//
// A horizontally curved deck (radius R > 0): the plan is the annular sector of centreline
// radius R, width W (radii R -+ W/2) and subtended angle phi = L / R, L the centreline's arc
// length; its ends are radial. Its centre of curvature lies on the -y side; a point at polar
// angle psi (from the sector's axis of symmetry, positive towards +x) and radius rho is at
// (rho sin psi, rho cos psi - rbar) in the body frame, whose origin is the centroid at the
// distance rbar from the centre of curvature (annular_sector()). The ends are at psi = -+phi/2:
// a radial end face has the normal of a straight end of skew -+phi/2, so end_skew_deg() is
// -phi/2 (left) and +phi/2 (right) and face_normal() serves both kinds.
//
// Contacts (paper, Figure 2), 0-based index i here:
//   i = 0: left end, y_b = +W/2 (curved: outer radius);  i = 1: left end, y_b = -W/2;
//   i = 2: right end, y_b = +W/2;                        i = 3: right end, y_b = -W/2.
// The face normal n points from the abutment towards the deck: n = (cos a, -sin a) at the
// left end, (-cos a, sin a) at the right end, a that end's angle; the tangent is n rotated
// +90 degrees.
// gap_right / gap_left: clear distance along the deck axis at x = y = theta = 0 (the normal
// gap is gap cos(alpha)); of a curved deck, along the centreline's tangent at that end (the
// face's normal, so the normal gap itself).
//
// Units: m, deg.
#pragma once

#include "models/contact_geometry.hpp"

#include <Eigen/Dense>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace nsb::models {

// The plan of an annular sector of centreline radius R, width W (radii R -+ W/2) and
// subtended angle phi, as closed forms (docs/bridge.md, "Curved decks"):
//   area A = phi R W,
//   centroid at rbar = 4 sin(phi/2) (Ro^3 - Ri^3) / (3 phi (Ro^2 - Ri^2)) from the centre of
//     curvature, on the axis of symmetry,
//   polar moment about the centre of curvature per unit mass (Ro^2 + Ri^2) / 2, so about the
//     centroid (parallel axes) I_G / m = (Ro^2 + Ri^2) / 2 - rbar^2.
struct AnnularSector {
  double area = 0.0;               // [m^2]
  double centroid_radius = 0.0;    // rbar [m]
  double inertia_per_mass = 0.0;   // I_G / m [m^2]
};
// R > W/2 > 0, phi in (0, 2 pi]; throws std::invalid_argument otherwise.
AnnularSector annular_sector(double radius, double width, double angle_rad);

struct DeckGeometry {
  double length = 0.0;     // L [m], > 0: along the axis; curved: the centreline's arc length
  double width = 0.0;      // W [m], > 0
  double skew_deg = 0.0;   // alpha of every end face [deg], |alpha| < 80; curved: 0
  double gap_right = 0.0;  // clear gap along the axis at the right end [m], >= 0
  double gap_left = 0.0;   // clear gap along the axis at the left end [m], >= 0
  // The left (right) end's own angle [deg], |alpha| < 80; none: skew_deg. Straight decks only.
  std::optional<double> skew_left_deg{};
  std::optional<double> skew_right_deg{};
  // R of a horizontally curved deck's centreline [m], > W/2; 0: straight. phi = L / R in
  // [0.001 rad, 180 degrees).
  double radius = 0.0;

  // Throws std::invalid_argument naming the field (prefix is prepended to the field name).
  void validate(const std::string& prefix = "") const;
  bool curved() const { return radius > 0.0; }
  // phi = L / R [rad] of a curved deck; 0 when straight.
  double subtended_angle() const { return curved() ? length / radius : 0.0; }
  // The angle of end 0 (left) or 1 (right) [deg]: its skew, or -+phi/2 of a curved deck.
  double end_skew_deg(int end) const;
  // Corner of contact i (0..3) in the deck frame (theta = 0) [m].
  Eigen::Vector2d corner(int contact) const;
  // Face normal of contact i (0..3), from its abutment towards the deck, at rest.
  Eigen::Vector2d face_normal(int contact) const;
  // The point of end 0 (left) or 1 (right) on the axis (centreline), in the deck frame [m].
  Eigen::Vector2d end_point(int end) const;
  // The deck frame's coordinates of the axis's midpoint (straight) or mid-arc point (curved),
  // from which bent positions are measured: (-xbar, -ybar) or (0, R - rbar) [m].
  Eigen::Vector2d axis_centre() const;
  // Corner-face pairs for contacts 0..3. Each face point is the origin of its abutment
  // frame: the abutment pose is (reference_face_point, 0) plus the abutment motion.
  std::array<CornerFace, 4> corner_faces() const;
  // Reference position (at rest) of the left (0) and right (1) face point on the deck axis.
  std::array<Eigen::Vector2d, 2> face_points() const;
  // Abutment (0 = left, 1 = right) of contact i (0-based).
  static int abutment_of(int contact) { return contact < 2 ? 0 : 1; }

  // A bent at position s along the axis (arc length from the axis centre when curved) with
  // its columns at the transverse offsets e_c from the axis and its own skew beta from the
  // normal of the axis (radial when curved), as models/parts.hpp's Bent takes it: the line
  // of the columns crosses the deck frame's x axis at `position`, at the angle `skew_deg`
  // from the y axis, and the columns lie on it at y = `column_offsets`. rest_rotation: the
  // deck frame's rotation at rest [rad] (a frame of a curved deck), which turns the line.
  struct BentSite {
    double position = 0.0;
    std::vector<double> column_offsets;
    double skew_deg = 0.0;
  };
  BentSite bent_site(double position, const std::vector<double>& column_offsets,
                     double skew_deg, double rest_rotation = 0.0) const;
};

}  // namespace nsb::models
