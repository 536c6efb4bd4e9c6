// The numerical error of a run's numbers, estimated by a companion run and Richardson's
// extrapolation at the method's measured order (docs/error-estimates.md, where the constants
// below are derived):
//
//   p_h - p ≈ C h^p  and  p_rh - p ≈ C (r h)^p  give  |p_h - p| ≈ |p_h - p_rh| / (r^p - 1)
//
// Moreau–Jean's companion takes the step r h = 2 h; the adaptive methods' (event-driven,
// compliance) takes the tolerance r tol = 100 tol, their error being C tol^p. The order p is
// the lowest measured with impacts (the nonsmooth order), never the smooth one.
#pragma once

#include "integrators/run.hpp"
#include "runs/digest.hpp"

#include <optional>
#include <string>
#include <utility>

namespace nsb::runs {

// Moreau–Jean: the step ratio, and the order with impacts: 0.95 is the lowest order measured
// on the bridge (verification/moreau_order_check.cpp, excitations 5 and 7; the bouncing ball
// 1.02, two simultaneous contacts 1.00), below the method's order 1 with impacts.
inline constexpr double kMoreauStepRatio = 2.0;
inline constexpr double kMoreauOrder = 0.95;
// The adaptive methods: the tolerance ratio of the companion.
inline constexpr double kToleranceRatio = 100.0;
// Event-driven: error ≈ 1.89 tol^0.912 on the impact oscillator with impacts
// (verification/measured_orders_check.cpp, section 3, asserted 1 ± 0.12); 0.88 is the lowest
// slope that check admits.
inline constexpr double kEventDrivenOrder = 0.88;
// Compliance: no order in its tolerance is measured, so the estimate is |p_tol - p_100tol|
// itself (factor 1, the order ln 2 / ln 100 ≈ 0.15 that makes 100^p - 1 = 1): it assumes only
// that the run's error is at most half the companion's.
inline constexpr double kComplianceOrder = 0.150514997831990598;  // ln 2 / ln 100

// What the companion run changes.
struct CompanionPlan {
  integrators::RunConfig config;  // the run's options with the step or tolerance changed
  std::string setting;            // "step" or "tolerance"
  double value = 0.0;             // the run's
  double companion_value = 0.0;   // the companion's
  double order = 0.0;             // p
  double factor = 0.0;            // 1 / ((companion_value / value)^p - 1)
};

// What sets a run's accuracy: ("step", solver.step) for Moreau–Jean, ("tolerance",
// solver.tolerance) for the adaptive methods.
std::pair<std::string, double> accuracy_setting(const integrators::RunConfig& config);

// The companion of a run's options; std::nullopt when none can be made (Moreau–Jean whose
// 2 h exceeds the run's duration, an adaptive method whose tolerance is already at the top
// of its range). duration: end_time - the system's initial time [s].
std::optional<CompanionPlan> companion_plan(const integrators::RunConfig& config,
                                            double duration);

// Sets the errors of run's peaks, coordinate peaks, impact count and first impact time from
// the companion's digest, and the estimate's plan fields; estimate.computed = true.
void apply_estimate(Digest& run, const integrators::Recorder& run_history,
                    const Digest& companion, const integrators::Recorder& companion_history,
                    const CompanionPlan& plan);

// The run judged against solver.accuracy = target: met when every generalized coordinate's
// error estimate is at most target times its peak. Not judged without an estimate.
Accuracy judge_accuracy(const Digest& digest, double target);

// The first impact's time in a history's events [s]; NaN without an impact.
double first_impact_time(const integrators::Recorder& history);

// The "accuracy: ..." warning of a run whose estimate exceeds its target, or of a run whose
// estimate could not be made (the companion did not reach a result); empty otherwise.
std::string accuracy_warning(const Digest& digest);

}  // namespace nsb::runs
