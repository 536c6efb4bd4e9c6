// Rayleigh damping: a 2-DOF case by hand and the modal ratios of random systems.
#include "models/rayleigh.hpp"

#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

using nsb::models::rayleigh;

namespace {

// Closed-form coefficients and eigenvalues of well-conditioned small problems agree to
// round-off.
constexpr double kHandTolerance = 1e-12;
// Random 6-DOF systems with condition numbers up to ~1e4: the modal ratios are recovered
// to round-off amplified by the conditioning.
constexpr double kModalTolerance = 1e-8;

Eigen::MatrixXd random_spd(int n, std::mt19937& rng, double spread) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = u(rng);
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(A);
  const Eigen::MatrixXd Q = qr.householderQ();
  Eigen::VectorXd d(n);
  for (int i = 0; i < n; ++i) d(i) = std::pow(spread, static_cast<double>(i) / (n - 1));
  return Q * d.asDiagonal() * Q.transpose();
}

void expect_error(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K, int i, double zi, int j,
                  double zj, const std::string& fragment) {
  try {
    rayleigh(M, K, i, zi, j, zj);
    FAIL("expected std::invalid_argument containing " << fragment);
  } catch (const std::invalid_argument& e) {
    INFO("message: " << e.what());
    CHECK(std::string(e.what()).find(fragment) != std::string::npos);
  }
}

}  // namespace

TEST_CASE("rayleigh: 2-DOF system by hand") {
  // M = diag(2, 1), K = [[3, -1], [-1, 1]]: det(K - l M) = 2 l^2 - 5 l + 2 = 0, l = 1/2 and 2,
  // so w1 = 1/sqrt(2) = 0.70711 and w2 = sqrt(2) = 1.41421 rad/s.
  Eigen::MatrixXd M(2, 2), K(2, 2);
  M << 2, 0, 0, 1;
  K << 3, -1, -1, 1;
  const double w1 = 1.0 / std::sqrt(2.0), w2 = std::sqrt(2.0);
  // Equal ratios 5 %: a0 = 2 z w1 w2 / (w1 + w2) = 0.1 / (3/sqrt 2) = 0.0471405,
  // a1 = 2 z / (w1 + w2) = 0.0471405 (w1 w2 = 1).
  auto r = rayleigh(M, K, 1, 0.05, 2, 0.05);
  REQUIRE(r.omega.size() == 2);
  CHECK(r.omega(0) == doctest::Approx(w1).epsilon(kHandTolerance));
  CHECK(r.omega(1) == doctest::Approx(w2).epsilon(kHandTolerance));
  CHECK(r.a0 == doctest::Approx(0.1 * std::sqrt(2.0) / 3.0).epsilon(kHandTolerance));
  CHECK(r.a1 == doctest::Approx(0.1 * std::sqrt(2.0) / 3.0).epsilon(kHandTolerance));
  CHECK(r.a0 == doctest::Approx(0.0471405).epsilon(1e-6));
  // 2 % and 5 %: a0 = 2 w1 w2 (z1 w2 - z2 w1)/(w2^2 - w1^2) = 2 (0.0282843 - 0.0353553)/1.5
  // = -0.0094281; a1 = 2 (z2 w2 - z1 w1)/1.5 = 2 (0.0707107 - 0.0141421)/1.5 = 0.0754247.
  r = rayleigh(M, K, 2, 0.05, 1, 0.02);  // the order of the two modes does not matter
  CHECK(r.a0 == doctest::Approx(-0.0094281).epsilon(1e-5));
  CHECK(r.a1 == doctest::Approx(0.0754247).epsilon(1e-6));
  const Eigen::MatrixXd C = r.a0 * M + r.a1 * K;
  const auto zeta = nsb::models::modal_damping_ratios(M, K, C);
  CHECK(zeta(0) == doctest::Approx(0.02).epsilon(kHandTolerance));
  CHECK(zeta(1) == doctest::Approx(0.05).epsilon(kHandTolerance));
}

TEST_CASE("rayleigh: the chosen modes get the requested ratios (random systems)") {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> z(0.0, 0.2);
  for (int trial = 0; trial < 50; ++trial) {
    const int n = 6;
    const Eigen::MatrixXd M = random_spd(n, rng, 10.0) * 140.5;
    const Eigen::MatrixXd K = random_spd(n, rng, 1e3) * 2.5e4;
    const int i = 1 + trial % n, j = 1 + (trial + 2) % n;
    const double zi = z(rng), zj = z(rng);
    const auto r = rayleigh(M, K, i, zi, j, zj);
    const Eigen::MatrixXd C = r.a0 * M + r.a1 * K;
    // Independent modal analysis in the test: zeta_n = phi^T C phi / (2 w phi^T M phi).
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
    for (int k = 0; k < n; ++k) {
      const Eigen::VectorXd phi = es.eigenvectors().col(k);
      const double w = std::sqrt(es.eigenvalues()(k));
      CHECK(r.omega(k) == doctest::Approx(w).epsilon(kModalTolerance));
      const double zeta_k = phi.dot(C * phi) / (2.0 * w * phi.dot(M * phi));
      // Every mode follows zeta = a0/(2w) + a1 w/2 (Chopra eq. 11.4.8) ...
      CHECK(zeta_k == doctest::Approx(r.a0 / (2 * w) + r.a1 * w / 2).epsilon(kModalTolerance));
      if (k + 1 == i) CHECK(zeta_k == doctest::Approx(zi).epsilon(kModalTolerance).scale(0.01));
      if (k + 1 == j) CHECK(zeta_k == doctest::Approx(zj).epsilon(kModalTolerance).scale(0.01));
      // ... and C is diagonal in the modal basis.
      for (int l = k + 1; l < n; ++l) {
        const Eigen::VectorXd psi = es.eigenvectors().col(l);
        CHECK(std::abs(phi.dot(C * psi)) <= kModalTolerance * (std::abs(phi.dot(C * phi)) + 1.0));
      }
    }
    CHECK(r.omega(0) <= r.omega(n - 1));
  }
}

TEST_CASE("rayleigh: equal ratios on modes 1 and 3 leave mode 2 less damped") {
  // Rayleigh's zeta(w) = a0/(2w) + a1 w/2 is convex with equal values at w1 and w3, hence
  // smaller in between (the bridge uses 8 % on modes 1 and 3).
  Eigen::MatrixXd M = Eigen::Vector3d(140.5, 140.5, 13090.0).asDiagonal();
  Eigen::MatrixXd K(3, 3);
  K << 7.9e4, 0, 0, 0, 7.9e4, 3.0e5, 0, 3.0e5, 6.0e6;
  const auto r = rayleigh(M, K, 1, 0.08, 3, 0.08);
  const auto zeta = nsb::models::modal_damping_ratios(M, K, r.a0 * M + r.a1 * K);
  CHECK(zeta(0) == doctest::Approx(0.08).epsilon(kModalTolerance));
  CHECK(zeta(2) == doctest::Approx(0.08).epsilon(kModalTolerance));
  CHECK(zeta(1) < 0.08);
  CHECK(r.a0 > 0.0);
  CHECK(r.a1 > 0.0);
}

TEST_CASE("rayleigh: bad input throws with a reason") {
  Eigen::MatrixXd M = Eigen::Matrix2d::Identity(), K(2, 2);
  K << 2, -1, -1, 2;
  expect_error(M, Eigen::MatrixXd::Identity(3, 3), 1, 0.05, 2, 0.05, "equal size");
  expect_error(Eigen::MatrixXd(0, 0), Eigen::MatrixXd(0, 0), 1, 0.05, 2, 0.05, "non-empty");
  Eigen::MatrixXd bad_m = M;
  bad_m(1, 1) = -1.0;
  expect_error(bad_m, K, 1, 0.05, 2, 0.05, "positive definite");
  Eigen::MatrixXd nonsym = K;
  nonsym(0, 1) = 0.0;
  expect_error(M, nonsym, 1, 0.05, 2, 0.05, "K must be symmetric");
  Eigen::MatrixXd indefinite = K;
  indefinite(0, 0) = -5.0;
  expect_error(M, indefinite, 1, 0.05, 2, 0.05, "semi-definite");
  expect_error(M, K, 1, -0.01, 2, 0.05, "zeta_i");
  expect_error(M, K, 1, 0.05, 2, std::nan(""), "zeta_j");
  expect_error(M, K, 2, 0.05, 2, 0.05, "must differ");
  expect_error(M, K, 0, 0.05, 2, 0.05, "mode_i");
  expect_error(M, K, 1, 0.05, 3, 0.05, "mode_j");
  expect_error(M, Eigen::Matrix2d::Identity(), 1, 0.05, 2, 0.05, "distinct");
}
