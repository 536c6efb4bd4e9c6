#include "runs/estimate.hpp"

#include "io/csv.hpp"

#include <algorithm>
#include <cmath>
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

}  // namespace

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

Accuracy judge_accuracy(const Digest& digest, double target) {
  Accuracy a;
  a.target = target;
  if (!digest.estimate.computed) return a;
  a.judged = true;
  a.met = true;
  a.worst_relative = 0.0;
  for (const CoordinatePeak& c : digest.coordinates) {
    // A peak of zero with a zero error is exact; with a nonzero one, infinitely wrong.
    const double rel = c.error == 0.0 ? 0.0 : c.error / c.peak;
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
    p.allowed = known(mine.error) + known(p.error) + accuracy * std::abs(mine.peak);
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
                ") and the floor " + io::three_digits(check.floor * std::abs(mine.peak)) +
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
