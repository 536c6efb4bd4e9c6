// Rayleigh damping C = a0 M + a1 K from two modal damping ratios (Chopra, Dynamics of
// Structures, 4th ed., §11.4.1): the modal ratio of mode n is
//   zeta_n = a0 / (2 omega_n) + a1 omega_n / 2,
// and the two chosen modes fix a0 and a1. Frequencies come from K phi = omega^2 M phi.
#pragma once

#include <Eigen/Dense>

namespace nsb::models {

struct RayleighDamping {
  double a0 = 0.0, a1 = 0.0;  // C = a0 M + a1 K  [1/s, s]
  Eigen::VectorXd omega;      // natural circular frequencies, sorted ascending [rad/s]
};

// Modes are 1-based. Throws std::invalid_argument on bad sizes, non-symmetric K or M,
// non-SPD M, K not positive semi-definite, modes out of range, ratios < 0, equal modes or
// equal frequencies.
RayleighDamping rayleigh(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K, int mode_i,
                         double zeta_i, int mode_j, double zeta_j);

// Modal damping ratio zeta = phi^T C phi / (2 omega phi^T M phi) of every mode of (M, K) for
// a given C (addition beyond the agreed interface, used by the tests and the bridge docs).
Eigen::VectorXd modal_damping_ratios(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K,
                                     const Eigen::MatrixXd& C);

}  // namespace nsb::models
