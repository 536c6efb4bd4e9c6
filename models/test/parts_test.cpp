// The parts of an assembly (models/parts.hpp): body plans and end faces, the kinematics of a
// corner on the face of another free body checked against finite differences, the contact
// writers and the motion table.
#include "models/parts.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>

namespace {

using nsb::models::CornerFace;
using namespace nsb::models::parts;

// Central differences with step 1e-6 on O(10 m) geometry: truncation ~ h^2 * 10 ~ 1e-11,
// round-off ~ 1e-16 * 10 / 1e-6 ~ 1e-9.
constexpr double kFdStep = 1e-6;
constexpr double kFdTol = 1e-7;
// Second differences with step 1e-4: truncation ~ h^2 ~ 1e-8, round-off ~ 1e-16 * 10 / 1e-8
// ~ 1e-7.
constexpr double kFd2Step = 1e-4;
constexpr double kFd2Tol = 1e-5;

RigidBody body(double length, double skew_deg) {
  return {.mass = 100.0, .inertia = 5000.0, .length = length, .width = 2.0,
          .skew_deg = skew_deg};
}

// A corner of body A (left end, +W/2) on the right end face of body B, both skewed.
CornerFace hinge() {
  const RigidBody a = body(20.0, 15.0), b = body(24.0, 15.0);
  const Face f = end_face(b, End::kRight);
  return {.body_point = a.corner(0), .face_point = f.point, .face_normal = f.normal};
}

struct State {
  Eigen::Vector3d qa, ua, qb, ub;
};

State moving() {
  // B near the origin, A just beyond B's right end; both translating and rotating.
  return {.qa = {22.1, 0.05, 0.01}, .ua = {-0.7, 0.2, 0.03},
          .qb = {0.02, -0.03, -0.004}, .ub = {0.4, -0.1, -0.02}};
}

}  // namespace

TEST_CASE("end faces pass through the end midpoints with outward normals") {
  const RigidBody b = body(20.0, 30.0);
  const Face l = end_face(b, End::kLeft), r = end_face(b, End::kRight);
  const double a = 30.0 * std::numbers::pi / 180.0;
  CHECK(l.point.isApprox(Eigen::Vector2d(-10.0, 0.0)));
  CHECK(r.point.isApprox(Eigen::Vector2d(10.0, 0.0)));
  CHECK(r.normal.isApprox(Eigen::Vector2d(std::cos(a), -std::sin(a))));
  CHECK(l.normal.isApprox(-r.normal));
  // The corners of each end lie on its face: (corner - point) . normal = 0.
  CHECK(std::abs((b.corner(0) - l.point).dot(l.normal)) < 1e-12);
  CHECK(std::abs((b.corner(1) - l.point).dot(l.normal)) < 1e-12);
  CHECK(std::abs((b.corner(2) - r.point).dot(r.normal)) < 1e-12);
  CHECK(std::abs((b.corner(3) - r.point).dot(r.normal)) < 1e-12);
}

TEST_CASE("a rigid body names the bad field") {
  RigidBody b = body(20.0, 0.0);
  b.inertia = -1.0;
  CHECK_THROWS_WITH_AS(b.validate("bodies[2]."), "bodies[2].inertia: must be > 0 [t m^2]",
                       std::invalid_argument);
  b = body(20.0, 85.0);
  CHECK_THROWS_WITH_AS(b.validate("bodies[0]."), "bodies[0].skew_deg: must be in (-80, 80) [deg]",
                       std::invalid_argument);
}

TEST_CASE("corner on a body: W_N, W_T of both bodies are the gradients of g_N, g_T") {
  const CornerFace c = hinge();
  const State s = moving();
  const auto k = corner_on_body(c, s.qa, s.ua, s.qb, s.ub);
  auto gaps = [&](const Eigen::Vector3d& qa, const Eigen::Vector3d& qb) {
    const auto g = corner_on_body(c, qa, s.ua, qb, s.ub);
    return Eigen::Vector2d(g.a.gap_normal, g.a.gap_tangent);
  };
  for (int i = 0; i < 3; ++i) {
    INFO("coordinate ", i);
    const Eigen::Vector3d e = kFdStep * Eigen::Vector3d::Unit(i);
    const Eigen::Vector2d da = (gaps(s.qa + e, s.qb) - gaps(s.qa - e, s.qb)) / (2 * kFdStep);
    const Eigen::Vector2d db = (gaps(s.qa, s.qb + e) - gaps(s.qa, s.qb - e)) / (2 * kFdStep);
    CHECK(std::abs(da.x() - k.a.w_normal(i)) < kFdTol);
    CHECK(std::abs(da.y() - k.a.w_tangent(i)) < kFdTol);
    CHECK(std::abs(db.x() - k.w_normal_b(i)) < kFdTol);
    CHECK(std::abs(db.y() - k.w_tangent_b(i)) < kFdTol);
  }
  // The rates: W_A^T u_A + W_B^T u_B is corner_contact's relative rate (B as a moving face).
  CHECK(std::abs(k.a.w_normal.dot(s.ua) + k.w_normal_b.dot(s.ub) - k.a.gap_rate_normal) < 1e-12);
  CHECK(std::abs(k.a.w_tangent.dot(s.ua) + k.w_tangent_b.dot(s.ub) - k.a.gap_rate_tangent) <
        1e-12);
}

TEST_CASE("corner on a body: wbar is the second time derivative at zero acceleration") {
  // Along q(t) = q0 + u t with u constant (udot = 0), gddot = wbar exactly.
  const CornerFace c = hinge();
  const State s = moving();
  const auto k = corner_on_body(c, s.qa, s.ua, s.qb, s.ub);
  auto gaps = [&](double t) {
    const auto g = corner_on_body(c, s.qa + t * s.ua, s.ua, s.qb + t * s.ub, s.ub);
    return Eigen::Vector2d(g.a.gap_normal, g.a.gap_tangent);
  };
  const Eigen::Vector2d second =
      (gaps(kFd2Step) - 2.0 * gaps(0.0) + gaps(-kFd2Step)) / (kFd2Step * kFd2Step);
  CHECK(std::abs(second.x() - k.a.wbar_normal) < kFd2Tol);
  CHECK(std::abs(second.y() - k.a.wbar_tangent) < kFd2Tol);
}

TEST_CASE("contact writers fill the bodies' rows and zero the rest") {
  const State s = moving();
  const auto k = corner_on_body(hinge(), s.qa, s.ua, s.qb, s.ub);
  nsb::integrators::ContactData d;
  d.w_normal = Eigen::VectorXd::Constant(9, 7.0);  // stale values must go
  d.w_tangent = Eigen::VectorXd::Constant(9, 7.0);
  write_body_contact(k, 6, 0, 0.4, 0.6, d);
  CHECK(d.w_normal.segment<3>(6) == k.a.w_normal);
  CHECK(d.w_normal.segment<3>(0) == k.w_normal_b);
  CHECK(d.w_normal.segment<3>(3).isZero());
  CHECK(d.w_tangent.segment<3>(3).isZero());
  CHECK(d.what_normal == 0.0);
  CHECK(d.what_tangent == 0.0);
  CHECK(d.restitution == 0.4);
  CHECK(d.friction == 0.6);
  nsb::integrators::ContactData n;
  n.w_normal = Eigen::VectorXd::Constant(9, 7.0);
  write_body_contact_normal(k, 6, 0, n);
  CHECK(n.gap_normal == d.gap_normal);
  CHECK(n.w_normal == d.w_normal);
  CHECK(n.far == d.far);
}

TEST_CASE("corner on a body: the normal part alone gives the same numbers") {
  const State s = moving();
  const auto k = corner_on_body(hinge(), s.qa, s.ua, s.qb, s.ub);
  const auto n = corner_on_body_normal(hinge(), s.qa, s.ua, s.qb, s.ub);
  CHECK(n.a.gap_normal == k.a.gap_normal);
  CHECK(n.a.w_normal == k.a.w_normal);
  CHECK(n.a.what_normal == k.a.what_normal);
  CHECK(n.a.gap_rate_normal == k.a.gap_rate_normal);
  CHECK(n.a.point == k.a.point);
  CHECK(n.w_normal_b == k.w_normal_b);
  nsb::integrators::ContactData full, part;
  full.w_normal = Eigen::VectorXd::Constant(9, 7.0);
  part.w_normal = Eigen::VectorXd::Constant(9, 7.0);
  write_body_contact_normal(k, 6, 0, full);
  write_body_contact_normal(n, 6, 0, part);
  CHECK(part.gap_normal == full.gap_normal);
  CHECK(part.w_normal == full.w_normal);
  CHECK(part.what_normal == full.what_normal);
  CHECK(part.far == full.far);
}

TEST_CASE("the motion table shares a record between supports and caches one time") {
  nsb::models::Record r{.t = {0.0, 0.5, 1.0, 1.5}, .a = {0.0, 1.0, -1.0, 0.0}, .source = "test"};
  nsb::models::GroundMotionOptions o;
  o.baseline_correction = false;
  const Motion m = std::make_shared<const nsb::models::GroundMotion>(r, o);
  const Motion other = std::make_shared<const nsb::models::GroundMotion>(r, o);
  MotionTable t;
  CHECK(t.add(nullptr, true) == MotionTable::kNone);
  const int i = t.add(m, false);
  CHECK(t.add(m, true) == i);  // the same object: one entry, now with its acceleration
  CHECK(t.add(other, false) != i);
  CHECK(t.update(0.7));
  CHECK(!t.update(0.7));  // cached
  const auto g = m->values(0.7);
  CHECK(t.value(i).d == g.displacement);
  CHECK(t.value(i).v == g.velocity);
  CHECK(t.value(i).a == g.acceleration);
  CHECK(t.value(t.add(other, false)).a == 0.0);  // springs need no acceleration
  CHECK(t.value(MotionTable::kNone).d == 0.0);
}
