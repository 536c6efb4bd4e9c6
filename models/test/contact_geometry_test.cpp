// Contact kinematics of a body corner against a moving, rotating face: W_N, W_T, gdot and
// gddot against finite differences of g_N and g_T (models/contact_geometry.hpp).
#include "models/contact_geometry.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>

namespace {

using nsb::models::ContactKinematics;
using nsb::models::CornerFace;
using nsb::models::corner_contact;
using nsb::models::PlanarMotion;

// Central differences with step h have truncation error O(h^2 f''') and round-off
// O(eps |f| / h) (first) or O(eps |f| / h^2) (second). With |f| ~ 10 m, h = 1e-4 the first
// derivative is good to ~1e-8 and the second to ~1e-5 (round-off 2e-16*10/1e-8 = 2e-7, plus
// truncation h^2 * f'''' ~ 1e-6): tolerances 1e-6 and 1e-4 relative to the quantities' scale.
constexpr double kStep = 1e-4;
constexpr double kFirstTol = 1e-6;
constexpr double kSecondTol = 1e-4;

// An obstacle in smooth prescribed motion: X, Y, Phi are sums of sines, with exact derivatives.
struct Trajectory {
  Eigen::Vector3d p0, a1, w1, a2;  // pose = p0 + a1 sin(w1 t) + a2 t^2 / 2
  PlanarMotion at(double t) const {
    PlanarMotion m;
    for (int k = 0; k < 3; ++k) {
      m.position(k) = p0(k) + a1(k) * std::sin(w1(k) * t) + 0.5 * a2(k) * t * t;
      m.velocity(k) = a1(k) * w1(k) * std::cos(w1(k) * t) + a2(k) * t;
      m.acceleration(k) = -a1(k) * w1(k) * w1(k) * std::sin(w1(k) * t) + a2(k);
    }
    return m;
  }
};

// Body motion with constant acceleration: q(t) = q0 + u0 t + a t^2 / 2.
struct BodyPath {
  Eigen::Vector3d q0, u0, a;
  Eigen::Vector3d q(double t) const { return q0 + u0 * t + 0.5 * a * t * t; }
  Eigen::Vector3d u(double t) const { return u0 + a * t; }
};

ContactKinematics eval(const CornerFace& c, const BodyPath& b, const Trajectory& o, double t) {
  return corner_contact(c, b.q(t), b.u(t), o.at(t));
}

}  // namespace

TEST_CASE("a corner of a body at rest against a fixed face: hand-derived gap and frame") {
  // Face through (1, 0) with normal (-1, 0) (obstacle to the right, body to its left).
  // Corner at body point (0.5, 0.25) of a body at (0, 0, 0): p = (0.5, 0.25).
  // g_N = n.(p - a) = -1 * (0.5 - 1) = 0.5; t = n rotated +90 deg = (0, -1);
  // g_T = t.(p - a) = -0.25. W_N = (n, r x n) = (-1, 0, 0.5*0 - 0.25*(-1)) = (-1, 0, 0.25).
  // W_T = (0, -1, 0.5*(-1) - 0.25*0) = (0, -1, -0.5).
  CornerFace c;
  c.body_point = {0.5, 0.25};
  c.face_point = {0.0, 0.0};
  c.face_normal = {-1.0, 0.0};
  PlanarMotion o;
  o.position << 1.0, 0.0, 0.0;
  const auto k = corner_contact(c, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), o);
  CHECK(k.gap_normal == doctest::Approx(0.5));
  CHECK(k.gap_tangent == doctest::Approx(-0.25));
  CHECK(k.w_normal(0) == doctest::Approx(-1.0));
  CHECK(k.w_normal(1) == doctest::Approx(0.0));
  CHECK(k.w_normal(2) == doctest::Approx(0.25));
  CHECK(k.w_tangent(0) == doctest::Approx(0.0));
  CHECK(k.w_tangent(1) == doctest::Approx(-1.0));
  CHECK(k.w_tangent(2) == doctest::Approx(-0.5));
  CHECK(k.what_normal == 0.0);
  CHECK(k.wbar_normal == 0.0);
}

TEST_CASE("a face translating towards a resting corner closes the gap at its own speed") {
  // Face normal (-1, 0) moving with velocity (-2, 0): gdot_N = -n.adot = -(-1)(-2) = -2.
  CornerFace c;
  c.face_normal = {-1.0, 0.0};
  PlanarMotion o;
  o.position << 1.0, 0.0, 0.0;
  o.velocity << -2.0, 0.0, 0.0;
  const auto k = corner_contact(c, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), o);
  CHECK(k.what_normal == doctest::Approx(-2.0));
  CHECK(k.gap_rate_normal == doctest::Approx(-2.0));
}

TEST_CASE("W_N and W_T are the partial derivatives of g_N and g_T with respect to q") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    CornerFace c;
    c.body_point = {10.0 * U(rng), 2.0 * U(rng)};
    c.face_point = {U(rng), U(rng)};
    const double ang = 3.0 * U(rng);
    c.face_normal = {std::cos(ang), std::sin(ang)};
    PlanarMotion o;
    o.position << 5.0 * U(rng), U(rng), 0.3 * U(rng);
    const Eigen::Vector3d q(U(rng), U(rng), 0.2 * U(rng));
    const auto k = corner_contact(c, q, Eigen::Vector3d::Zero(), o);
    for (int j = 0; j < 3; ++j) {
      Eigen::Vector3d qp = q, qm = q;
      qp(j) += kStep;
      qm(j) -= kStep;
      const auto kp = corner_contact(c, qp, Eigen::Vector3d::Zero(), o);
      const auto km = corner_contact(c, qm, Eigen::Vector3d::Zero(), o);
      const double dn = (kp.gap_normal - km.gap_normal) / (2 * kStep);
      const double dt = (kp.gap_tangent - km.gap_tangent) / (2 * kStep);
      CHECK(k.w_normal(j) == doctest::Approx(dn).epsilon(kFirstTol).scale(10.0));
      CHECK(k.w_tangent(j) == doctest::Approx(dt).epsilon(kFirstTol).scale(10.0));
    }
  }
}

TEST_CASE("gdot and gddot match finite differences of g_N and g_T along a trajectory with a "
          "moving, rotating obstacle") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    CornerFace c;
    c.body_point = {10.0 * U(rng), 2.0 * U(rng)};
    c.face_point = {U(rng), U(rng)};
    const double ang = 3.0 * U(rng);
    c.face_normal = {std::cos(ang), std::sin(ang)};
    Trajectory o;
    o.p0 << 5.0 * U(rng), U(rng), 0.3 * U(rng);
    o.a1 << 0.5 * U(rng), 0.5 * U(rng), 0.1 * U(rng);
    o.w1 << 3.0 + U(rng), 3.0 + U(rng), 3.0 + U(rng);
    o.a2 << U(rng), U(rng), 0.2 * U(rng);
    BodyPath b;
    b.q0 << U(rng), U(rng), 0.2 * U(rng);
    b.u0 << U(rng), U(rng), 0.3 * U(rng);
    b.a << U(rng), U(rng), 0.3 * U(rng);
    const double t = 0.5 + 0.4 * U(rng);
    const auto k0 = eval(c, b, o, t);
    const auto kp = eval(c, b, o, t + kStep);
    const auto km = eval(c, b, o, t - kStep);
    const double gdot_n = (kp.gap_normal - km.gap_normal) / (2 * kStep);
    const double gdot_t = (kp.gap_tangent - km.gap_tangent) / (2 * kStep);
    const double gdd_n = (kp.gap_normal - 2 * k0.gap_normal + km.gap_normal) / (kStep * kStep);
    const double gdd_t = (kp.gap_tangent - 2 * k0.gap_tangent + km.gap_tangent) / (kStep * kStep);
    const Eigen::Vector3d u = b.u(t);
    CHECK(k0.w_normal.dot(u) + k0.what_normal == doctest::Approx(gdot_n).epsilon(kFirstTol).scale(10.0));
    CHECK(k0.w_tangent.dot(u) + k0.what_tangent == doctest::Approx(gdot_t).epsilon(kFirstTol).scale(10.0));
    CHECK(k0.gap_rate_normal == doctest::Approx(gdot_n).epsilon(kFirstTol).scale(10.0));
    CHECK(k0.w_normal.dot(b.a) + k0.wbar_normal ==
          doctest::Approx(gdd_n).epsilon(kSecondTol).scale(10.0));
    CHECK(k0.w_tangent.dot(b.a) + k0.wbar_tangent ==
          doctest::Approx(gdd_t).epsilon(kSecondTol).scale(10.0));
  }
}

TEST_CASE("the contact frame rotates with the obstacle and t is n rotated +90 degrees") {
  CornerFace c;
  c.face_normal = {1.0, 0.0};
  PlanarMotion o;
  o.position << 0.0, 0.0, std::acos(-1.0) / 2;  // quarter turn: n = (0, 1), t = (-1, 0)
  const auto k = corner_contact(c, Eigen::Vector3d(0, 1, 0), Eigen::Vector3d::Zero(), o);
  CHECK(k.normal.x() == doctest::Approx(0.0).epsilon(1e-12));
  CHECK(k.normal.y() == doctest::Approx(1.0));
  CHECK(k.tangent.x() == doctest::Approx(-1.0));
  CHECK(k.tangent.y() == doctest::Approx(0.0).epsilon(1e-12));
  CHECK(k.gap_normal == doctest::Approx(1.0));
}
