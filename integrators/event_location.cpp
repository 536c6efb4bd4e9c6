#include "integrators/event_location.hpp"

#include "integrators/event_integrator.hpp"

#include <gsl/gsl_errno.h>

#include <limits>
#include <mutex>

namespace nsb::integrators::detail {

namespace {

// Brent iterations; the bracket halves at least every few iterations, so 200 is ample for
// any step down to event_time_tolerance.
constexpr int kBrentIterations = 200;

// GSL's error handler is process-wide: it is set once, before the first location, and never
// switched again (see EventRootFinder).
void turn_gsl_error_handler_off_once() {
  static std::once_flag once;
  std::call_once(once, [] { gsl_set_error_handler_off(); });
}

}  // namespace

EventRootFinder::EventRootFinder(double time_tolerance) : tolerance_(time_tolerance) {
  turn_gsl_error_handler_off_once();
  solver_.reset(gsl_root_fsolver_alloc(gsl_root_fsolver_brent));
}

void EventRootFinder::bracket(gsl_function& f, double& lo, double& hi) {
  gsl_root_fsolver* s = solver_.get();
  if (gsl_root_fsolver_set(s, &f, lo, hi) != GSL_SUCCESS) return;
  for (int it = 0; it < kBrentIterations; ++it) {
    if (gsl_root_fsolver_iterate(s) != GSL_SUCCESS) break;
    lo = gsl_root_fsolver_x_lower(s);
    hi = gsl_root_fsolver_x_upper(s);
    if (gsl_root_test_interval(lo, hi, tolerance_, 0.0) == GSL_SUCCESS) break;
  }
}

// Earliest event time in (ta, tb] for indicator k, or +inf. ha = indicator at ta.
double EventDriven::locate(int k, double ta, double tb, double ha, double hb) {
  const double inf = std::numeric_limits<double>::infinity();
  const int i = k / 2;
  const bool gap = (k % 2 == 0) && !closed(modes_[idx(i)]);
  auto h = [this, k](double t) { return indicator_at(t, k); };
  if (!gap) {
    if (hb >= 0.0) return inf;
    if (ha < 0.0) return ta;
    return roots_.first_crossing(h, ta, tb);
  }
  // An open contact the system says is far at tb (one it removed, or one far from
  // touching) has no impact in the step.
  if (cbuf_[idx(i)].far) return inf;
  // An open contact: an impact when g_N goes below 0 while closing.
  auto gd = [this, i](double t) { return gap_rate_at(t, i); };
  const double va = gd(ta), vb = gd(tb);
  // A gap that is negative at tb fires only if it is closing faster than the Zeno
  // threshold there or has gone below -gap_shift_: a contact that touches without
  // closing (zero load, sliding along its face) stays open through round-off of g_N.
  const bool fires = hb < 0.0 && (hb < -gap_shift_ || vb < -closing_velocity_);
  if (ha > 0.0 && fires) return roots_.first_crossing(h, ta, tb);
  if (ha <= 0.0 && fires) {
    // The contact has just been released at ta. If it rose and came back, locate the apex
    // (gdot_N = 0), then the crossing after it.
    if (va > 0.0 && vb < 0.0) {
      auto ngd = [&gd](double t) { return gd(t); };
      const double apex = roots_.first_crossing(ngd, ta, tb);
      if (h(apex) > 0.0) return roots_.first_crossing(h, apex, tb);
    }
    if (va > 0.0) return inf;
    // Released with gdot_N = 0 and gddot_N >= 0, but higher derivatives bring it back:
    // the event is where the penetration reaches gap_shift_.
    if (ha > -gap_shift_ && hb < -gap_shift_) {
      auto hs = [&h, this](double t) { return h(t) + gap_shift_; };
      return roots_.first_crossing(hs, ta, tb);
    }
    return ta;
  }
  if (ha > 0.0 && hb >= 0.0 && va < 0.0 && vb > 0.0) {
    // Grazing inside the step: the gap has a minimum; test whether it dips below 0.
    auto neg_gd = [&gd](double t) { return -gd(t); };
    const double tmin = roots_.first_crossing(neg_gd, ta, tb);
    if (h(tmin) < -gap_shift_) return roots_.first_crossing(h, ta, tmin);
  }
  return inf;
}

}  // namespace nsb::integrators::detail
