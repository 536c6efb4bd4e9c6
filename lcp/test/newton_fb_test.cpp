// Newton–Fischer–Burmeister: the Jacobian element against finite differences, the degenerate
// (0, 0) case, quadratic convergence on nondegenerate P-matrix problems, failures and edges.
#include "lcp/newton_fb.hpp"
#include "lcp/test/problems.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <sstream>

using namespace nsb::lcp;
using nsb::lcp::testing::relative_distance;

namespace {
// Central differences with step 1e-6 on O(1) data: truncation ~1e-12 * phi''' plus
// cancellation ~1e-16 / 1e-6 = 1e-10; 1e-7 leaves a wide margin for curvature near kinks.
constexpr double kFiniteDifference = 1e-7;
constexpr double kStep = 1e-6;
}  // namespace

TEST_CASE("the Jacobian element matches finite differences away from kinks") {
  std::mt19937 rng(21);
  for (int trial = 0; trial < 50; ++trial) {
    const int n = 1 + trial % 8;
    Problem p;
    p.M = testing::p_matrix(rng, n);
    p.q = testing::random_vector(rng, n);
    const Vector z = testing::random_vector(rng, n, -1.0, 1.0);
    Vector phi;
    Matrix H;
    fischer_burmeister(p, z, phi, H);
    for (int j = 0; j < n; ++j) {
      Vector zp = z, zm = z;
      zp(j) += kStep;
      zm(j) -= kStep;
      Vector fp, fm;
      Matrix dummy;
      fischer_burmeister(p, zp, fp, dummy);
      fischer_burmeister(p, zm, fm, dummy);
      const Vector fd = (fp - fm) / (2 * kStep);
      INFO("trial " << trial << ", column " << j);
      CHECK((fd - H.col(j)).lpNorm<Eigen::Infinity>() < kFiniteDifference);
    }
  }
}

TEST_CASE("the degenerate (0, 0) case uses the directional limit along the indicator c") {
  // M = I, q = (0, -1), z = (0, 0.5): w = (0, -0.5), so (z_0, w_0) = (0, 0).
  // c = e_0, M c = e_0, s = sqrt(2): D_a = D_b = 1/sqrt(2) - 1, H(0, 0) = sqrt(2) - 2.
  // This is the one-sided derivative of phi(t, t) = sqrt(2) t - 2 t along c.
  Problem p;
  p.M = Matrix::Identity(2, 2);
  p.q = (Vector(2) << 0.0, -1.0).finished();
  const Vector z = (Vector(2) << 0.0, 0.5).finished();
  Vector phi;
  Matrix H;
  fischer_burmeister(p, z, phi, H);
  CHECK(phi(0) == 0.0);
  CHECK(H(0, 0) == doctest::Approx(std::sqrt(2.0) - 2.0).epsilon(1e-15));
  CHECK(H(0, 1) == 0.0);
  // Row 1 is smooth: (z, w) = (0.5, -0.5), r = sqrt(0.5): D_a = 0.5/r - 1, D_b = -0.5/r - 1.
  const double r = std::sqrt(0.5);
  CHECK(H(1, 1) == doctest::Approx((0.5 / r - 1.0) + (-0.5 / r - 1.0)).epsilon(1e-15));
  // One-sided difference along c confirms H c.
  Vector zt = z;
  zt(0) += kStep;
  Vector phit;
  Matrix dummy;
  fischer_burmeister(p, zt, phit, dummy);
  CHECK(std::abs((phit(0) - phi(0)) / kStep - H(0, 0)) < kFiniteDifference);
  // And Newton solves this degenerate problem: z = (0, 1) is the solution.
  const Result s = newton_fb(p);
  REQUIRE(s.ok());
  CHECK(relative_distance(s.z, (Vector(2) << 0.0, 1.0).finished()) < 1e-12);
}

TEST_CASE("quadratic convergence on nondegenerate P-matrix problems (iteration history)") {
  std::mt19937 rng(1996);
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 5 + trial % 20;
    // Strict complementarity (no z_i = w_i = 0) and a P-matrix: the solution is a BD-regular
    // point, where semismooth Newton converges quadratically (De Luca et al. 1996, Thm 11).
    const auto m = testing::manufacture(rng, testing::p_matrix(rng, n), 0.0);
    NewtonFbOptions o;
    o.record_history = true;
    o.tolerance = 1e-15;  // run into the quadratic regime before stopping
    o.polish = false;     // show the pure Newton rate
    const Result r = newton_fb(m.problem, o);
    std::ostringstream h;
    for (double v : r.history) h << ' ' << v;
    INFO("trial " << trial << ", n = " << n << ", residual history:" << h.str());
    if (trial == 0) MESSAGE("Newton-FB residual history, n = " << n << ":" << h.str());
    REQUIRE(r.status == Status::kSolved);
    CHECK(relative_distance(r.z, m.z) < 1e-12);
    // Quadratic rate: once the residual is below 1e-3, each step at least squares it up to a
    // constant, r_{k+1} <= C r_k^2. C = 1e3 bounds ||H^-1|| times the curvature of phi for
    // these O(1) P-matrices with a wide margin; a linear rate would fail it within one step.
    int checked = 0;
    for (std::size_t k = 0; k + 1 < r.history.size(); ++k) {
      const double a = r.history[k];
      const double b = r.history[k + 1];
      if (a < 1e-3 && a > 1e-12) {
        CHECK(b <= 1e3 * a * a + 1e-15);
        ++checked;
      }
    }
    CHECK(checked >= 1);
  }
}

TEST_CASE("symmetric positive definite problems take few Newton steps") {
  std::mt19937 rng(5);
  int worst = 0;
  for (int trial = 0; trial < 30; ++trial) {
    const int n = 10 + trial;
    const double cond = std::pow(10.0, trial % 7);
    const auto m = testing::manufacture(rng, testing::spd(rng, n, cond));
    const Result r = newton_fb(m.problem);
    INFO("trial " << trial << ", n = " << n << ", cond = " << cond);
    REQUIRE(r.ok());
    CHECK(testing::lcp_violations(m.problem, r.z, 1e-11).empty());
    worst = std::max(worst, r.iterations);
  }
  MESSAGE("most Newton-FB steps on SPD problems, cond 1 to 1e6: " << worst);
  CHECK(worst <= NewtonFbOptions{}.max_iterations);
}

TEST_CASE("failures are statuses: no solution, iteration limit") {
  Problem p;
  p.M = -Matrix::Identity(3, 3);
  p.q = -Vector::Ones(3);
  const Result r = newton_fb(p);  // infeasible: w = -z - e < 0
  CHECK_FALSE(r.ok());
  CHECK(r.status != Status::kNotRun);

  std::mt19937 rng(3);
  const auto m = testing::manufacture(rng, testing::p_matrix(rng, 8));
  NewtonFbOptions o;
  o.max_iterations = 1;
  const Result one = newton_fb(m.problem, o);
  CHECK(one.status == Status::kMaxIterations);
  CHECK(one.iterations == 1);
  // Warm start at the solution: solved at once.
  const Result warm = newton_fb(m.problem, {}, m.z);
  CHECK(warm.ok());
  CHECK(warm.iterations == 0);
  NewtonFbOptions bad;
  bad.armijo = 0.7;
  CHECK_THROWS_WITH_AS(newton_fb(m.problem, bad), doctest::Contains("armijo"),
                       std::invalid_argument);
}

// A Newton step solves a linear system only on the rows with D_b,ii != 0: a component with
// z_i = 0 and w_i > 0 has the row -d_i = -Phi_i = 0. The step must be the full system's,
// H d = -Phi with H from fischer_burmeister() and a dense LU of all n rows.
TEST_CASE("the Newton step on the reduced rows is the full system's step") {
  // Both directions come from LUs of matrices with cond ~ 1e2: agreement to ~1e-14 times that.
  constexpr double kSameStep = 1e-11;
  std::mt19937 rng(31);
  for (Eigen::Index n : {3, 8, 12, 13, 40}) {
    for (int k = 0; k < 3; ++k) {
      INFO("n = " << n << ", problem " << k);
      const auto m = testing::manufacture(rng, testing::p_matrix(rng, n), 0.0);
      // Start near the solution: the support perturbed by 1e-3, the rest exactly 0 (there
      // w_i >= 0.1 before the perturbation, which moves it by less than that).
      Vector start = m.z;
      Eigen::Index fixed = 0;
      for (Eigen::Index i = 0; i < n; ++i) {
        if (m.z(i) > 0.0) {
          start(i) *= 1.0 + 1e-3 * (i % 2 == 0 ? 1.0 : -1.0);
        } else {
          ++fixed;
        }
      }
      const Vector w = m.problem.M * start + m.problem.q;
      for (Eigen::Index i = 0; i < n; ++i)
        if (start(i) == 0.0) REQUIRE(w(i) > 0.0);
      Vector phi;
      Matrix H;
      fischer_burmeister(m.problem, start, phi, H);
      const Vector full = start + H.partialPivLu().solve(-phi);
      NewtonFbOptions one;
      one.max_iterations = 1;
      one.polish = false;
      const Result r = newton_fb(m.problem, one, start);
      REQUIRE(r.iterations == 1);
      CHECK(relative_distance(r.z, full) <= kSameStep);
      CHECK(fixed > 0);  // the reduced system did run
    }
  }
}

TEST_CASE("edges: n = 0, n = 1 by hand, a reused solver across the two workspaces") {
  NewtonFb solver;
  Result r;
  solver.solve(Problem{}, NewtonFbOptions{}, r);
  CHECK(r.ok());
  CHECK(r.z.size() == 0);
  // n = 1: M = [2], q = (-4): z = 2.
  Problem one;
  one.M = (Matrix(1, 1) << 2).finished();
  one.q = (Vector(1) << -4).finished();
  solver.solve(one, NewtonFbOptions{}, r);
  REQUIRE(r.ok());
  CHECK(r.z(0) == doctest::Approx(2.0).epsilon(1e-15));
  std::mt19937 rng(32);
  for (Eigen::Index n : {12, 13, 12, 60, 5}) {
    INFO("n = " << n);
    const auto m = testing::manufacture(rng, testing::spd(rng, n, 1e3), 0.0);
    solver.solve(m.problem, NewtonFbOptions{}, r);
    REQUIRE(r.ok());
    CHECK(testing::lcp_violations(m.problem, r.z, 1e-11).empty());
    CHECK(r.residual == residual(m.problem.M, m.problem.q, r.z));
  }
}
