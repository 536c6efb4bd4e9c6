// Problem generators shared by the LCP tests and the LCP verification checks.
//
// Every generator takes an explicit std::mt19937 so that a failure reproduces from its seed.
#pragma once

#include "lcp/frictional.hpp"
#include "lcp/lcp.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace nsb::lcp::testing {

inline Vector random_vector(std::mt19937& rng, Eigen::Index n, double lo = -1.0,
                            double hi = 1.0) {
  std::uniform_real_distribution<double> u(lo, hi);
  Vector v(n);
  for (Eigen::Index i = 0; i < n; ++i) v(i) = u(rng);
  return v;
}

inline Matrix random_matrix(std::mt19937& rng, Eigen::Index rows, Eigen::Index cols) {
  std::normal_distribution<double> g(0.0, 1.0);
  Matrix A(rows, cols);
  for (Eigen::Index j = 0; j < cols; ++j)
    for (Eigen::Index i = 0; i < rows; ++i) A(i, j) = g(rng);
  return A;
}

// A random orthogonal matrix (QR of a Gaussian matrix).
inline Matrix random_orthogonal(std::mt19937& rng, Eigen::Index n) {
  const Eigen::HouseholderQR<Matrix> qr(random_matrix(rng, n, n));
  return qr.householderQ() * Matrix::Identity(n, n);
}

// Symmetric positive definite with eigenvalues log-spaced in [scale / cond, scale], so
// cond_2(M) = cond exactly (up to round-off).
inline Matrix spd(std::mt19937& rng, Eigen::Index n, double cond, double scale = 1.0) {
  const Matrix Q = random_orthogonal(rng, n);
  Vector eig(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = n > 1 ? static_cast<double>(i) / static_cast<double>(n - 1) : 0.0;
    eig(i) = scale * std::pow(cond, -t);
  }
  Matrix M = Q * eig.asDiagonal() * Q.transpose();
  return 0.5 * (M + M.transpose());
}

// Nonsymmetric P-matrix: S + K with S symmetric positive definite and K skew-symmetric, so
// x^T M x = x^T S x > 0 for x != 0 (positive definite, hence every principal minor > 0).
inline Matrix p_matrix(std::mt19937& rng, Eigen::Index n, double cond = 10.0) {
  const Matrix A = random_matrix(rng, n, n);
  return spd(rng, n, cond) + 0.5 * (A - A.transpose());
}

// Singular positive semidefinite of rank r < n: B B^T with B n x r.
inline Matrix singular_psd(std::mt19937& rng, Eigen::Index n, Eigen::Index rank) {
  const Matrix B = random_matrix(rng, n, rank);
  return B * B.transpose() / static_cast<double>(rank);
}

// A manufactured LCP: z* and w* with complementary supports (each index is in exactly one
// support, or in neither with probability `degenerate`), q = w* - M z*.
struct Manufactured {
  Problem problem;
  Vector z;
  Vector w;
};

inline Manufactured manufacture(std::mt19937& rng, const Matrix& M, double degenerate = 0.0,
                                double magnitude = 1.0) {
  const Eigen::Index n = M.rows();
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Manufactured m;
  m.z = Vector::Zero(n);
  m.w = Vector::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double pick = u(rng);
    if (pick < degenerate) continue;  // z_i = w_i = 0
    const double value = magnitude * (0.1 + u(rng));
    if (pick < degenerate + 0.5 * (1.0 - degenerate)) {
      m.z(i) = value;
    } else {
      m.w(i) = value;
    }
  }
  m.problem.M = M;
  m.problem.q = m.w - M * m.z;
  return m;
}

// A planar rigid body (mass, inertia) with contact points on its boundary, and the contact
// problem of an impact at those points: W_N and W_T columns from the point's lever arm r
// and the unit normal n (t = n rotated by +90 degrees), W = [n; r x n], G = W^T M^-1 W
// (eq. 8), pre-impact contact velocities gdot- = W^T u- for a random u-.
struct RigidBodyImpact {
  FrictionalProblem problem;
  Eigen::Matrix3d mass = Eigen::Matrix3d::Identity();
  Matrix W_n;  // 3 x m
  Matrix W_t;  // 3 x m
  Eigen::Vector3d u_minus = Eigen::Vector3d::Zero();
};

inline RigidBodyImpact rigid_body_impact(std::mt19937& rng, int contacts, double restitution,
                                         double friction, bool approaching = true) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  RigidBodyImpact b;
  const double mass = 0.5 + 2.0 * u(rng);
  const double length = 0.5 + 2.0 * u(rng);
  const double width = 0.2 + u(rng);
  const double inertia = mass * (length * length + width * width) / 12.0;
  b.mass.diagonal() << mass, mass, inertia;
  b.W_n.resize(3, contacts);
  b.W_t.resize(3, contacts);
  for (int i = 0; i < contacts; ++i) {
    // Corners of a rectangle with a small random normal tilt (skewed faces).
    const double sx = (i / 2) % 2 == 0 ? 1.0 : -1.0;
    const double sy = i % 2 == 0 ? 1.0 : -1.0;
    const Eigen::Vector2d r(sx * length / 2, sy * width / 2);
    const double angle = (sx > 0 ? std::numbers::pi : 0.0) + 0.6 * (u(rng) - 0.5);
    const Eigen::Vector2d n(std::cos(angle), std::sin(angle));
    const Eigen::Vector2d t(-n.y(), n.x());
    b.W_n.col(i) << n, r.x() * n.y() - r.y() * n.x();
    b.W_t.col(i) << t, r.x() * t.y() - r.y() * t.x();
  }
  Matrix W(3, 2 * contacts);
  W << b.W_n, b.W_t;
  const Eigen::Matrix3d Minv = b.mass.inverse();
  b.u_minus = random_vector(rng, 3, -1.0, 1.0);
  if (approaching) {
    // Make the first contact close: subtract enough of its normal direction.
    const Eigen::Vector3d dir = Minv * b.W_n.col(0);
    const double g0 = b.W_n.col(0).dot(b.u_minus);
    b.u_minus -= (g0 + 0.5 + u(rng)) / b.W_n.col(0).dot(dir) * dir;
  }
  FrictionalProblem& p = b.problem;
  if (friction == 0.0) {
    p.delassus = b.W_n.transpose() * Minv * b.W_n;
    p.gdot_free = b.W_n.transpose() * b.u_minus;
  } else {
    p.delassus = W.transpose() * Minv * W;
    p.gdot_free = W.transpose() * b.u_minus;
  }
  p.gdot_n_minus = b.W_n.transpose() * b.u_minus;
  p.restitution = Vector::Constant(contacts, restitution);
  p.friction = Vector::Constant(contacts, friction);
  return b;
}

// Checks the three LCP conditions directly (not through lcp::residual), each scaled by
// (1 + ||q||_inf): z >= -tol, w >= -tol, |z_i w_i| <= tol (1 + |z_i| + |w_i|).
// Returns "" when they hold, else a description of every violated entry.
inline std::string lcp_violations(const Problem& p, const Vector& z, double tol) {
  std::ostringstream s;
  if (z.size() != p.size()) {
    s << "z has size " << z.size() << ", expected " << p.size();
    return s.str();
  }
  const Vector w = p.M * z + p.q;
  const double scale = 1.0 + p.q.lpNorm<Eigen::Infinity>();
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    if (!std::isfinite(z(i))) s << " z(" << i << ") not finite;";
    if (z(i) < -tol * scale) s << " z(" << i << ") = " << z(i) << " < 0;";
    if (w(i) < -tol * scale) s << " w(" << i << ") = " << w(i) << " < 0;";
    if (std::abs(z(i) * w(i)) > tol * scale * (1.0 + std::abs(z(i)) + std::abs(w(i))))
      s << " z(" << i << ") w(" << i << ") = " << z(i) << " * " << w(i) << " != 0;";
  }
  return s.str();
}

// Relative distance ||a - b||_inf / (1 + ||b||_inf).
inline double relative_distance(const Vector& a, const Vector& b) {
  if (a.size() != b.size()) return std::numeric_limits<double>::infinity();
  return (a - b).lpNorm<Eigen::Infinity>() / (1.0 + b.lpNorm<Eigen::Infinity>());
}

}  // namespace nsb::lcp::testing
