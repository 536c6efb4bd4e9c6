#include "integrators/event_integrator.hpp"
#include "io/csv.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace nsb::integrators::detail {

namespace {

// Relative size of the shifts that make "reaches 0" a strict sign change of an indicator
// (lambda_N + shift, s gdot_T + shift): far below any tolerance a user can ask for, but
// large enough that an indicator which starts a phase at round-off zero does not fire.
constexpr double kIndicatorShift = 1e-10;
// Iterations of the Newton projection onto g_N = 0 (the gaps are near-linear in q over the
// drift corrected, so two or three iterations reach round-off).
constexpr int kProjectionIterations = 4;
// Relative margin below which |lambda_T| counts as on the friction cone mu lambda_N: the
// contact LCP is solved to 1e-12.
constexpr double kConeSaturation = 1e-9;
// A normal force below this fraction of the applied forces' scale is round-off of the
// contact LCP (solved to 1e-12): the contact is not held closed by it.
constexpr double kClosedForce = 1e-12;

// The mode of a closed contact sliding with the sign of its slip velocity (kSlipPositive /
// kSlipNegative), or kClosed when frictionless (sign 0).
ContactState slip_state(double sign) {
  return sign > 0.0 ? ContactState::kSlipPositive
                    : sign < 0.0 ? ContactState::kSlipNegative : ContactState::kClosed;
}

}  // namespace

// Reports a contact problem the stage could not solve and says whether the run must stop:
// non-finite data is divergence; an unsolved problem stops the run (the phase that follows
// would rest on impulses or modes no solver confirmed).
bool EventDriven::stage_failed(double t, int contact, ContactStatus status, const char* problem) {
  if (status == ContactStatus::kSolved || status == ContactStatus::kSolvedByFallback) return false;
  std::string& message = book_.result().message;
  if (status == ContactStatus::kNonFiniteInput) {
    book_.diverge(t);
    message = std::string(problem) + ": non-finite data at t = " + io::three_digits(t) + " s";
  } else {
    book_.note_unsolved(t);
    const lcp::FrictionalResult& r = stage_.result();
    message = std::string(problem) + " not solved by any solver of the chain at t = " +
              io::three_digits(t) + " s (last: " + std::string(lcp::to_string(r.solver_used)) +
              ", " + std::string(lcp::to_string(r.status)) + ", residual " +
              io::three_digits(r.residual) + ")";
  }
  warn(t, contact, message);
  return true;
}

// The work of the stage's last impulses, booked as book_impulses does: per contact of the
// index set, the normal impulse along W_N and (with tangential unknowns) the tangential one.
void EventDriven::book_stage_impulses(const std::vector<int>& index, const Vector& u_minus,
                                      const Vector& u_plus) {
  for (std::size_t j = 0; j < index.size(); ++j) {
    const auto& c = cbuf_[idx(index[j])];
    const int jj = static_cast<int>(j);
    const double ln = stage_.lambda_n(jj), lt = stage_.lambda_t(jj);
    step_impulse_[index[j]] += ln;
    impact_impulse_[index[j]] += ln;
    const double mid_n = 0.5 * (c.w_normal.dot(u_minus) + c.w_normal.dot(u_plus));
    impact_normal_work_ += ln * (mid_n + c.what_normal);
    impact_ground_work_ -= ln * c.what_normal;
    if (stage_.kinematics().tangential()) {
      const double mid_t = 0.5 * (c.w_tangent.dot(u_minus) + c.w_tangent.dot(u_plus));
      impact_friction_work_ += lt * (mid_t + c.what_tangent);
      impact_ground_work_ -= lt * c.what_tangent;
    }
  }
}

void EventDriven::project_positions(double t, Vector& q, const Vector& u) {
  // Closest point in the kinetic metric on g_N,i(q) = 0 for every closed contact:
  //   dq = -M^-1 W (W^T M^-1 W)^+ g      (Newton iterations on the gap functions).
  std::vector<int> closed_set;
  for (int i = 0; i < m_; ++i) {
    if (closed(modes_[idx(i)])) closed_set.push_back(i);
  }
  if (closed_set.empty()) return;
  const int k = static_cast<int>(closed_set.size());
  Matrix W(n_, k);
  Vector g(k);
  for (int it = 0; it < kProjectionIterations; ++it) {
    sys_.contact_data(t, q, u, cbuf_);
    for (int j = 0; j < k; ++j) {
      W.col(j) = cbuf_[idx(closed_set[idx(j)])].w_normal;
      g[j] = cbuf_[idx(closed_set[idx(j)])].gap_normal;
    }
    if (g.cwiseAbs().maxCoeff() <= 1e-15) break;
    const Matrix G = W.transpose() * minv_ * W;
    q -= minv_ * (W * G.completeOrthogonalDecomposition().solve(g));
  }
}

void EventDriven::project_velocities(double t, const Vector& q, Vector& u) {
  // gdot_N = 0 for closed contacts and gdot_T = 0 for sticking ones, closest in the kinetic
  // metric: du = -M^-1 R (R^T M^-1 R)^+ (R^T u + what), the effect of the impulses
  // P = -(R^T M^-1 R)^+ (R^T u + what) along R. Their work is booked like an impact's.
  sys_.contact_data(t, q, u, cbuf_);
  const int k = closed_unknowns();
  if (k == 0) return;
  Matrix R(n_, k);
  Vector r(k), what(k);
  std::vector<bool> tangential(static_cast<std::size_t>(k), false);
  int j = 0;
  for (int i = 0; i < m_; ++i) {
    const auto& c = cbuf_[idx(i)];
    const auto& md = modes_[idx(i)];
    if (!closed(md)) continue;
    R.col(j) = c.w_normal;
    what[j] = c.what_normal;
    r[j++] = c.gap_rate(u);
    if (md == ContactState::kStick) {
      R.col(j) = c.w_tangent;
      what[j] = c.what_tangent;
      tangential[idx(j)] = true;
      r[j++] = c.slip_rate(u);
    }
  }
  const Matrix G = R.transpose() * minv_ * R;
  const Vector impulse = -G.completeOrthogonalDecomposition().solve(r);
  const Vector u_plus = u + minv_ * (R * impulse);
  book_impulses(R, impulse, what, tangential, u, u_plus);
  u = u_plus;
}

// Work of impulses P along the columns of W for a velocity jump u- -> u+:
// P . W^T (u- + u+)/2 (Glocker 2001), split as for the contact forces into the work in the
// contact, P . gdot_mid (normal: impacts, tangential: friction), and the work of the moving
// seats, -P . what (ground).
void EventDriven::book_impulses(const Matrix& W, const Vector& impulse, const Vector& what,
                                const std::vector<bool>& tangential, const Vector& u_minus,
                                const Vector& u_plus) {
  const Vector u_mid = 0.5 * (u_minus + u_plus);
  for (Eigen::Index j = 0; j < impulse.size(); ++j) {
    const double in_contact = impulse[j] * (W.col(j).dot(u_mid) + what[j]);
    (tangential[static_cast<std::size_t>(j)] ? impact_friction_work_ : impact_normal_work_) +=
        in_contact;
    impact_ground_work_ -= impulse[j] * what[j];
  }
}


// Zeno guard: a bounded number of events per window of time. Sets `forced` while touching
// contacts are forced closed; returns false when the bound is reached again under forced
// closure (the run stalls).
bool EventDriven::zeno_guard(double t, int trigger_contact, bool initial, bool& forced) {
  forced = t < forced_closure_until_;
  if (initial) return true;
  recent_events_.push_back(t);
  while (!recent_events_.empty() && recent_events_.front() < t - opt_.event_window) {
    recent_events_.pop_front();
  }
  const auto count = static_cast<int>(recent_events_.size());
  if (count >= 2 * opt_.max_events_per_window) {
    warn(t, trigger_contact, "event bound reached again under forced closure; run stopped");
    book_.result().message = "more than " + std::to_string(2 * opt_.max_events_per_window) +
                     " events within " + io::three_digits(opt_.event_window) + " s at t = " +
                     io::three_digits(t) + " s";
    book_.stall(t);
    return false;
  }
  if (count >= opt_.max_events_per_window && !forced) {
    warn(t, trigger_contact,
         "event bound reached (" + std::to_string(count) + " events within " +
             io::three_digits(opt_.event_window) + " s): touching contacts forced closed");
    forced_closure_until_ = t + opt_.event_window;
    forced = true;
  }
  return true;
}

// Step 1, location's outcome: the contacts touching at t (closed, or open within
// gap_tolerance) and whether one of them is closing faster than the Zeno threshold.
void EventDriven::find_touching(double t, const Vector& q, const Vector& u, bool initial,
                                bool& any_impact) {
  sys_.forces(t, q, u, f_);
  sys_.contact_data(t, q, u, cbuf_);
  touching_.clear();
  any_impact = false;
  for (int i = 0; i < m_; ++i) {
    const auto& c = cbuf_[idx(i)];
    // A far contact (one the system removed, or one far from touching) takes no part.
    const bool is_touching = !c.far && (closed(modes_[idx(i)]) || c.gap_normal <= gap_tolerance_);
    if (!is_touching) continue;
    touching_.push_back(i);
    if (c.gap_rate(u) < -closing_velocity_) any_impact = true;
    if (initial && c.gap_normal < -gap_tolerance_) {
      warn(t, i + 1, "initial penetration g_N = " + io::three_digits(c.gap_normal) + " m");
    }
  }
}

// Step 2, the impact problem: eq. (6) on every touching contact that is closing or resting,
// with the pre-impact velocities and Newton's law (restitution 0 under forced closure).
// Touching contacts that separate are left out: an impulse elsewhere that would make them
// close is caught as an impact just after. Returns false when the run must stop.
bool EventDriven::impact_problem(double t, Vector& u, bool forced, int trigger_contact) {
  touching_.erase(std::remove_if(touching_.begin(), touching_.end(),
                                 [&](int i) {
                                   return cbuf_[idx(i)].gap_rate(u) > closing_velocity_;
                                 }),
                  touching_.end());
  bool frictionless = true;
  for (int i : touching_) frictionless = frictionless && cbuf_[idx(i)].friction == 0.0;
  lcp::FrictionalProblem& fp =
      stage_.build(cbuf_, touching_, !frictionless, minv_, u, ContactLevel::kVelocity);
  for (std::size_t j = 0; j < touching_.size(); ++j) {
    const auto& c = cbuf_[idx(touching_[j])];
    const auto jj = static_cast<Eigen::Index>(j);
    fp.gdot_n_minus[jj] = std::min(0.0, c.gap_rate(u));
    if (forced) fp.restitution[jj] = 0.0;
  }
  const ContactStatus status = stage_.solve({ProblemKind::kImpact, t, book_.result().steps});
  if (stage_failed(t, trigger_contact, status, "impact problem (eq. 6)")) return false;
  u_plus_ = u;
  stage_.apply(u_plus_);
  book_stage_impulses(touching_, u, u_plus_);
  for (std::size_t j = 0; j < touching_.size(); ++j) {
    const int i = touching_[j];
    const int jj = static_cast<int>(j);
    if (cbuf_[idx(i)].gap_rate(u) < -closing_velocity_) {
      rec_.impact(t, i + 1, stage_.lambda_n(jj), stage_.lambda_t(jj));
    }
  }
  u = u_plus_;
  return true;
}

// Step 3a: candidates for closure are the touching contacts not separating faster than
// closing_velocity; each is a stick candidate when frictional and slower than stick_velocity,
// else sliding in the direction of its slip velocity.
void EventDriven::closure_candidates(const Vector& u) {
  // A slip event is located where s gdot_T + velocity_shift_ turns negative, so the slip
  // velocity there is velocity_shift_ (plus the Brent bracket's overshoot, far smaller):
  // a stick threshold below it (stick_velocity = 10 tolerance is 1e-10 m/s at tolerance
  // 1e-11, the shift 3e-10 m/s at 2 m/s) would take the contact for sliding the other way
  // and fire the reversal again at once. Twice the shift covers the overshoot.
  const double stick = std::max(stick_velocity_, 2.0 * velocity_shift_);
  for (auto& md : modes_) md = ContactState::kOpen;
  for (int i : touching_) {
    const auto& c = cbuf_[idx(i)];
    if (c.gap_rate(u) > closing_velocity_) continue;
    if (c.friction > 0.0 && std::abs(c.slip_rate(u)) <= stick) {
      modes_[idx(i)] = ContactState::kStick;
    } else {
      const double sgn = c.friction > 0.0 ? (c.slip_rate(u) > 0.0 ? 1.0 : -1.0) : 0.0;
      modes_[idx(i)] = slip_state(sgn);
    }
  }
}

// Step 3b, the contact problem: eq. (6) at acceleration level on the candidates, eps = 0
// (Pfeiffer & Glocker 1996, ch. 6). Sliding contacts carry lambda_T = -mu s lambda_N in their
// normal column and no tangential unknown. Sets the modes of the next phase. Returns false
// when the run must stop.
bool EventDriven::contact_problem(double t, Vector& q, Vector& u) {
  candidates_.clear();
  for (int i = 0; i < m_; ++i) {
    if (closed(modes_[idx(i)])) candidates_.push_back(i);
  }
  if (candidates_.empty()) return true;
  sys_.forces(t, q, u, f_);
  sys_.contact_data(t, q, u, cbuf_);
  bool tangential = false;
  for (std::size_t j = 0; j < candidates_.size(); ++j) {
    const auto& c = cbuf_[idx(candidates_[j])];
    const auto& md = modes_[idx(candidates_[j])];
    tangential = tangential || md == ContactState::kStick;
    slip_coupling_[j] = -c.friction * slip_sign(md);
  }
  a_free_.noalias() = minv_ * f_;
  lcp::FrictionalProblem& fp = stage_.build(cbuf_, candidates_, tangential, minv_, a_free_,
                                            ContactLevel::kAcceleration, slip_coupling_.data());
  for (std::size_t j = 0; j < candidates_.size(); ++j) {
    const auto& md = modes_[idx(candidates_[j])];
    if (tangential && md == ContactState::kStick) {
      fp.friction[static_cast<Eigen::Index>(j)] = cbuf_[idx(candidates_[j])].friction;
    }
  }
  const ContactStatus status =
      stage_.solve({ProblemKind::kContinuous, t, book_.result().steps});
  if (status == ContactStatus::kUnsolved) {
    // The candidates keep their modes, and the run goes on; the status says
    // contact_unsolved from here (failure_time: the first such event).
    book_.note_unsolved(t);
    warn(t, candidates_.front() + 1,
         "contact problem (eq. 6, accelerations) not solved by any solver of the chain "
         "(residual " + io::three_digits(stage_.result().residual) +
             "): touching contacts kept closed in their current modes");
    return true;
  }
  if (stage_failed(t, candidates_.front() + 1, status, "contact problem (eq. 6, accelerations)")) {
    return false;
  }
  const lcp::FrictionalResult& r = stage_.result();
  // Scale of the accelerations, for "gddot = 0" decisions on round-off.
  const double acc_scale = 1e-9 * (1.0 + fp.gdot_free.cwiseAbs().maxCoeff());
  const double force_scale = 1.0 + f_.cwiseAbs().maxCoeff();
  for (std::size_t j = 0; j < candidates_.size(); ++j) {
    const auto jj = static_cast<Eigen::Index>(j);
    auto& md = modes_[idx(candidates_[j])];
    // Closed only under a positive normal force: at a lift-off both lambda_N and gddot_N
    // pass through 0, and keeping a contact closed on gddot_N = 0 would fire the lift-off
    // again at once.
    if (!(r.lambda_n[jj] > kClosedForce * force_scale)) {
      md = ContactState::kOpen;
      continue;
    }
    if (md != ContactState::kStick) continue;
    // Stick while the friction force is inside the cone; on its boundary the contact slips
    // against the friction force, lambda_T = -mu s lambda_N (eq. 5). Deciding on the force
    // rather than on the sign of gddot_T, which is round-off at a stick-slip transition,
    // keeps a transition from firing again at once.
    const double lt = r.lambda_t[jj], cone = fp.friction[jj] * r.lambda_n[jj];
    const bool saturated = std::abs(lt) >= cone * (1.0 - kConeSaturation) && cone > 0.0;
    const double at = r.gdot_t_plus[jj];
    if (saturated || std::abs(at) > acc_scale) {
      const double sgn = saturated && lt != 0.0 ? (lt > 0.0 ? -1.0 : 1.0) : (at > 0.0 ? 1.0 : -1.0);
      md = slip_state(sgn);
    }
  }
  return true;
}

// Step 5: events for the mode changes.
void EventDriven::record_mode_changes(double t, const std::vector<ContactState>& old) {
  for (int i = 0; i < m_; ++i) {
    const auto& a = old[idx(i)];
    const auto& b = modes_[idx(i)];
    if (!closed(a) && closed(b)) rec_.event(t, i + 1, EventKind::kClose);
    if (closed(a) && !closed(b)) rec_.event(t, i + 1, EventKind::kOpen);
    if (b == ContactState::kStick && a != ContactState::kStick) rec_.event(t, i + 1, EventKind::kStick);
    if (sliding(b) && a != b) {
      rec_.event(t, i + 1, EventKind::kSlip);
    }
  }
}

// Resolves what happens at time t in state x (modified in place), along the steps of
// Shi & Dimitrakopoulos (2017), section 2.2: the located event's touching contacts, the
// impact problem, the contact problem that sets the modes of the next phase, the projection
// onto the constraints, and the mode update. Returns false if the run must stop.
bool EventDriven::handle_event(double t, State& x, int trigger_contact, bool initial) {
  unpack(x, q_event_, u_event_);
  Vector& q = q_event_;
  Vector& u = u_event_;
  if (!q.allFinite() || !u.allFinite()) {
    book_.diverge(t);
    book_.result().message = "non-finite state at t = " + io::three_digits(t) + " s";
    warn(t, trigger_contact, book_.result().message);
    return false;
  }
  bool forced = false;
  if (!zeno_guard(t, trigger_contact, initial, forced)) return false;

  bool any_impact = false;
  find_touching(t, q, u, initial, any_impact);
  bool solved_lcp = false;
  if (any_impact) {
    solved_lcp = true;
    if (!impact_problem(t, u, forced, trigger_contact)) return false;
  }

  old_modes_ = modes_;
  closure_candidates(u);
  // Project the candidates onto the constraint manifold (drift correction, and gdot_N = 0
  // for a contact whose post-impact velocity is below the Zeno threshold).
  project_positions(t, q, u);
  project_velocities(t, q, u);
  bool any_candidate = false;
  for (const auto& md : modes_) any_candidate = any_candidate || closed(md);
  if (any_candidate) {
    solved_lcp = true;
    if (!contact_problem(t, q, u)) return false;
    // Final projection with the decided modes (sticking contacts get gdot_T = 0).
    project_positions(t, q, u);
    project_velocities(t, q, u);
  }
  if (solved_lcp) ++book_.result().steps_with_lcp;
  record_mode_changes(t, old_modes_);

  // Indicator shifts for the new phase, scaled to the forces and velocities in play.
  sys_.forces(t, q, u, f_);
  force_shift_ = kIndicatorShift * (1.0 + f_.cwiseAbs().maxCoeff());
  velocity_shift_ = kIndicatorShift * (1.0 + u.cwiseAbs().maxCoeff());
  pack(q, u, x);
  return true;
}

}  // namespace nsb::integrators::detail
