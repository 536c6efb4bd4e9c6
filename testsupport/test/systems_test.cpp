// The test-support systems: their contact data against finite differences of their own gaps
// (W_N = dg_N/dq, gdot_N = W_N^T u + what_N) and of their gap rates along a path with
// acceleration a (gddot = W^T a + wbar, normal and tangential), and the defaults they take
// from SystemBase.
#include "testsupport/systems.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace ts = nsb::testsupport;
using ts::ContactData;
using ts::Matrix;
using ts::Vector;

// Central differences with step h have truncation error ~h^2 |g'''| / 6 and round-off
// ~eps |g| / h. With |g''| and |g'''| of order 10 (w^2 and w^3 of the test motions, w <= 3)
// and h = 1e-5: truncation ~2e-10, round-off ~1e-11. Measured worst case over these systems
// and points: 1.4e-10; the bound 1e-8 leaves a factor 70.
constexpr double kStep = 1e-5;
constexpr double kDifferenceTol = 1e-8;

struct Point {
  double t;
  Vector q, u, a;
};

std::vector<ContactData> contacts_at(const nsb::integrators::System& s, double t, const Vector& q,
                                     const Vector& u) {
  auto c = s.make_contact_buffer();
  s.contact_data(t, q, u, c);
  return c;
}

// Position and velocity at time t + d on the path q + u d + a d^2 / 2.
Vector path_q(const Point& p, double d) { return p.q + d * p.u + 0.5 * d * d * p.a; }
Vector path_u(const Point& p, double d) { return p.u + d * p.a; }

// Checks every contact of s at p against finite differences.
void check_contact_derivatives(const nsb::integrators::System& s, const Point& p) {
  const int n = s.dofs();
  const auto c0 = contacts_at(s, p.t, p.q, p.u);
  REQUIRE(static_cast<int>(c0.size()) == s.contacts());
  for (std::size_t i = 0; i < c0.size(); ++i) {
    INFO("contact ", i + 1, " at t = ", p.t);
    // W_N = dg_N/dq, column by column.
    for (int j = 0; j < n; ++j) {
      Vector qp = p.q, qm = p.q;
      qp[j] += kStep;
      qm[j] -= kStep;
      const double dg = (contacts_at(s, p.t, qp, p.u)[i].gap_normal -
                         contacts_at(s, p.t, qm, p.u)[i].gap_normal) / (2 * kStep);
      CHECK(std::abs(dg - c0[i].w_normal[j]) <= kDifferenceTol);
    }
    // gdot_N = dg_N/dt along the path = W_N^T u + what_N.
    const double gdot = (contacts_at(s, p.t + kStep, path_q(p, kStep), path_u(p, kStep))[i].gap_normal -
                         contacts_at(s, p.t - kStep, path_q(p, -kStep), path_u(p, -kStep))[i].gap_normal) /
                        (2 * kStep);
    CHECK(std::abs(gdot - c0[i].gap_rate(p.u)) <= kDifferenceTol);
    // gddot = d(gdot)/dt along the path = W^T a + wbar, for both directions.
    const auto cp = contacts_at(s, p.t + kStep, path_q(p, kStep), path_u(p, kStep));
    const auto cm = contacts_at(s, p.t - kStep, path_q(p, -kStep), path_u(p, -kStep));
    const double gddot_n =
        (cp[i].gap_rate(path_u(p, kStep)) - cm[i].gap_rate(path_u(p, -kStep))) / (2 * kStep);
    const double gddot_t =
        (cp[i].slip_rate(path_u(p, kStep)) - cm[i].slip_rate(path_u(p, -kStep))) / (2 * kStep);
    CHECK(std::abs(gddot_n - (c0[i].w_normal.dot(p.a) + c0[i].wbar_normal)) <= kDifferenceTol);
    CHECK(std::abs(gddot_t - (c0[i].w_tangent.dot(p.a) + c0[i].wbar_tangent)) <= kDifferenceTol);
  }
}

// Random points with |q|, |u|, |a| <= 1 and t in [0, 2].
std::vector<Point> random_points(int n, int count) {
  std::mt19937 rng(20261123);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Point> points;
  for (int k = 0; k < count; ++k) {
    Point p{1.0 + unit(rng), Vector(n), Vector(n), Vector(n)};
    for (int j = 0; j < n; ++j) {
      p.q[j] = unit(rng);
      p.u[j] = unit(rng);
      p.a[j] = unit(rng);
    }
    points.push_back(p);
  }
  return points;
}

void check_system(const nsb::integrators::System& s) {
  for (const Point& p : random_points(s.dofs(), 20)) check_contact_derivatives(s, p);
}

}  // namespace

TEST_CASE("test systems: contact Jacobians and rheonomic terms match finite differences") {
  SUBCASE("spring mass against a moving wall") {
    check_system(ts::SpringMass({.stiffness = 4.0, .wall = true, .wall_velocity = 0.3}));
  }
  SUBCASE("ball above a moving floor") {
    check_system(ts::Ball({.floor_velocity = 0.2, .floor_amplitude = 0.1, .floor_frequency = 3.0}));
  }
  SUBCASE("block on the ground") { check_system(ts::Block({.friction = 0.4, .stiffness = 2.0})); }
  SUBCASE("block against an accelerating wall") {
    check_system(ts::WallBlock({.friction = 0.3, .wall_position = 0.1, .wall_velocity = -0.5,
                                .wall_acceleration = 2.0}));
  }
  SUBCASE("two masses") { check_system(ts::TwoMasses({.distance = 0.1})); }
  SUBCASE("two-corner bar") {
    check_system(ts::TwoCornerBody({.half_length = 1.5, .friction = 0.5}));
  }
}

TEST_CASE("test systems: the accelerating wall's exact motion") {
  // x_w(t) = x0 + v0 t + a t^2 / 2 at t = 2: 0.1 - 1 + 4 = 3.1; x_w' = v0 + a t = 3.5.
  const ts::WallBlock s({.wall_position = 0.1, .wall_velocity = -0.5, .wall_acceleration = 2.0,
                         .initial_gap = 0.25});
  CHECK(s.wall_position(2.0) == doctest::Approx(3.1).epsilon(1e-15));
  CHECK(s.wall_velocity(2.0) == doctest::Approx(3.5).epsilon(1e-15));
  // Starts at the given gap and at the wall's velocity: gdot_N(0) = 0.
  const auto c = contacts_at(s, 0.0, s.initial_position(), s.initial_velocity());
  CHECK(c[0].gap_normal == doctest::Approx(0.25).epsilon(1e-15));
  CHECK(c[0].gap_rate(s.initial_velocity()) == 0.0);
  CHECK(c[0].wbar_normal == -2.0);
}

TEST_CASE("SystemBase: the defaults of a system that states only its size") {
  ts::FreeMass s(2);
  CHECK(s.dofs() == 2);
  CHECK(s.coordinate_names() == std::vector<std::string>{"q1", "q2"});
  CHECK(s.velocity_names() == std::vector<std::string>{"u1", "u2"});
  CHECK(s.mass() == Matrix::Identity(2, 2));
  CHECK(s.initial_position() == Vector::Zero(2));
  CHECK(s.initial_velocity() == Vector::Zero(2));
  CHECK(s.initial_time() == 0.0);
  CHECK(s.contacts() == 0);
  CHECK_FALSE(s.tangent_changed());
  Vector f = Vector::Ones(2);
  Matrix K = Matrix::Ones(2, 2), C = Matrix::Ones(2, 2);
  s.forces(0.0, Vector::Ones(2), Vector::Ones(2), f);
  s.tangent(0.0, Vector::Ones(2), Vector::Ones(2), K, C);
  CHECK(f == Vector::Zero(2));
  CHECK(K == Matrix::Zero(2, 2));
  CHECK(C == Matrix::Zero(2, 2));
  CHECK(s.power(0.0, Vector::Ones(2), Vector::Ones(2)).external == 0.0);
  CHECK(s.energy(0.0, Vector::Ones(2)).stored == 0.0);
  s.commit();
  CHECK(s.commits == 1);
  CHECK_THROWS_AS(ts::FreeMass({"a"}, {"va", "vb"}), std::invalid_argument);
  CHECK_THROWS_AS(ts::FreeMass(0), std::invalid_argument);
}
