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
#include <vector>

namespace nsb::runs {

// Moreau–Jean: the step ratio, and the order with impacts: 0.95 is the lowest order measured
// on the bridge (verification/moreau_order_check.cpp, excitations 5 and 7; the bouncing ball
// 1.02, two simultaneous contacts 1.00), below the method's order 1 with impacts. It predicts
// how the error of a whole run falls with its step (refined_value).
inline constexpr double kMoreauStepRatio = 2.0;
inline constexpr double kMoreauOrder = 0.95;
// Moreau–Jean's order in the extrapolation of a peak's error: the lower quartile of the orders
// at which the deck peaks' true errors fall with the step on the shipped bridges (one decade
// of step, 1e-4 to 1e-3 s and 1e-3 to 1e-2 s: lower quartile 0.58, median 0.95;
// docs/error-estimates.md, "Effectivity on the bridge"). A peak reached at an impact has the
// impact's instant, off by up to a step, and what follows it; its error falls more slowly
// than the run's, and half the order keeps the factor 1 / (2^0.5 - 1) = 2.41 on the side of
// the slow peaks.
inline constexpr double kMoreauPeakOrder = 0.5;
// Moreau–Jean with adaptive steps (solver.local_tolerance > 0): the companion takes the local
// tolerance kMoreauToleranceRatio times looser, and the error is taken as C tol^p with
// p = kAdaptiveMoreauOrder (docs/moreau-jean.md, "The companion of an adaptive run").
inline constexpr double kMoreauToleranceRatio = 10.0;
inline constexpr double kAdaptiveMoreauOrder = 0.5;
// The adaptive methods: the tolerance ratio of the companion.
inline constexpr double kToleranceRatio = 100.0;
// Compliance: no order in its tolerance is measured, so the estimate is |p_tol - p_100tol|
// itself (factor 1, the order ln 2 / ln 100 ≈ 0.15 that makes 100^p - 1 = 1): it assumes only
// that the run's error is at most half the companion's.
inline constexpr double kComplianceOrder = 0.150514997831990598;  // ln 2 / ln 100
// Event-driven: the error goes as tol^0.912 on the impact oscillator (four impacts,
// verification/measured_orders_check.cpp, section 3), but not on the bridge: the deck peaks'
// true errors on the shipped bridge scenes at tolerances 1e-8, 1e-6 and 1e-4 fall with orders
// of lower quartile 0.12 and median 0.43 (docs/error-estimates.md, "Coarse steps warn"): a
// pounding found at one tolerance and not at another moves a peak whatever the tolerance.
// The estimate assumes what the compliance method's does, factor 1.
inline constexpr double kEventDrivenOrder = kComplianceOrder;

// solver.adapt (docs/error-estimates.md, "Choosing the step"): a run is repeated with a finer
// step or a tighter tolerance while its estimate exceeds solver.accuracy, at most
// kAdaptAttempts times in all. Moreau–Jean's next step is the one the estimate predicts at
// the order kMoreauOrder, with the safety factor kAdaptSafety on the target, kept between
// kAdaptMinStepRatio and kAdaptMaxStepRatio times the step (one estimate can be off by a
// factor of ten, so one attempt never refines by more than 4; at least by 2, so that every
// attempt makes progress and all of them cost at most twice the last); the adaptive methods divide
// their tolerance by kAdaptToleranceDivisor (the compliance method's order in its tolerance is
// not measured, and event-driven's error goes as tol^0.9: one decade of tolerance is about
// one decade of error).
inline constexpr int kAdaptAttempts = 6;
inline constexpr double kAdaptSafety = 0.5;
inline constexpr double kAdaptMinStepRatio = 0.25;
inline constexpr double kAdaptMaxStepRatio = 0.5;
inline constexpr double kAdaptToleranceDivisor = 10.0;

// The relative floor below which two methods' peaks agree whatever their estimates: the
// run's solver.accuracy times the run's peak (a difference the user's own target accepts).
// The cross-check's warning is for |difference| > error_run + error_other + floor.

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

// The impact-order check (docs/error-estimates.md, "Impacts in an unresolved order"): at each
// impact of contact c in the run, every other contact d still open and closing (gap rate
// below -kClosingRate) has the separation s = g_d - g_c > 0; the companion's impact of c (the
// nearest in time, when the run's impact is also the nearest to it) gives s'. When
// s < factor |s - s'| (and that uncertainty exceeds kOrderFloor), the run cannot tell
// whether c or d closes first, and what follows depends on it: the earliest such impact.
// Only d on c's face (labels[].face; every d without labels): two corners of one face strike
// with torques of opposite signs, so their order decides the sense of the rotation the impact
// induces (the paper's mechanism); contacts of different faces, e.g. diagonal corners at the
// two abutments, induce rotations of one sense whichever strikes first. And only a d that
// still closes after c's impact at least kOrderConsequence times c's closing speed: a corner
// that c's impact stops, or nearly, strikes softly or not at all, whichever the order.
// stepped (Moreau–Jean): a d that closes within the companion's step of c's impact (s below
// d's closing speed times that step) is left out: the companion takes the two in one impact
// problem, so it cannot order them and its s' measures nothing; finer orders belong to the
// run's own error, which the companion sees. Contacts removed (a broken key) are left out
// from their removal on.
inline constexpr double kClosingRate = 1e-6;  // [m/s], event_velocity_tolerance's default
inline constexpr double kOrderFloor = 1e-9;   // [m]: round-off in a symmetric impact's gaps
inline constexpr double kOrderConsequence = 0.3;
UnresolvedImpactOrder impact_order(const integrators::Recorder& run,
                                   const integrators::Recorder& companion,
                                   const std::vector<ContactLabel>& labels, double factor,
                                   bool stepped);

// The peak a coordinate's error is judged against: its own, and at least the round-off of
// the largest coordinate's peak (kRoundOff times it, in the coordinates' own units as
// ContactTolerances::gap takes them). A deck that does not turn has a rotation of round-off
// alone (1e-19 to 1e-16 rad after symmetric impacts, against translations of 0.2 m), and its
// relative error is not a number any step or tolerance can bring below a target.
double judged_peak(const Digest& digest, const CoordinatePeak& coordinate);

// The run judged against solver.accuracy = target: met when every generalized coordinate's
// error estimate is at most target times its judged peak. Not judged without an estimate.
Accuracy judge_accuracy(const Digest& digest, double target);

// The first impact's time in a history's events [s]; NaN without an impact.
double first_impact_time(const integrators::Recorder& history);

// The next step or tolerance of an adapting run (solver.adapt) after an attempt with
// `value` whose largest relative error estimate was worst_relative (NaN: no estimate, or the
// attempt was not a result) against the relative target; setting: "step" or "tolerance".
double refined_value(const std::string& setting, double value, double worst_relative,
                     double target);

// The cross-check of a run against the same scene under another method: each coordinate's
// peak of `other` beside the run's, their difference, and whether it is within the two
// estimates plus floor = accuracy x the run's peak; the other run's impact count and first
// impact with their errors. Sets method, status (from other_status), coordinates, impacts,
// first_impact and floor; the caller sets warnings and cpu_seconds.
// run_first_impact, other_first_impact: the two runs' first impact times (first_impact_time).
CrossCheck compare_runs(const Digest& run, const Digest& other, double run_first_impact,
                        double other_first_impact, const std::string& other_method,
                        const std::string& other_status, double accuracy);

// The "cross_check: ..." warnings of a cross-check: one per coordinate whose difference
// exceeds what the estimates allow, naming both peaks; one when the other run is not a result.
// run_method: the run's own method.
std::vector<std::string> cross_check_warnings(const Digest& run, const std::string& run_method,
                                              const CrossCheck& check);

// The "accuracy: ..." warning of a run whose estimate exceeds its target, or of a run whose
// estimate could not be made (the companion did not reach a result); empty otherwise.
std::string accuracy_warning(const Digest& digest);

}  // namespace nsb::runs
