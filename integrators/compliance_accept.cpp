// Accepting a step of the compliance method: events, commit, the step handed to the system,
// the energy balance (trapezoidal rule) and the recorder's sample.
#include "integrators/compliance_integrator.hpp"

#include "io/csv.hpp"

namespace nsb::integrators::compliance_detail {

bool ComplianceRun::accept_step(double t_new, bool landed, bool close_at_start) {
  record_openings(t_new);
  const double h = t_new - t_;
  x_ = xnew_;
  t_ = t_new;
  book_.count_step();
  core_.evaluate(t_, x_, false, ContactFields::kAll);
  system_.commit();
  const bool closed_now = record_closures(landed, close_at_start);
  if (landed) {
    target_ = std::numeric_limits<double>::infinity();
    std::fill(pending_.begin(), pending_.end(), 0);
  }
  // The forces with the new v_minus, for the record.
  if (closed_now) core_.evaluate(t_, x_, false, ContactFields::kAll);
  const StepVerdict verdict = watch(h);
  accumulate_energy(h);
  recorder_.step(t_, core_.q_, core_.u_, core_.contacts_, core_.lambda_n_, core_.lambda_t_,
                 energy_.error);
  remember_start();
  if (verdict != StepVerdict::kUnseated) return true;
  book_.unseat(t_);
  book_.result().message = "unseated at t = " + io::three_digits(t_) + " s";
  return false;
}

// The impulses of each contact episode (OutputGroup::kImpulses): the integral of the law's
// forces from the "close" to the "open" (the step in which it opens included: the force is
// zero once the gap is open), written on the "close" event as it grows, and on the "impact"
// row just before it when the episode is an impact.
void ComplianceRun::add_episode_impulses(double h) {
  for (int i = 0; i < m_; ++i) {
    const auto ii = static_cast<std::size_t>(i);
    if (episode_event_[ii] >= 0) {
      episode_normal_[i] += impulse_[i];
      episode_tangent_[i] += 0.5 * h * (lambda_t_start_[i] + core_.lambda_t_[i]);
      const auto close_row = static_cast<std::size_t>(episode_event_[ii]);
      recorder_.set_impulses(close_row, episode_normal_[i], episode_tangent_[i]);
      if (episode_impact_[ii]) {
        recorder_.set_impulses(close_row - 1, episode_normal_[i], episode_tangent_[i]);
      }
      if (episode_ends_[ii]) episode_event_[ii] = -1;
    }
    lambda_t_start_[i] = core_.lambda_t_[i];
  }
}

StepVerdict ComplianceRun::watch(double h) {
  for (int i = 0; i < m_; ++i) {
    impulse_[i] = 0.5 * h * (lambda_start_[i] + core_.lambda_n_[i]);
  }
  if (!episode_event_.empty()) add_episode_impulses(h);
  accepted_.t = t_;
  accepted_.h = h;
  const StepVerdict verdict = system_.accept_step(accepted_);
  if (verdict == StepVerdict::kContactsRemoved) {
    record_removed_contacts(system_, t_, recorder_);
    core_.evaluate(t_, x_, false, ContactFields::kAll);
    for (int i = 0; i < m_; ++i) {
      const auto ii = static_cast<std::size_t>(i);
      if (!core_.contacts_[ii].far) continue;
      pending_[ii] = 0;
      if (closed_[ii]) recorder_.event(t_, i + 1, EventKind::kOpen);
      closed_[ii] = 0;
    }
  }
  lambda_start_ = core_.lambda_n_;
  return verdict;
}

double ComplianceRun::contact_potential() const {
  double v = 0.0;
  for (const ContactData& c : core_.contacts_) {
    if (!c.far && c.gap_normal < 0.0) {
      v += 0.4 * contact_stiffness(options_, c) * std::pow(-c.gap_normal, 2.5);
    }
  }
  return v;
}

Powers ComplianceRun::powers() const {
  Powers p;
  const PowerTerms s = system_.power(t_, core_.q_, core_.u_);
  p.external = s.external;
  p.ground = s.ground;
  p.damping = s.damping;
  for (int i = 0; i < m_; ++i) {
    const ContactData& c = core_.contacts_[static_cast<std::size_t>(i)];
    // Work of the contact forces on the system: lambda (W^T u) = lambda (gdot - what).
    // The spring part of lambda_N is stored energy (contact_potential); the rest of the
    // normal work is the dissipation of the dashpot; the what-terms are work done by
    // moving obstacles (ground).
    p.impacts += core_.damping_part_[i] * c.gap_rate(core_.u_);
    p.ground -= core_.lambda_n_[i] * c.what_normal + core_.lambda_t_[i] * c.what_tangent;
    p.friction += core_.lambda_t_[i] * c.slip_rate(core_.u_);
  }
  return p;
}

void ComplianceRun::update_state_energy() {
  momentum_.noalias() = system_.mass() * core_.u_;  // M u, in a buffer sized once
  energy_.kinetic = 0.5 * core_.u_.dot(momentum_);
  const EnergyState es = system_.energy(t_, core_.q_);
  energy_.stored = es.stored + contact_potential();
  energy_.hysteretic = es.hysteretic;
}

void ComplianceRun::accumulate_energy(double h) {
  const Powers p_new = powers();
  energy_.external += 0.5 * h * (p_old_.external + p_new.external);
  energy_.ground += 0.5 * h * (p_old_.ground + p_new.ground);
  energy_.damping += 0.5 * h * (p_old_.damping + p_new.damping);
  energy_.impacts += 0.5 * h * (p_old_.impacts + p_new.impacts);
  energy_.friction += 0.5 * h * (p_old_.friction + p_new.friction);
  p_old_ = p_new;
  update_state_energy();
  energy_.close();
}

}  // namespace nsb::integrators::compliance_detail
