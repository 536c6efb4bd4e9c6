// Tests of the simple benchmark systems: forces against hand values, contact Jacobians and
// tangents against finite differences, energies against their closed forms.
#include "models/simple_systems.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>

namespace {

using nsb::integrators::Matrix;
using nsb::integrators::System;
using nsb::integrators::Vector;
using nsb::models::BouncingBall;
using nsb::models::ImpactOscillator;
using nsb::models::SlidingBlock;

// Hand values are evaluated by the same floating-point formula: a few ulps.
constexpr double kExact = 1e-12;
// Central differences of smooth functions with step kStep: truncation O(h^2 f''') and
// round-off O(eps f / h) are both below 1e-7 for the O(1)-scaled data used here.
constexpr double kStep = 1e-5;
constexpr double kFiniteDifference = 1e-7;

double gap_of(const System& s, double t, const Vector& q) {
  auto c = s.make_contact_buffer();
  s.contact_data(t, q, Vector::Zero(s.dofs()), c);
  return c[0].gap_normal;
}

// dg/dq by central differences.
Vector gap_gradient(const System& s, double t, const Vector& q) {
  Vector g(s.dofs());
  for (int j = 0; j < s.dofs(); ++j) {
    Vector qp = q, qm = q;
    qp(j) += kStep;
    qm(j) -= kStep;
    g(j) = (gap_of(s, t, qp) - gap_of(s, t, qm)) / (2.0 * kStep);
  }
  return g;
}

// K = -df/dq and C = -df/du by central differences.
void tangent_fd(System& s, double t, const Vector& q, const Vector& u, Matrix& K, Matrix& C) {
  const int n = s.dofs();
  K.resize(n, n);
  C.resize(n, n);
  Vector fp(n), fm(n);
  for (int j = 0; j < n; ++j) {
    Vector qp = q, qm = q, up = u, um = u;
    qp(j) += kStep;
    qm(j) -= kStep;
    s.forces(t, qp, u, fp);
    s.forces(t, qm, u, fm);
    K.col(j) = -(fp - fm) / (2.0 * kStep);
    up(j) += kStep;
    um(j) -= kStep;
    s.forces(t, q, up, fp);
    s.forces(t, q, um, fm);
    C.col(j) = -(fp - fm) / (2.0 * kStep);
  }
}

void check_tangent(System& s, double t, const Vector& q, const Vector& u) {
  Matrix K, C, Kfd, Cfd;
  s.tangent(t, q, u, K, C);
  tangent_fd(s, t, q, u, Kfd, Cfd);
  INFO("K = " << K << "\nK_fd = " << Kfd << "\nC = " << C << "\nC_fd = " << Cfd);
  CHECK((K - Kfd).cwiseAbs().maxCoeff() <= kFiniteDifference * (1.0 + K.cwiseAbs().maxCoeff()));
  CHECK((C - Cfd).cwiseAbs().maxCoeff() <= kFiniteDifference * (1.0 + C.cwiseAbs().maxCoeff()));
}

// The conservative part of the force is -dV/dq (V = stored energy): checked with u = 0 at a
// time where the driving force vanishes (t = 0).
void check_potential(System& s, const Vector& q) {
  Vector f(s.dofs());
  s.forces(0.0, q, Vector::Zero(s.dofs()), f);
  for (int j = 0; j < s.dofs(); ++j) {
    Vector qp = q, qm = q;
    qp(j) += kStep;
    qm(j) -= kStep;
    const double dv = (s.energy(0.0, qp).stored - s.energy(0.0, qm).stored) / (2.0 * kStep);
    CHECK(f(j) == doctest::Approx(-dv).epsilon(kFiniteDifference));
  }
}

}  // namespace

TEST_CASE("BouncingBall: forces, contact and energy by hand") {
  BouncingBall ball({.mass = 2.0, .height = 3.0, .velocity = 0.5, .restitution = 0.8,
                     .gravity = 9.81});
  REQUIRE(ball.dofs() == 1);
  CHECK(ball.initial_position()(0) == 3.0);
  CHECK(ball.initial_velocity()(0) == 0.5);
  CHECK(ball.mass()(0, 0) == 2.0);
  Vector q = Vector::Constant(1, 1.25), u = Vector::Constant(1, -2.0), f(1);
  ball.forces(0.3, q, u, f);
  CHECK(f(0) == doctest::Approx(-2.0 * 9.81).epsilon(kExact));  // -m g
  auto c = ball.make_contact_buffer();
  ball.contact_data(0.3, q, u, c);
  CHECK(c[0].gap_normal == 1.25);  // g_N = y
  CHECK(c[0].w_normal(0) == 1.0);
  CHECK(c[0].w_tangent(0) == 0.0);
  CHECK(c[0].restitution == 0.8);
  CHECK(c[0].friction == 0.0);
  CHECK(c[0].what_normal == 0.0);
  CHECK(c[0].wbar_normal == 0.0);
  CHECK(c[0].gap_rate(u) == -2.0);
  CHECK(gap_gradient(ball, 0.3, q)(0) == doctest::Approx(c[0].w_normal(0)).epsilon(kFiniteDifference));
  CHECK(ball.energy(0.0, q).stored == doctest::Approx(2.0 * 9.81 * 1.25).epsilon(kExact));
  CHECK(ball.power(0.0, q, u).damping == 0.0);
  CHECK(ball.power(0.0, q, u).external == 0.0);
  check_tangent(ball, 0.3, q, u);
  check_potential(ball, q);
}

TEST_CASE("ImpactOscillator: forces, contact and energy by hand") {
  const double m = 2.0, k = 50.0, zeta = 0.05, f0 = 3.0, freq = 1.5;
  ImpactOscillator osc({.mass = m, .stiffness = k, .damping_ratio = zeta, .gap = 0.2,
                        .restitution = 0.6, .initial_position = 0.1, .initial_velocity = -0.3,
                        .force_amplitude = f0, .force_frequency = freq});
  const double c = 2.0 * zeta * std::sqrt(k * m);  // = 1.0 kN s/m
  CHECK(osc.damping_coefficient() == doctest::Approx(1.0).epsilon(kExact));
  CHECK(osc.initial_position()(0) == 0.1);
  CHECK(osc.initial_velocity()(0) == -0.3);
  const double t = 0.1;
  Vector q = Vector::Constant(1, 0.15), u = Vector::Constant(1, 0.4), f(1);
  osc.forces(t, q, u, f);
  // -k x - c v + F0 sin(2 pi f t) = -7.5 - 0.4 + 3 sin(0.3 pi)
  const double ft = f0 * std::sin(2.0 * std::numbers::pi * freq * t);
  CHECK(f(0) == doctest::Approx(-7.5 - 0.4 + ft).epsilon(kExact));
  auto cd = osc.make_contact_buffer();
  osc.contact_data(t, q, u, cd);
  CHECK(cd[0].gap_normal == doctest::Approx(0.05).epsilon(kExact));  // gap - x
  CHECK(cd[0].w_normal(0) == -1.0);
  CHECK(cd[0].restitution == 0.6);
  CHECK(gap_gradient(osc, t, q)(0) == doctest::Approx(-1.0).epsilon(kFiniteDifference));
  CHECK(osc.energy(t, q).stored == doctest::Approx(0.5 * k * 0.15 * 0.15).epsilon(kExact));
  const auto pw = osc.power(t, q, u);
  CHECK(pw.damping == doctest::Approx(c * 0.4 * 0.4).epsilon(kExact));
  CHECK(pw.external == doctest::Approx(ft * 0.4).epsilon(kExact));
  check_tangent(osc, t, q, u);
  check_potential(osc, q);
}

TEST_CASE("SlidingBlock: forces, contact Jacobians and energy, level and inclined") {
  for (double incline : {0.0, 20.0, -35.0}) {
    CAPTURE(incline);
    const double m = 3.0, g = 9.81, force = 4.0, f0 = 2.0, freq = 0.7;
    SlidingBlock block({.mass = m, .friction = 0.3, .gravity = g, .initial_velocity = 1.5,
                        .force = force, .force_amplitude = f0, .force_frequency = freq,
                        .incline_deg = incline});
    const double beta = incline * std::numbers::pi / 180.0;
    REQUIRE(block.dofs() == 2);
    CHECK(block.initial_position().isZero());
    CHECK(block.initial_velocity()(0) == 1.5);
    CHECK(block.initial_velocity()(1) == 0.0);
    const double t = 0.4;
    Vector q(2), u(2), f(2);
    q << 0.7, 0.02;
    u << 1.1, -0.2;
    block.forces(t, q, u, f);
    const double drive = force + f0 * std::sin(2.0 * std::numbers::pi * freq * t);
    CHECK(block.driving_force(t) == doctest::Approx(drive).epsilon(kExact));
    CHECK(f(0) == doctest::Approx(drive - m * g * std::sin(beta)).epsilon(kExact));
    CHECK(f(1) == doctest::Approx(-m * g * std::cos(beta)).epsilon(kExact));
    auto c = block.make_contact_buffer();
    block.contact_data(t, q, u, c);
    CHECK(c[0].gap_normal == 0.02);
    CHECK(c[0].friction == 0.3);
    CHECK(c[0].restitution == 0.0);
    const Vector dg = gap_gradient(block, t, q);
    for (int j = 0; j < 2; ++j) {
      CHECK(dg(j) == doctest::Approx(c[0].w_normal(j)).scale(1.0).epsilon(kFiniteDifference));
    }
    // Tangential slip of the block on the fixed ground is x: W_T = d x / d q = (1, 0).
    CHECK(c[0].w_tangent(0) == 1.0);
    CHECK(c[0].w_tangent(1) == 0.0);
    CHECK(c[0].slip_rate(u) == 1.1);
    CHECK(c[0].w_normal.dot(c[0].w_tangent) == 0.0);
    CHECK(block.energy(t, q).stored ==
          doctest::Approx(m * g * (0.7 * std::sin(beta) + 0.02 * std::cos(beta))).epsilon(kExact));
    CHECK(block.power(t, q, u).external == doctest::Approx(drive * 1.1).epsilon(kExact));
    CHECK(block.power(t, q, u).damping == 0.0);
    check_tangent(block, t, q, u);
  }
  SlidingBlock level({.mass = 3.0, .gravity = 9.81, .incline_deg = 10.0});
  Vector q(2);
  q << 0.3, 0.1;
  check_potential(level, q);
}

TEST_CASE("Parameters: invalid values are rejected with the field named") {
  auto message = [](const std::function<void()>& f) -> std::string {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  CHECK(message([] { BouncingBall({.mass = -1.0}); }).find("mass") != std::string::npos);
  CHECK(message([] { BouncingBall({.height = -0.1}); }).find("height") != std::string::npos);
  CHECK(message([] { BouncingBall({.restitution = 1.5}); }).find("restitution") !=
        std::string::npos);
  CHECK(message([] { BouncingBall({.velocity = NAN}); }).find("velocity") != std::string::npos);
  CHECK(message([] { ImpactOscillator({.gap = 0.1, .initial_position = 0.2}); })
            .find("initial_position") != std::string::npos);
  CHECK(message([] { ImpactOscillator({.stiffness = -1.0}); }).find("stiffness") !=
        std::string::npos);
  CHECK(message([] { ImpactOscillator({.damping_ratio = -0.1}); }).find("damping_ratio") !=
        std::string::npos);
  CHECK(message([] { ImpactOscillator({.force_frequency = -1.0}); }).find("force_frequency") !=
        std::string::npos);
  CHECK(message([] { SlidingBlock({.friction = -0.1}); }).find("friction") != std::string::npos);
  CHECK(message([] { SlidingBlock({.incline_deg = 90.0}); }).find("incline_deg") !=
        std::string::npos);
  CHECK(message([] { SlidingBlock({.mass = 0.0}); }).find("mass") != std::string::npos);
  // Valid edge values are accepted.
  CHECK_NOTHROW(BouncingBall({.height = 0.0, .restitution = 0.0}));
  CHECK_NOTHROW(ImpactOscillator({.gap = 0.1, .initial_position = 0.1}));
  CHECK_NOTHROW(SlidingBlock({.friction = 0.0}));
}
