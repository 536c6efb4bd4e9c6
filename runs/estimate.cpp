#include "runs/estimate.hpp"

#include "integrators/contact_stage.hpp"
#include "io/csv.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <type_traits>
#include <vector>

namespace nsb::runs {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

CompanionPlan plan_of(integrators::RunConfig config, std::string setting, double value,
                      double companion_value, double order) {
  const double r = companion_value / value;
  return CompanionPlan{std::move(config), std::move(setting), value, companion_value, order,
                       1.0 / (std::pow(r, order) - 1.0)};
}

// The companion of an adaptive method: tolerance r tol, at most `top` (the open upper end of
// the tolerance's range, halved); none when that is no looser than the run's.
template <class Options>
std::optional<CompanionPlan> looser(const Options& o, double top, double order) {
  const double loose = std::min(kToleranceRatio * o.tolerance, 0.5 * top);
  if (!(loose > o.tolerance)) return std::nullopt;
  Options c = o;
  c.tolerance = loose;
  return plan_of(c, "tolerance", o.tolerance, loose, order);
}

bool is_compliance(const integrators::RunConfig& config) {
  return std::holds_alternative<integrators::ComplianceOptions>(config);
}

bool is_impact_with_gaps(const integrators::Event& e) {
  return e.kind == integrators::EventKind::kImpact && e.contact >= 1 && !e.gaps.empty();
}

// The impact of `contact` in `events` nearest to t; nullptr when it has none.
const integrators::Event* nearest_impact(const std::vector<integrators::Event>& events,
                                         int contact, double t) {
  const integrators::Event* best = nullptr;
  for (const integrators::Event& e : events) {
    if (!is_impact_with_gaps(e) || e.contact != contact) continue;
    if (best == nullptr || std::abs(e.t - t) < std::abs(best->t - t)) best = &e;
  }
  return best;
}

}  // namespace

UnresolvedImpactOrder impact_order(const integrators::Recorder& run,
                                   const integrators::Recorder& companion,
                                   const std::vector<ContactLabel>& labels, double factor,
                                   bool stepped) {
  UnresolvedImpactOrder found;
  const auto& events = run.events();
  // Whether each contact is closed (in contact) just before the event at hand: set by close,
  // stick and slip, cleared by open.
  std::vector<char> closed(static_cast<std::size_t>(run.contacts()), 0);
  for (const integrators::Event& e : events) {
    const auto ci = static_cast<std::size_t>(e.contact - 1);
    if (e.contact >= 1 && ci < closed.size()) {
      if (e.kind == integrators::EventKind::kOpen) closed[ci] = 0;
      if (e.kind == integrators::EventKind::kClose || e.kind == integrators::EventKind::kStick ||
          e.kind == integrators::EventKind::kSlip) {
        closed[ci] = 1;
      }
    }
    if (!is_impact_with_gaps(e)) continue;
    const integrators::Event* other = nearest_impact(companion.events(), e.contact, e.t);
    if (other == nullptr || other->gaps.size() != e.gaps.size() ||
        nearest_impact(events, e.contact, other->t) != &e) {
      continue;
    }
    for (std::size_t d = 0; d < e.gaps.size(); ++d) {
      if (d == ci || closed[d] != 0) continue;
      if (d < labels.size() && ci < labels.size() && labels[d].face != labels[ci].face) continue;
      const int di = static_cast<int>(d);
      if (!(e.t < run.removed_at(di)) || !(other->t < companion.removed_at(di))) continue;
      // d's closing speed once c has struck: the next impact, if it is of c's size.
      const double closing =
          -(e.gap_rates_after.empty() ? e.gap_rates[d] : e.gap_rates_after[d]);
      if (!(closing > kOrderConsequence * -e.gap_rates[ci])) continue;
      const double s = e.gaps[d] - e.gaps[ci];
      if (!(s > 0.0)) continue;
      if (stepped && !(s > closing * other->gap_interval)) continue;
      const double s_companion = other->gaps[d] - other->gaps[ci];
      const double uncertainty = factor * std::abs(s - s_companion);
      if (s < uncertainty && uncertainty > kOrderFloor) {
        return UnresolvedImpactOrder{true, e.t, e.contact, di + 1, s, uncertainty};
      }
    }
  }
  return found;
}

std::pair<std::string, double> accuracy_setting(const integrators::RunConfig& config) {
  return std::visit(
      [](const auto& o) -> std::pair<std::string, double> {
        if constexpr (std::is_same_v<std::decay_t<decltype(o)>, integrators::MoreauJeanOptions>) {
          if (o.local_tolerance > 0.0) return {"local_tolerance", o.local_tolerance};
          return {"step", o.step};
        } else {
          return {"tolerance", o.tolerance};
        }
      },
      config);
}

std::optional<CompanionPlan> companion_plan(const integrators::RunConfig& config,
                                            double duration) {
  return std::visit(
      [duration](const auto& o) -> std::optional<CompanionPlan> {
        using O = std::decay_t<decltype(o)>;
        if constexpr (std::is_same_v<O, integrators::MoreauJeanOptions>) {
          if (o.local_tolerance > 0.0) {
            // Adaptive steps: the same run at a looser local tolerance (below 1, its range).
            const double loose = std::min(kMoreauToleranceRatio * o.local_tolerance, 0.5);
            if (!(loose > o.local_tolerance)) return std::nullopt;
            O c = o;
            c.local_tolerance = loose;
            return plan_of(c, "local_tolerance", o.local_tolerance, loose,
                           kAdaptiveMoreauOrder);
          }
          const double coarse = kMoreauStepRatio * o.step;
          if (!(coarse <= duration)) return std::nullopt;
          O c = o;
          c.step = coarse;
          return plan_of(c, "step", o.step, coarse, kMoreauPeakOrder);
        } else if constexpr (std::is_same_v<O, integrators::EventDrivenOptions>) {
          return looser(o, 1.0, kEventDrivenOrder);  // tolerance in (0, 1)
        } else {
          return looser(o, 0.1, kComplianceOrder);  // tolerance in (0, 0.1)
        }
      },
      config);
}

double first_impact_time(const integrators::Recorder& history) {
  for (const auto& e : history.events()) {
    if (e.kind == integrators::EventKind::kImpact) return e.t;
  }
  return kNaN;
}

void apply_estimate(Digest& run, const integrators::Recorder& run_history,
                    const Digest& companion, const integrators::Recorder& companion_history,
                    const CompanionPlan& plan) {
  ErrorEstimate& e = run.estimate;
  e.computed = true;
  e.setting = plan.setting;
  e.value = plan.value;
  e.companion_value = plan.companion_value;
  e.order = plan.order;
  e.ratio = plan.companion_value / plan.value;
  e.factor = plan.factor;
  // The peaks: both digests have the columns of one system, in one order.
  for (std::size_t c = 0; c < run.peaks.size() && c < companion.peaks.size(); ++c) {
    run.peaks[c].error = plan.factor * std::abs(run.peaks[c].abs_max - companion.peaks[c].abs_max);
  }
  for (std::size_t c = 0; c < run.coordinates.size() && c < companion.coordinates.size(); ++c) {
    run.coordinates[c].error =
        plan.factor * std::abs(run.coordinates[c].peak - companion.coordinates[c].peak);
  }
  // An impact whose order against another contact's closing is not resolved: what follows it
  // is on one branch of two, which no extrapolation bounds; every peak's error is then at
  // least the peak itself.
  // The compliance method's contact forces are smooth in the order of closing: no branch.
  if (!is_compliance(plan.config)) {
    e.impact_order = impact_order(run_history, companion_history, run.contacts, plan.factor,
                                  plan.setting != "tolerance");
  }
  if (e.impact_order.found) {
    for (ColumnPeak& p : run.peaks) p.error = std::max(p.error, p.abs_max);
    for (CoordinatePeak& c : run.coordinates) c.error = std::max(c.error, c.peak);
  }
  // A count has no asymptotic order: its error is the difference itself.
  e.impacts = run.count(integrators::EventKind::kImpact);
  e.impacts_error = std::abs(static_cast<double>(
      e.impacts - companion.count(integrators::EventKind::kImpact)));
  // The first impact's time: extrapolated like a peak; Moreau–Jean places an event at the end
  // of its step, so its error is at least the step.
  e.first_impact = first_impact_time(run_history);
  const double tc = first_impact_time(companion_history);
  if (std::isnan(e.first_impact) != std::isnan(tc)) {
    e.first_impact_error = std::numeric_limits<double>::infinity();  // one run has none
  } else if (!std::isnan(e.first_impact)) {
    e.first_impact_error = plan.factor * std::abs(e.first_impact - tc);
    if (plan.setting == "step") e.first_impact_error = std::max(e.first_impact_error, plan.value);
  }
}

double judged_peak(const Digest& digest, const CoordinatePeak& coordinate) {
  double largest = 0.0;
  for (const CoordinatePeak& c : digest.coordinates) largest = std::max(largest, std::abs(c.peak));
  return std::max(std::abs(coordinate.peak),
                  integrators::ContactTolerances::kRoundOff * largest);
}

Accuracy judge_accuracy(const Digest& digest, double target) {
  Accuracy a;
  a.target = target;
  if (!digest.estimate.computed) return a;
  a.judged = true;
  a.met = true;
  a.worst_relative = 0.0;
  for (const CoordinatePeak& c : digest.coordinates) {
    // A peak of zero with a zero error is exact; with a nonzero one, infinitely wrong.
    const double rel = c.error == 0.0 ? 0.0 : c.error / judged_peak(digest, c);
    if (!(rel <= target)) a.met = false;
    if (!(rel <= a.worst_relative)) {
      a.worst_relative = rel;
      a.worst = c.name;
    }
  }
  return a;
}

double refined_value(const std::string& setting, double value, double worst_relative,
                     double target) {
  if (setting != "step") return value / kAdaptToleranceDivisor;
  // rel(h) ≈ rel(h0) (h / h0)^p: the step at which the estimate would be kAdaptSafety x target.
  double ratio = kAdaptMaxStepRatio;
  if (std::isfinite(worst_relative) && worst_relative > 0.0) {
    ratio = std::pow(kAdaptSafety * target / worst_relative, 1.0 / kMoreauOrder);
  }
  return value * std::clamp(ratio, kAdaptMinStepRatio, kAdaptMaxStepRatio);
}

CrossCheck compare_runs(const Digest& run, const Digest& other, double run_first_impact,
                        double other_first_impact, const std::string& other_method,
                        const std::string& other_status, double accuracy) {
  CrossCheck x;
  x.method = other_method;
  x.status = other_status;
  x.floor = accuracy;
  // An error that is not estimated counts as zero: the floor alone then decides.
  const auto known = [](double e) { return std::isfinite(e) ? e : 0.0; };
  for (std::size_t c = 0; c < run.coordinates.size(); ++c) {
    const CoordinatePeak& mine = run.coordinates[c];
    CrossPeak p;
    p.name = mine.name;
    if (c < other.coordinates.size()) {
      p.peak = other.coordinates[c].peak;
      p.error = other.coordinates[c].error;
    }
    p.difference = mine.peak - p.peak;
    p.allowed = known(mine.error) + known(p.error) + accuracy * judged_peak(run, mine);
    p.agrees = std::abs(p.difference) <= p.allowed;
    x.coordinates.push_back(std::move(p));
  }
  x.impacts = other.count(integrators::EventKind::kImpact);
  x.impacts_difference = static_cast<double>(run.count(integrators::EventKind::kImpact) - x.impacts);
  x.impacts_error = other.estimate.impacts_error;
  x.first_impact = other_first_impact;
  x.first_impact_error = other.estimate.first_impact_error;
  x.first_impact_difference = run_first_impact - other_first_impact;
  x.compared = true;
  return x;
}

std::vector<std::string> cross_check_warnings(const Digest& run, const std::string& run_method,
                                              const CrossCheck& check) {
  std::vector<std::string> w;
  if (check.method.empty()) return w;
  if (!check.compared) {
    w.push_back("cross_check: the run under " + check.method + " ended " + check.status +
                "; the peaks are not cross-checked");
    return w;
  }
  const auto known = [](double e) { return std::isfinite(e) ? e : 0.0; };
  for (std::size_t c = 0; c < check.coordinates.size() && c < run.coordinates.size(); ++c) {
    const CoordinatePeak& mine = run.coordinates[c];
    const CrossPeak& other = check.coordinates[c];
    if (other.agrees) continue;
    w.push_back("cross_check: the peak |" + mine.name + "| is " + io::three_digits(mine.peak) +
                " under " + run_method + " and " + io::three_digits(other.peak) + " under " +
                check.method + ", a difference of " +
                io::three_digits(std::abs(other.difference)) + " beyond the two estimates (" +
                io::three_digits(known(mine.error)) + " and " + io::three_digits(known(other.error)) +
                ") and the floor " + io::three_digits(check.floor * judged_peak(run, mine)) +
                " (solver.accuracy x the peak)");
  }
  return w;
}

std::string accuracy_warning(const Digest& digest) {
  const ErrorEstimate& e = digest.estimate;
  const Accuracy& a = digest.accuracy;
  if (!e.enabled) return {};
  const std::string knob = "solver." + e.setting;
  if (!e.computed) {
    return "accuracy: no error estimate: " +
           (e.companion_status.empty()
                ? std::string("no companion run can be made for these solver settings")
                : "the companion run ended " + e.companion_status) +
           "; the peaks' errors are unknown";
  }
  if (a.met) return {};
  if (e.impact_order.found) {
    const UnresolvedImpactOrder& o = e.impact_order;
    char at[32];
    std::snprintf(at, sizeof at, "%.5g", o.time);
    return "accuracy: at " + std::string(at) + " s contact " +
           std::to_string(o.contact) + " strikes while contact " + std::to_string(o.other) +
           " is " + io::three_digits(o.separation) + " m from closing, within the estimate's " +
           "uncertainty of that distance (" + io::three_digits(o.uncertainty) +
           " m): which closes first is not resolved, and no peak after it is bounded; reduce " +
           knob + " (now " + io::three_digits(e.value) + ")";
  }
  const CoordinatePeak* worst = nullptr;
  for (const CoordinatePeak& c : digest.coordinates) {
    if (c.name == a.worst) worst = &c;
  }
  const std::string peak = worst != nullptr ? io::three_digits(worst->peak) : "?";
  const std::string error = worst != nullptr ? io::three_digits(worst->error) : "?";
  return "accuracy: the peak |" + a.worst + "| " + peak + " has an estimated error of " +
         error + " (" + io::three_digits(100.0 * a.worst_relative) + " % of it), above " +
         "solver.accuracy = " + io::three_digits(100.0 * a.target) + " %; reduce " + knob +
         " (now " + io::three_digits(e.value) + ")";
}

}  // namespace nsb::runs
