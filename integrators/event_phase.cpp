#include "integrators/event_integrator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace nsb::integrators::detail {

// The reduced system of the closed contacts, A lambda = rhs with A = (R^T M^-1) B, by a
// complete orthogonal decomposition (A is singular when closed contacts are redundant), and
// udot = a_free + M^-1 (B lambda). Up to kSmallClosed unknowns the matrices have fixed
// maximum sizes (storage inside the objects), so the decomposition and its solve allocate
// nothing; the larger case keeps one workspace whose size changes only with k.
template <class SquareMatrix>
void EventDriven::solve_closed(int k, SquareMatrix& a,
                               Eigen::CompleteOrthogonalDecomposition<SquareMatrix>& cod) {
  using Column =
      Eigen::Matrix<double, Eigen::Dynamic, 1, 0, SquareMatrix::MaxRowsAtCompileTime, 1>;
  a.resize(k, k);
  a.noalias() = phase_rt_minv_.topRows(k) * phase_b_.leftCols(k);
  Column rhs(k);
  rhs.noalias() = phase_r_.leftCols(k).transpose() * phase_a_free_;
  rhs = -(rhs + phase_wbar_.head(k));
  cod.compute(a);
  const Column lambda = cod.solve(rhs);
  phase_lambda_.head(k) = lambda;
  phase_b_lambda_.noalias() = phase_b_.leftCols(k) * lambda;
  udot_ = phase_a_free_;
  udot_.noalias() += minv_ * phase_b_lambda_;
}

// Unknowns of the closed contacts: lambda_N of each, and lambda_T of each sticking one.
int EventDriven::closed_unknowns() const {
  int k = 0;
  for (const auto& md : modes_) {
    if (closed(md)) ++k;
    if (md == ContactState::kStick) ++k;
  }
  return k;
}

// Accelerations and contact forces with the modes of the current phase held fixed:
//   M udot = f + sum_closed B_i lambda_N,i + sum_stick W_T,i lambda_T,i
// with B_i = W_N,i for sticking and B_i = W_N,i - mu_i s_i W_T,i for sliding contacts, and
// the constraints gddot_N,i = W_N,i^T udot + wbar_N,i = 0 (closed) and
// gddot_T,i = W_T,i^T udot + wbar_T,i = 0 (sticking). Redundant constraints (four corners
// closed on a three-DOF deck) give a singular system; its minimum-norm solution is one
// admissible distribution of the forces.
void EventDriven::phase_forces(double t, const Vector& q, const Vector& u) {
  sys_.forces(t, q, u, f_);
  lambda_n_.setZero();
  lambda_t_.setZero();
  const int k = closed_unknowns();
  if (k == 0) {
    udot_.noalias() = minv_ * f_;
    return;
  }
  sys_.contact_data(t, q, u, cbuf_);
  // Columns of the closed contacts into the workspace sized once for every contact (n x 2m):
  // the right-hand side of every smooth-phase step runs this, so nothing here allocates.
  auto B = phase_b_.leftCols(k);
  auto R = phase_r_.leftCols(k);
  int j = 0;
  for (int i = 0; i < m_; ++i) {
    const auto& md = modes_[idx(i)];
    const auto& c = cbuf_[idx(i)];
    if (!closed(md)) continue;
    R.col(j) = c.w_normal;
    B.col(j) = c.w_normal;
    if (sliding(md)) {
      B.col(j) -= c.friction * slip_sign(md) * c.w_tangent;
    }
    phase_wbar_[j] = c.wbar_normal;
    ++j;
    if (md == ContactState::kStick) {
      R.col(j) = c.w_tangent;
      B.col(j) = c.w_tangent;
      phase_wbar_[j] = c.wbar_tangent;
      ++j;
    }
  }
  phase_a_free_.noalias() = minv_ * f_;
  // A = (R^T M^-1) B and rhs = -(R^T a_free + wbar), evaluated in that order.
  auto rt_minv = phase_rt_minv_.topRows(k);
  rt_minv.noalias() = R.transpose() * minv_;
  if (k <= kSmallClosed) {
    solve_closed(k, phase_small_, phase_small_cod_);
  } else {
    solve_closed(k, phase_large_, phase_large_cod_);
  }
  j = 0;
  for (int i = 0; i < m_; ++i) {
    const auto& md = modes_[idx(i)];
    if (!closed(md)) continue;
    lambda_n_[i] = phase_lambda_[j++];
    if (md == ContactState::kStick) {
      lambda_t_[i] = phase_lambda_[j++];
    } else if (sliding(md)) {
      lambda_t_[i] = -cbuf_[idx(i)].friction * slip_sign(md) * lambda_n_[i];
    }
  }
}

// The right-hand side of the smooth phase: d/dt (q, u, energies).
void EventDriven::rhs(const State& x, State& dxdt, double t) {
  ++rhs_evaluations_;
  unpack(x, q_, u_);
  if (!q_.allFinite() || !u_.allFinite()) {
    // Never hand a non-finite state to the system: the step that produced it is reported
    // as divergence once Odeint returns (run()).
    std::fill(dxdt.begin(), dxdt.end(), std::numeric_limits<double>::quiet_NaN());
    return;
  }
  phase_forces(t, q_, u_);
  for (int i = 0; i < n_; ++i) {
    dxdt[idx(i)] = u_[i];
    dxdt[idx(n_ + i)] = udot_[i];
  }
  const PowerTerms p = sys_.power(t, q_, u_);
  // The power of a contact force on the system, lambda W^T u = lambda (gdot - what), splits
  // into the power in the contact, lambda gdot (<= 0: zero when closed or sticking,
  // -mu lambda_N |gdot_T| when sliding), and the power of the moving seat, -lambda what,
  // which is energy put in through support motion.
  double normal = 0.0, friction = 0.0, seat = 0.0;
  bool any_closed = false;
  for (const auto& md : modes_) any_closed = any_closed || closed(md);
  if (any_closed) {
    for (int i = 0; i < m_; ++i) {
      if (!closed(modes_[idx(i)])) continue;
      const auto& c = cbuf_[idx(i)];
      normal += lambda_n_[i] * c.gap_rate(u_);
      friction += lambda_t_[i] * c.slip_rate(u_);
      seat -= lambda_n_[i] * c.what_normal + lambda_t_[i] * c.what_tangent;
    }
  }
  dxdt[idx(2 * n_ + kDamping)] = p.damping;
  dxdt[idx(2 * n_ + kGround)] = p.ground + seat;
  dxdt[idx(2 * n_ + kExternal)] = p.external;
  dxdt[idx(2 * n_ + kNormal)] = normal;
  dxdt[idx(2 * n_ + kFriction)] = friction;
}

// Event indicators at (t, x): h[2i] is g_N (open) or lambda_N + shift (closed); h[2i+1] is
// s gdot_T + shift (sliding with friction), mu lambda_N - |lambda_T| + shift (sticking),
// or +1 (no tangential event possible). An event is a sign change from >= 0 to < 0.
void EventDriven::indicators(double t, const State& x) {
  unpack(x, q_, u_);
  if (!q_.allFinite() || !u_.allFinite()) {
    h_.setOnes();  // no event in a non-finite state: run() stops on it as divergence
    return;
  }
  phase_forces(t, q_, u_);
  sys_.contact_data(t, q_, u_, cbuf_);
  for (int i = 0; i < m_; ++i) {
    const auto& c = cbuf_[idx(i)];
    const auto& md = modes_[idx(i)];
    switch (md) {
      case ContactState::kOpen:
        h_[2 * i] = c.gap_normal;
        h_[2 * i + 1] = 1.0;
        break;
      case ContactState::kStick:
        h_[2 * i] = lambda_n_[i] + force_shift_;
        h_[2 * i + 1] = c.friction * lambda_n_[i] - std::abs(lambda_t_[i]) + force_shift_;
        break;
      case ContactState::kClosed:
        h_[2 * i] = lambda_n_[i] + force_shift_;
        h_[2 * i + 1] = 1.0;
        break;
      case ContactState::kSlipPositive:
      case ContactState::kSlipNegative:
        h_[2 * i] = lambda_n_[i] + force_shift_;
        h_[2 * i + 1] = slip_sign(md) * c.slip_rate(u_) + velocity_shift_;
        break;
    }
  }
}

// Indicator k on the dense output of the current step at t.
double EventDriven::indicator_at(double t, int k) {
  dense_.calc_state(t, xs_);
  indicators(t, xs_);
  return h_[k];
}

// gdot_N of contact i on the dense output of the current step at t.
double EventDriven::gap_rate_at(double t, int i) {
  dense_.calc_state(t, xs_);
  unpack(xs_, q_, u_);
  sys_.contact_data(t, q_, u_, cbuf_);
  return cbuf_[idx(i)].gap_rate(u_);
}

}  // namespace nsb::integrators::detail
