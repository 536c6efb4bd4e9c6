// The right-hand side of the compliance method (compliance_integrator.hpp): the smooth forces
// plus the contact forces of eqs. (9) and (10), their Jacobian, and the gaps on a step's
// interpolant.
#include "integrators/compliance_integrator.hpp"

#include <algorithm>

namespace nsb::integrators::compliance_detail {

Core::Core(System& system, const ComplianceOptions& o)
    : sys_(system), opt_(o), n_(system.dofs()), m_(system.contacts()) {
  minv_ = checked_inverse_mass(sys_, "compliance");
  q_ = Vector::Zero(n_);
  u_ = Vector::Zero(n_);
  f_ = Vector::Zero(n_);
  acc_ = Vector::Zero(n_);
  K_ = Matrix::Zero(n_, n_);
  C_ = Matrix::Zero(n_, n_);
  Jq_ = Matrix::Zero(n_, n_);
  Ju_ = Matrix::Zero(n_, n_);
  contacts_ = sys_.make_contact_buffer();
  probes_ = sys_.make_contact_buffer();
  lambda_n_ = Vector::Zero(m_);
  lambda_t_ = Vector::Zero(m_);
  damping_part_ = Vector::Zero(m_);
  chi_ = Vector::Zero(m_);
  v_minus_ = Vector::Constant(m_, opt_.min_impact_velocity);
}

void Core::evaluate(double t, const State& x, bool derivatives,
                    ContactFields data) {
  q_ = x.head(n_);
  u_ = x.tail(n_);
  sys_.forces(t, q_, u_, f_);
  if (f_smooth_.size() != 0) f_smooth_ = f_;
  load_contacts(t, data);
  if (derivatives) {
    Jq_.setZero();
    Ju_.setZero();
  }
  for (int i = 0; i < m_; ++i) {
    lambda_n_[i] = 0.0;
    lambda_t_[i] = 0.0;
    damping_part_[i] = 0.0;
    const ContactData& c = contacts_[static_cast<std::size_t>(i)];
    if (c.far || !(c.gap_normal < 0.0)) continue;
    const NormalForce fn = normal_force(i, c);
    const TangentForce ft = tangent_force(i, c, fn);
    if (derivatives) add_contact_jacobian(c, fn, ft);
  }
}

void Core::load_contacts(double t, ContactFields data) {
  if (data == ContactFields::kForces) {
    sys_.contact_normals(t, q_, u_, contacts_);
    const bool penetrated = std::any_of(contacts_.begin(), contacts_.end(),
                                        [](const ContactData& c) {
                                          return !c.far && c.gap_normal < 0.0;
                                        });
    if (!penetrated) return;
  }
  sys_.contact_data(t, q_, u_, contacts_);
}

NormalForce Core::normal_force(int i, const ContactData& c) {
  const double delta = -c.gap_normal;
  const double delta_rate = -c.gap_rate(u_);
  const double k = contact_stiffness(opt_, c);
  const NormalForce fn = hertz_damp_force(k, chi_[i], v_minus_[i], delta, delta_rate);
  lambda_n_[i] = fn.force;
  damping_part_[i] = fn.force - k * delta * std::sqrt(delta);
  f_.noalias() += c.w_normal * fn.force;
  return fn;
}

TangentForce Core::tangent_force(int i, const ContactData& c, const NormalForce& fn) {
  TangentForce ft;
  if (c.friction > 0.0) {
    ft = regularized_coulomb(c.friction, fn.force, c.slip_rate(u_), opt_.stick_slip_velocity);
    lambda_t_[i] = ft.force;
    f_.noalias() += c.w_tangent * ft.force;
  }
  return ft;
}

void Core::add_contact_jacobian(const ContactData& c, const NormalForce& fn,
                                const TangentForce& ft) {
  // delta = -g_N with dg_N/dq = W_N^T, and deltadot = -(W_N^T u + what_N), so
  // dlambda_N/dq = -dF/ddelta W_N^T, dlambda_N/du = -dF/ddeltadot W_N^T.
  // The terms (dW_N/dq) u of dgdot/dq are left out: they are of the order of the
  // rotation rate times the damping force, small beside the stiffness terms, and a
  // Rosenbrock step with an approximate Jacobian stays consistent (the error control
  // sees the difference).
  Jq_.noalias() += fn.d_penetration * c.w_normal * c.w_normal.transpose();
  Ju_.noalias() += fn.d_rate * c.w_normal * c.w_normal.transpose();
  if (c.friction > 0.0) {
    Jq_.noalias() += (ft.d_normal * fn.d_penetration) * c.w_tangent * c.w_normal.transpose();
    Ju_.noalias() += (ft.d_normal * fn.d_rate) * c.w_tangent * c.w_normal.transpose();
    Ju_.noalias() -= ft.d_slip * c.w_tangent * c.w_tangent.transpose();
  }
}

void Core::rhs(const State& x, State& dxdt, double t) {
  evaluate(t, x, false);
  acc_.noalias() = minv_ * f_;
  dxdt.head(n_) = u_;
  dxdt.tail(n_) = acc_;
}

void Core::rhs_and_jacobian(const State& x, double t, State& dxdt, JacobianMatrix& J,
                            State& dfdt) {
  evaluate(t, x, true);
  acc_.noalias() = minv_ * f_;
  dxdt.head(n_) = u_;
  dxdt.tail(n_) = acc_;
  sys_.tangent(t, q_, u_, K_, C_);
  K_ += Jq_;
  C_ += Ju_;
  J.topLeftCorner(n_, n_).setZero();
  J.topRightCorner(n_, n_).setIdentity();
  J.bottomLeftCorner(n_, n_).noalias() = -minv_ * K_;
  J.bottomRightCorner(n_, n_).noalias() = -minv_ * C_;
  const double ht = kTimeDifferenceStep * std::max(1.0, std::abs(t));
  rhs(x, dfdt, t + ht);
  dfdt = (dfdt - dxdt) / ht;
}

const std::vector<ContactData>& Core::gaps_at(double t0, const State& x0, double t1,
                                              const State& x1, double s) {
  const double h = t1 - t0;
  const Hermite b(s);
  q_ = b.h00 * x0.head(n_) + (b.h10 * h) * x0.tail(n_) + b.h01 * x1.head(n_) +
       (b.h11 * h) * x1.tail(n_);
  u_ = (1.0 - s) * x0.tail(n_) + s * x1.tail(n_);
  sys_.contact_normals(t0 + s * h, q_, u_, probes_);
  return probes_;
}

}  // namespace nsb::integrators::compliance_detail
