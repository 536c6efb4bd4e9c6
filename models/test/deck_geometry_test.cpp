// The deck's plan (models/deck_geometry.hpp): faces with their own angles and the curved
// deck, against independent constructions: the shoelace centroid of the corners' polygon,
// numerical integration over the annular sector, the radial lines through the centre of
// curvature.
#include "models/deck_geometry.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <tuple>
#include <vector>

namespace {

using nsb::models::DeckGeometry;
constexpr double kPi = std::numbers::pi;
// Closed forms against the same formulas' round-off (lengths of tens of metres).
constexpr double kRoundOff = 1e-12;

// The centroid of a simple polygon (shoelace formula).
Eigen::Vector2d polygon_centroid(const std::vector<Eigen::Vector2d>& p) {
  double a = 0.0;
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector2d& u = p[i];
    const Eigen::Vector2d& v = p[(i + 1) % p.size()];
    const double cross = u.x() * v.y() - v.x() * u.y();
    a += 0.5 * cross;
    c += (u + v) * cross / 6.0;
  }
  return c / a;
}

}  // namespace

TEST_CASE("deck geometry: one skew_deg is every face's, bit for bit") {
  // The optional end angles equal to skew_deg change no number (the same operations).
  const DeckGeometry one{.length = 33.53, .width = 2.44, .skew_deg = 30.0, .gap_right = 0.0127,
                         .gap_left = 0.01};
  DeckGeometry both = one;
  both.skew_left_deg = 30.0;
  both.skew_right_deg = 30.0;
  for (int i = 0; i < 4; ++i) {
    CHECK(one.corner(i) == both.corner(i));
    CHECK(one.face_normal(i) == both.face_normal(i));
    // The parallelogram's corners: (+-L/2 + y tan a, y), no centroid shift.
    const double y = (i % 2 == 0 ? 0.5 : -0.5) * one.width;
    CHECK(one.corner(i).x() == (i < 2 ? -0.5 : 0.5) * one.length + y * std::tan(kPi / 6.0));
  }
  CHECK(one.face_points()[0] == both.face_points()[0]);
  CHECK(one.axis_centre() == Eigen::Vector2d::Zero());
}

TEST_CASE("deck geometry: unequal end angles put the frame's origin at the centroid") {
  // Trapezoids of unequal end angles: the shoelace centroid of the four corners (counter-
  // clockwise: 1, 3, 2, 0) must be the frame's origin; the end faces keep their angles.
  for (const auto& angles : {std::pair{0.0, 30.0}, std::pair{-20.0, 45.0},
                             std::pair{50.0, 10.0}}) {
    const double left = angles.first, right = angles.second;
    CAPTURE(left);
    CAPTURE(right);
    DeckGeometry g{.length = 30.0, .width = 8.0, .skew_deg = 0.0, .gap_right = 0.02,
                   .gap_left = 0.03};
    g.skew_left_deg = left;
    g.skew_right_deg = right;
    const Eigen::Vector2d c = polygon_centroid({g.corner(1), g.corner(3), g.corner(2), g.corner(0)});
    CHECK(c.norm() < kRoundOff * g.length);
    // Each end face along (sin a, cos a) of its own angle.
    const Eigen::Vector2d dl = g.corner(0) - g.corner(1), dr = g.corner(2) - g.corner(3);
    CHECK(std::atan2(dl.x(), dl.y()) == doctest::Approx(left * kPi / 180.0));
    CHECK(std::atan2(dr.x(), dr.y()) == doctest::Approx(right * kPi / 180.0));
    // The abutment faces lie their gap along the axis beyond each end, on the face's line.
    const auto f = g.face_points();
    CHECK((f[1] - g.end_point(1) - Eigen::Vector2d(0.02, 0.0)).norm() < kRoundOff * g.length);
    CHECK((g.end_point(0) - f[0] - Eigen::Vector2d(0.03, 0.0)).norm() < kRoundOff * g.length);
    // The axis's midpoint from the centroid: -(xbar, ybar), xbar = W^2 (t_r^2 - t_l^2) / (24 L),
    // ybar = W^2 (t_r - t_l) / (12 L).
    const double tl = std::tan(left * kPi / 180.0), tr = std::tan(right * kPi / 180.0);
    CHECK(g.axis_centre().x() == doctest::Approx(-64.0 * (tr * tr - tl * tl) / 720.0));
    CHECK(g.axis_centre().y() == doctest::Approx(-64.0 * (tr - tl) / 360.0));
  }
}

TEST_CASE("deck geometry: the annular sector's area, centroid and inertia by integration") {
  // Midpoint rule over (rho, psi) with the area element rho drho dpsi: second-order, with
  // n = 400 cells per direction its relative error is below 1e-6 here; 1e-5 gives margin.
  constexpr double kQuadrature = 1e-5;
  constexpr int n = 400;
  for (const auto& sector :
       {std::tuple{100.0, 10.0, 60.0}, std::tuple{40.0, 12.0, 120.0}, std::tuple{500.0, 8.0, 5.0}}) {
    const double radius = std::get<0>(sector), width = std::get<1>(sector),
                 angle_deg = std::get<2>(sector);
    CAPTURE(radius);
    CAPTURE(angle_deg);
    const double phi = angle_deg * kPi / 180.0;
    const double ri = radius - 0.5 * width, dr = width / n, dp = phi / n;
    double area = 0.0, my = 0.0, j0 = 0.0;  // integrals of 1, y and rho^2 (about the centre)
    for (int a = 0; a < n; ++a) {
      const double rho = ri + (a + 0.5) * dr;
      for (int b = 0; b < n; ++b) {
        const double psi = -0.5 * phi + (b + 0.5) * dp;
        const double da = rho * dr * dp;
        area += da;
        my += rho * std::cos(psi) * da;
        j0 += rho * rho * da;
      }
    }
    const double rbar = my / area;
    const auto s = nsb::models::annular_sector(radius, width, phi);
    CHECK(s.area == doctest::Approx(area).epsilon(kQuadrature));
    CHECK(s.centroid_radius == doctest::Approx(rbar).epsilon(kQuadrature));
    // I_G / m = J_centre / A - rbar^2 (parallel axes).
    CHECK(s.inertia_per_mass == doctest::Approx(j0 / area - rbar * rbar).epsilon(kQuadrature));
  }
}

TEST_CASE("deck geometry: a curved deck's ends, faces and bents are radial") {
  const DeckGeometry g{.length = 100.0 * kPi / 3.0, .width = 10.0, .skew_deg = 0.0,
                       .gap_right = 0.05, .gap_left = 0.04, .radius = 100.0};
  REQUIRE_NOTHROW(g.validate());
  CHECK(g.subtended_angle() == doctest::Approx(kPi / 3.0));
  // The centre of curvature: the mid-arc point R above it, at axis_centre() - (0, R).
  const Eigen::Vector2d centre = g.axis_centre() - Eigen::Vector2d(0.0, 100.0);
  for (int i = 0; i < 4; ++i) {
    CAPTURE(i);
    const Eigen::Vector2d r = g.corner(i) - centre;
    CHECK(r.norm() == doctest::Approx(i % 2 == 0 ? 105.0 : 95.0));
    // The face normal is perpendicular to the radius through the corner (a radial face).
    CHECK(std::abs(r.normalized().dot(g.face_normal(i))) < kRoundOff);
    CHECK(std::abs(std::atan2(r.x(), r.y())) == doctest::Approx(kPi / 6.0));
  }
  // The abutment face points on the ends' radial lines' normals, the gap away.
  const auto f = g.face_points();
  CHECK((f[1] - g.end_point(1)).norm() == doctest::Approx(0.05));
  CHECK(std::abs((f[1] - g.end_point(1)).dot(g.end_point(1) - centre)) < 1e-9);
  // A bent at arc length s with columns at +-3 m: the columns at radii R -+ 3 on the radial
  // line at psi = s / R, in the parts' form (x = position + e tan(beta), y = e).
  const double s = 20.0;
  const auto site = g.bent_site(s, {-3.0, 3.0}, 0.0);
  REQUIRE(site.column_offsets.size() == 2);
  for (std::size_t c = 0; c < 2; ++c) {
    const double e = site.column_offsets[c];
    const Eigen::Vector2d p(site.position + e * std::tan(site.skew_deg * kPi / 180.0), e);
    const Eigen::Vector2d r = p - centre;
    CHECK(r.norm() == doctest::Approx(c == 0 ? 97.0 : 103.0));
    CHECK(std::atan2(r.x(), r.y()) == doctest::Approx(s / 100.0));
  }
  CHECK(site.skew_deg == doctest::Approx(s / 100.0 * 180.0 / kPi));
}

TEST_CASE("deck geometry: bad plans name their field") {
  DeckGeometry g{.length = 10.0, .width = 4.0, .radius = 1.0};
  CHECK_THROWS_WITH_AS(g.validate(), doctest::Contains("radius"), std::invalid_argument);
  g.radius = 3.0;  // L / R = 3.33 > pi: the radius cannot hold the arc, R > L / pi = 3.18 m
  CHECK_THROWS_WITH_AS(g.validate(),
                       doctest::Contains("radius: R = 3 m cannot hold an arc of L = 10 m"),
                       std::invalid_argument);
  g.radius = 1e5;  // L / R = 1e-4 rad: straight for every purpose
  CHECK_THROWS_WITH_AS(g.validate(), doctest::Contains("radius"), std::invalid_argument);
  g.radius = 30.0;
  g.skew_deg = 10.0;
  CHECK_THROWS_WITH_AS(g.validate(), doctest::Contains("skew_deg"), std::invalid_argument);
  g = DeckGeometry{.length = 10.0, .width = 4.0};
  g.skew_right_deg = 85.0;
  CHECK_THROWS_WITH_AS(g.validate(), doctest::Contains("skew_right_deg"), std::invalid_argument);
}
