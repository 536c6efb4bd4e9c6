// The Rosenbrock method RODAS 4(3) with step-size control, for stiff first-order systems
// (the compliance method's contact springs and dashpots).
#pragma once

// Only the coefficient table of Odeint's rosenbrock4 (Hairer & Wanner's RODAS 4(3)) is
// used: its stepper is built on uBLAS, whose storage in Boost 1.74 calls
// std::allocator::construct, removed in C++20, so it cannot be instantiated here. The
// stepper and controller below are the same algorithm on Eigen vectors.
#include <boost/numeric/odeint/stepper/rosenbrock4.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <utility>

namespace nsb::integrators {

// LU with partial pivoting of an n x n matrix, n <= kMaxSize, and its solves: the very
// floating-point operations of Eigen 3.4's PartialPivLU at these sizes (the unblocked
// factorisation: pivot = the first largest |a_ik| of the column, the column below it divided
// by it, rank-one update of the trailing block; a solve applies the row transpositions, then
// column-wise forward (unit lower) and backward (upper) substitution within one panel of 8,
// skipping exact zeros), so the factors and solutions are the same to the last bit. Written
// out because at n = 6 (the bridge) Eigen's dynamic-size dispatch, and the l1 norm that
// PartialPivLU::compute forms for rcond(), which the stepper never asks, cost more than the
// arithmetic. Storage is fixed-size: no allocation.
class SmallLu {
 public:
  static constexpr int kMaxSize = 8;  // Eigen's triangular-solve panel width

  // Factors a (column-major, n x n, n <= kMaxSize) in place of a copy.
  void compute(const Eigen::MatrixXd& a) {
    n_ = static_cast<int>(a.rows());
    for (int j = 0; j < n_; ++j) {
      for (int i = 0; i < n_; ++i) lu_[j][i] = a(i, j);
    }
    for (int k = 0; k < n_; ++k) {
      int p = k;
      double biggest = std::abs(lu_[k][k]);
      for (int i = k + 1; i < n_; ++i) {
        const double v = std::abs(lu_[k][i]);
        if (v > biggest) biggest = v, p = i;
      }
      perm_[k] = p;
      if (biggest != 0.0) {
        if (p != k) {
          for (int j = 0; j < n_; ++j) std::swap(lu_[j][k], lu_[j][p]);
        }
        const double pivot = lu_[k][k];
        for (int i = k + 1; i < n_; ++i) lu_[k][i] /= pivot;
      }
      for (int j = k + 1; j < n_; ++j) {
        const double ukj = lu_[j][k];
        for (int i = k + 1; i < n_; ++i) lu_[j][i] -= lu_[k][i] * ukj;
      }
    }
  }

  // b := A^-1 b.
  void solve_in_place(Eigen::VectorXd& b) const {
    for (int k = 0; k < n_; ++k) std::swap(b[k], b[perm_[k]]);
    for (int i = 0; i < n_; ++i) {
      if (b[i] == 0.0) continue;
      for (int r = i + 1; r < n_; ++r) b[r] -= b[i] * lu_[i][r];
    }
    for (int i = n_ - 1; i >= 0; --i) {
      if (b[i] == 0.0) continue;
      b[i] /= lu_[i][i];
      for (int r = 0; r < i; ++r) b[r] -= b[i] * lu_[i][r];
    }
  }

 private:
  int n_ = 0;
  double lu_[kMaxSize][kMaxSize] = {};  // lu_[column][row]
  int perm_[kMaxSize] = {};             // row transpositions, in order
};

// One RODAS 4(3) step (Hairer & Wanner 1996, "Solving ODEs II", §IV.7; the coefficients of
// Odeint's rosenbrock4): six stages with one LU of (I / (gamma h) - J) per step, an embedded
// third-order solution for the error estimate, and Odeint's controller (the error norm is
// the RMS of err_i / (atol + rtol max(|x_old,i|, |x_new,i|)); step factor in [1/5, 6]
// with safety 0.9 and Gustafsson's predictive control).
//
// Problem is any first-order system x' = f(t, x) of fixed size that provides
//   void rhs(const State& x, State& dxdt, double t);                    // dxdt = f(t, x)
//   void rhs_and_jacobian(const State& x, double t, State& dxdt,
//                         JacobianMatrix& J, State& dfdt);              // f, df/dx, df/dt
// called directly (no virtual call); every buffer is sized at construction, so a step
// allocates nothing.
template <class Problem>
class Rosenbrock4 {
 public:
  using State = Eigen::VectorXd;
  using JacobianMatrix = Eigen::MatrixXd;

  // n: size of the state; atol, rtol: the error tolerances; max_dt: largest step [s].
  Rosenbrock4(Problem& problem, Eigen::Index n, double atol, double rtol, double max_dt)
      : problem_(problem), atol_(atol), rtol_(rtol), max_dt_(max_dt) {
    for (State* v : {&dxdt_, &dfdt_, &g1_, &g2_, &g3_, &g4_, &g5_, &xtmp_, &dxdtnew_, &xerr_}) {
      *v = State::Zero(n);
    }
    jac_ = JacobianMatrix::Zero(n, n);
    small_ = n <= SmallLu::kMaxSize;
    if (!small_) lu_ = Eigen::PartialPivLU<JacobianMatrix>(n);
  }

  // Tries a step of size dt from (t, x). On success writes xout, advances t and proposes the
  // next dt; on failure proposes a smaller dt. Mirrors odeint::rosenbrock4_controller.
  bool try_step(const State& x, double& t, State& xout, double& dt) {
    do_step(x, t, xout, dt);
    double err = 0.0;
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      const double sk = atol_ + rtol_ * std::max(std::abs(x[i]), std::abs(xout[i]));
      err += xerr_[i] * xerr_[i] / (sk * sk);
    }
    err = std::sqrt(err / static_cast<double>(x.size()));
    if (!std::isfinite(err)) {
      dt *= kMinFactor;
      last_rejected_ = true;
      return false;
    }
    constexpr double safe = 0.9, fac1 = 5.0, fac2 = 1.0 / 6.0;
    double fac = std::max(fac2, std::min(fac1, std::pow(err, 0.25) / safe));
    double dt_new = dt / fac;
    if (err <= 1.0) {
      if (!first_step_) {
        double fac_pred = (dt_old_ / dt) * std::pow(err * err / err_old_, 0.25) / safe;
        fac_pred = std::max(fac2, std::min(fac1, fac_pred));
        fac = std::max(fac, fac_pred);
        dt_new = dt / fac;
      }
      first_step_ = false;
      dt_old_ = dt;
      err_old_ = std::max(0.01, err);
      if (last_rejected_) dt_new = std::min(dt_new, dt);
      t += dt;
      dt = std::min(max_dt_, dt_new);
      last_rejected_ = false;
      return true;
    }
    dt = dt_new;
    last_rejected_ = true;
    return false;
  }

 private:
  static constexpr double kMinFactor = 0.25;  // step cut after a non-finite error estimate

  void do_step(const State& x, double t, State& xout, double dt) {
    const auto& c = coef_;
    problem_.rhs_and_jacobian(x, t, dxdt_, jac_, dfdt_);
    jac_ *= -1.0;
    jac_.diagonal().array() += 1.0 / (c.gamma * dt);
    factor();
    g1_ = dxdt_ + dt * c.d1 * dfdt_;
    solve(g1_);
    xtmp_ = x + c.a21 * g1_;
    problem_.rhs(xtmp_, dxdtnew_, t + c.c2 * dt);
    g2_ = dxdtnew_ + dt * c.d2 * dfdt_ + c.c21 * g1_ / dt;
    solve(g2_);
    xtmp_ = x + c.a31 * g1_ + c.a32 * g2_;
    problem_.rhs(xtmp_, dxdtnew_, t + c.c3 * dt);
    g3_ = dxdtnew_ + dt * c.d3 * dfdt_ + (c.c31 * g1_ + c.c32 * g2_) / dt;
    solve(g3_);
    xtmp_ = x + c.a41 * g1_ + c.a42 * g2_ + c.a43 * g3_;
    problem_.rhs(xtmp_, dxdtnew_, t + c.c4 * dt);
    g4_ = dxdtnew_ + dt * c.d4 * dfdt_ + (c.c41 * g1_ + c.c42 * g2_ + c.c43 * g3_) / dt;
    solve(g4_);
    xtmp_ = x + c.a51 * g1_ + c.a52 * g2_ + c.a53 * g3_ + c.a54 * g4_;
    problem_.rhs(xtmp_, dxdtnew_, t + dt);
    g5_ = dxdtnew_ + (c.c51 * g1_ + c.c52 * g2_ + c.c53 * g3_ + c.c54 * g4_) / dt;
    solve(g5_);
    xtmp_ += g5_;
    problem_.rhs(xtmp_, dxdtnew_, t + dt);
    xerr_ = dxdtnew_ + (c.c61 * g1_ + c.c62 * g2_ + c.c63 * g3_ + c.c64 * g4_ + c.c65 * g5_) / dt;
    solve(xerr_);
    xout = xtmp_ + xerr_;
  }

  // The LU of (I / (gamma h) - J) and its solves: SmallLu up to its size, Eigen's beyond.
  void factor() {
    if (small_) {
      small_lu_.compute(jac_);
    } else {
      lu_.compute(jac_);
    }
  }
  void solve(State& b) const {
    if (small_) {
      small_lu_.solve_in_place(b);
    } else {
      b = lu_.solve(b);
    }
  }

  Problem& problem_;
  const boost::numeric::odeint::default_rosenbrock_coefficients<double> coef_;
  double atol_, rtol_, max_dt_;
  bool first_step_ = true, last_rejected_ = false;
  double err_old_ = 0.0, dt_old_ = 0.0;
  State dxdt_, dfdt_, g1_, g2_, g3_, g4_, g5_, xtmp_, dxdtnew_, xerr_;
  JacobianMatrix jac_;
  bool small_ = false;
  SmallLu small_lu_;
  Eigen::PartialPivLU<JacobianMatrix> lu_;
};

}  // namespace nsb::integrators
