#include "models/rayleigh.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace nsb::models {
namespace {

// Symmetry is checked relative to the largest entry: assembled matrices carry round-off.
constexpr double kSymmetryTolerance = 1e-10;
// Two frequencies closer than this (relative) cannot fix two Rayleigh coefficients: the
// 2x2 system below becomes singular.
constexpr double kDistinctFrequencyTolerance = 1e-9;
// K may be singular (a free rigid-body mode) but not indefinite; round-off in the eigenvalue
// solver is of the order of eps * ||K|| / ||M||.
constexpr double kNegativeEigenvalueTolerance = 1e-10;

void check_symmetric(const Eigen::MatrixXd& A, const char* name) {
  const double scale = A.cwiseAbs().maxCoeff();
  if (!((A - A.transpose()).cwiseAbs().maxCoeff() <= kSymmetryTolerance * scale)) {
    throw std::invalid_argument(std::string("rayleigh: ") + name +
                                " must be symmetric with finite entries");
  }
}

// Generalized eigenvalues of K phi = lambda M phi, ascending, after the argument checks.
Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solve_modes(
    const Eigen::MatrixXd& M, const Eigen::MatrixXd& K) {
  if (M.rows() == 0 || M.rows() != M.cols() || K.rows() != M.rows() || K.cols() != M.cols()) {
    throw std::invalid_argument("rayleigh: M and K must be square, non-empty and of equal size (M is " +
                                std::to_string(M.rows()) + "x" + std::to_string(M.cols()) +
                                ", K is " + std::to_string(K.rows()) + "x" +
                                std::to_string(K.cols()) + ")");
  }
  check_symmetric(M, "M");
  check_symmetric(K, "K");
  Eigen::LLT<Eigen::MatrixXd> llt(M);
  if (llt.info() != Eigen::Success) {
    throw std::invalid_argument("rayleigh: M must be symmetric positive definite");
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
  if (es.info() != Eigen::Success) {
    throw std::invalid_argument("rayleigh: the eigenproblem K phi = w^2 M phi did not converge");
  }
  const double lambda_scale = std::max(1.0, es.eigenvalues().cwiseAbs().maxCoeff());
  if (es.eigenvalues()(0) < -kNegativeEigenvalueTolerance * lambda_scale) {
    throw std::invalid_argument("rayleigh: K must be positive semi-definite");
  }
  return es;
}

}  // namespace

RayleighDamping rayleigh(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K, int mode_i,
                         double zeta_i, int mode_j, double zeta_j) {
  const auto es = solve_modes(M, K);
  const int n = static_cast<int>(M.rows());
  if (mode_i < 1 || mode_i > n) {
    throw std::invalid_argument("rayleigh: mode_i = " + std::to_string(mode_i) +
                                " must be in [1, " + std::to_string(n) + "]");
  }
  if (mode_j < 1 || mode_j > n) {
    throw std::invalid_argument("rayleigh: mode_j = " + std::to_string(mode_j) +
                                " must be in [1, " + std::to_string(n) + "]");
  }
  if (mode_i == mode_j) {
    throw std::invalid_argument("rayleigh: mode_i and mode_j must differ");
  }
  if (!(zeta_i >= 0.0) || !std::isfinite(zeta_i)) {
    throw std::invalid_argument("rayleigh: zeta_i must be finite and >= 0");
  }
  if (!(zeta_j >= 0.0) || !std::isfinite(zeta_j)) {
    throw std::invalid_argument("rayleigh: zeta_j must be finite and >= 0");
  }
  RayleighDamping out;
  out.omega = es.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  const double wi = out.omega(mode_i - 1);
  const double wj = out.omega(mode_j - 1);
  if (!(std::abs(wj - wi) > kDistinctFrequencyTolerance * std::max(wi, wj)) || wi <= 0.0 ||
      wj <= 0.0) {
    throw std::invalid_argument(
        "rayleigh: the chosen modes must have distinct, non-zero frequencies");
  }
  // Chopra eq. (11.4.8): zeta_n = a0/(2 w_n) + a1 w_n/2 for n = i, j, solved in closed form.
  const double den = wj * wj - wi * wi;
  out.a0 = 2.0 * wi * wj * (zeta_i * wj - zeta_j * wi) / den;
  out.a1 = 2.0 * (zeta_j * wj - zeta_i * wi) / den;
  return out;
}

Eigen::VectorXd modal_damping_ratios(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K,
                                     const Eigen::MatrixXd& C) {
  const auto es = solve_modes(M, K);
  if (C.rows() != M.rows() || C.cols() != M.cols()) {
    throw std::invalid_argument("modal_damping_ratios: C must have the size of M");
  }
  const Eigen::Index n = M.rows();
  Eigen::VectorXd zeta(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::VectorXd phi = es.eigenvectors().col(k);
    const double w = std::sqrt(std::max(es.eigenvalues()(k), 0.0));
    const double mass = phi.dot(M * phi);
    zeta(k) = w > 0.0 ? phi.dot(C * phi) / (2.0 * w * mass)
                      : std::numeric_limits<double>::infinity();
  }
  return zeta;
}

}  // namespace nsb::models
