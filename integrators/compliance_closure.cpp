// The gap elements of the compliance method: where a step's interpolant closes a gap (the step
// is then retaken to end there), and the closures and openings recorded as events.
#include "integrators/compliance_integrator.hpp"

#include "integrators/closure_bound.hpp"

#include <algorithm>

namespace nsb::integrators::compliance_detail {

void ComplianceRun::close_contact(int i, double time) {
  const ContactData& c = core_.contacts_[static_cast<std::size_t>(i)];
  closed_[static_cast<std::size_t>(i)] = 1;
  const double closing_speed = -c.gap_rate(core_.u_);
  core_.v_minus_[i] = std::max(closing_speed, options_.min_impact_velocity);
  // The episode is an impact (an "impact" row before its "close", docs/outputs.md, "One event
  // vocabulary") when the law of eq. (9) sees its closing speed: above min_impact_velocity,
  // below which v_minus is floored and the law treats the closure as a contact from rest.
  const bool impact = closing_speed > options_.min_impact_velocity;
  if (impact) recorder_.event(time, i + 1, EventKind::kImpact);
  if (!episode_event_.empty()) {
    const auto ii = static_cast<std::size_t>(i);
    episode_event_[ii] = static_cast<std::ptrdiff_t>(recorder_.events().size());
    episode_impact_[ii] = impact ? 1 : 0;
    episode_ends_[ii] = 0;
    episode_normal_[i] = 0.0;
    episode_tangent_[i] = 0.0;
  }
  recorder_.event(time, i + 1, EventKind::kClose);
}

bool ComplianceRun::searched(int i, const ContactData& c, bool landed) const {
  const auto ii = static_cast<std::size_t>(i);
  return !closed_[ii] && !c.far && !(landed && pending_[ii]);
}

double ComplianceRun::min_open_gap(double t_new, bool landed, double s) {
  double g = std::numeric_limits<double>::infinity();
  const auto& cs = core_.gaps_at(t_, x_, t_new, xnew_, s);
  for (int i = 0; i < m_; ++i) {
    const ContactData& c = cs[static_cast<std::size_t>(i)];
    if (searched(i, c, landed)) g = std::min(g, c.gap_normal);
  }
  return g;
}

void ComplianceRun::remember_start() {
  for (int i = 0; i < m_; ++i) {
    const ContactData& c = core_.contacts_[static_cast<std::size_t>(i)];
    start_gap_[i] = c.gap_normal;
    start_rate_[i] = c.gap_rate(core_.u_);
  }
}

bool ComplianceRun::may_close(double t_new, bool landed) {
  const auto& cs = core_.gaps_at(t_, x_, t_new, xnew_, 1.0);
  for (int i = 0; i < m_; ++i) {
    const auto ii = static_cast<std::size_t>(i);
    if (closed_[ii] || (landed && pending_[ii])) continue;
    if (!gap_stays_open(start_gap_[i], start_rate_[i], cs[ii].gap_normal,
                        cs[ii].gap_rate(core_.u_), t_new - t_)) {
      return true;
    }
  }
  return false;
}

ComplianceRun::Closure ComplianceRun::locate_closure(double t_new, bool landed) {
  Closure out;
  if (m_ == 0 || !may_close(t_new, landed)) return out;
  double s_lo = 0.0, s_hi = -1.0;
  for (int j = 1; m_ > 0 && j <= kClosureProbes; ++j) {
    const double s = static_cast<double>(j) / kClosureProbes;
    if (min_open_gap(t_new, landed, s) < 0.0) {
      s_hi = s;
      s_lo = static_cast<double>(j - 1) / kClosureProbes;
      break;
    }
  }
  if (!(s_hi > 0.0)) return out;
  for (int it = 0; it < kMaxBisections && s_hi - s_lo > kClosureRelativeWidth; ++it) {
    const double mid = 0.5 * (s_lo + s_hi);
    (min_open_gap(t_new, landed, mid) < 0.0 ? s_hi : s_lo) = mid;
  }
  const double t_close = t_ + s_lo * (t_new - t_);
  // The contacts that close first: their interpolated gap at s_hi is negative.
  const auto& cs = core_.gaps_at(t_, x_, t_new, xnew_, s_hi);
  std::fill(pending_.begin(), pending_.end(), 0);
  for (int i = 0; i < m_; ++i) {
    const ContactData& c = cs[static_cast<std::size_t>(i)];
    if (searched(i, c, landed) && c.gap_normal < 0.0) pending_[static_cast<std::size_t>(i)] = 1;
  }
  if (t_close - t_ > 10.0 * kMinRelativeStep * std::max(1.0, std::abs(t_))) {
    out.retake = true;
    out.time = t_close;
  } else {
    out.at_start = true;
  }
  return out;
}

void ComplianceRun::record_openings(double t_new) {
  const double h = t_new - t_;
  for (int i = 0; i < m_; ++i) {
    const auto ii = static_cast<std::size_t>(i);
    if (!closed_[ii]) continue;
    if (!(core_.gaps_at(t_, x_, t_new, xnew_, 1.0)[ii].gap_normal > 0.0)) continue;
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < kMaxBisections && hi - lo > kClosureRelativeWidth; ++it) {
      const double mid = 0.5 * (lo + hi);
      (core_.gaps_at(t_, x_, t_new, xnew_, mid)[ii].gap_normal > 0.0 ? hi : lo) = mid;
    }
    closed_[ii] = 0;
    if (!episode_ends_.empty()) episode_ends_[ii] = 1;
    recorder_.event(t_ + hi * h, i + 1, EventKind::kOpen);
  }
}

bool ComplianceRun::record_closures(bool landed, bool close_at_start) {
  bool closed_now = false;
  for (int i = 0; i < m_; ++i) {
    const auto ii = static_cast<std::size_t>(i);
    const ContactData& c = core_.contacts_[ii];
    if (closed_[ii] || c.far) {
      pending_[ii] = 0;
      continue;
    }
    if (c.gap_normal < 0.0 || (pending_[ii] && (landed || close_at_start))) {
      close_contact(i, t_);
      pending_[ii] = 0;
      closed_now = true;
    }
  }
  return closed_now;
}

}  // namespace nsb::integrators::compliance_detail
