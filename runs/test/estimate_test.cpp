// Tests of the peaks over every step and of their error estimates (runs/estimate.hpp,
// docs/error-estimates.md): the sampling interval changes the rows, never the peaks; the
// companion plans and Richardson's factors of each method; the errors and the accuracy verdict
// from hand-made digests; a shipped scene's estimate, its warning and its keys in summary.json.
#include "runs/estimate.hpp"
#include "runs/files.hpp"
#include "runs/run.hpp"
#include "runs/trajectory.hpp"

#include "integrators/run.hpp"
#include "testsupport/systems.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace nsb::runs {
namespace {

const std::string kScenes = NSB_SCENES_DIR;

// Two doubles equal as values, NaN equal to NaN.
bool same(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

// Excitation 7's first 4.5 s: the deck strikes the abutments (impacts) from 3.96 s on (the
// first impact of Moreau-Jean at the scene's step). Moreau-Jean at 5e-4 s: the property
// checked (peaks that do not depend on sample_dt) holds at any step, and the test stays
// short under the sanitizers.
RunRecord exc7(const std::string& method, const std::string& sample_dt,
               std::vector<std::string> more = {}) {
  std::vector<std::string> o{"solver.end_time=4.5", "output.sample_dt=" + sample_dt,
                             "solver.error_estimate=false"};
  if (method == "moreau") o.push_back("solver.step=5e-4");
  o.insert(o.end(), more.begin(), more.end());
  return execute({kScenes + "/bridge-exc7.toml", o, method, {}});
}

// The extremes of one column over the rows of a history, the first row reaching each: the
// peaks' definition applied to the rows that sample_dt = 0 records (every step).
ColumnPeak peak_of_rows(const integrators::Recorder& h, std::size_t c) {
  ColumnPeak p;
  p.max = -INFINITY, p.min = INFINITY, p.t_max = p.t_min = NAN;
  for (std::size_t r = 0; r < h.rows(); ++r) {
    const double v = h.at(r, c);
    if (!std::isfinite(v)) continue;
    if (v > p.max) p.max = v, p.t_max = h.at(r, 0);
    if (v < p.min) p.min = v, p.t_min = h.at(r, 0);
  }
  return p;
}

// Every generalized coordinate's estimate in run is at least its distance from the same
// coordinate's peak in ref.
void check_estimates_cover(const RunRecord& run, const RunRecord& ref) {
  for (std::size_t c = 0; c < run.digest.coordinates.size(); ++c) {
    const CoordinatePeak& p = run.digest.coordinates[c];
    CAPTURE(p.name);
    CAPTURE(p.peak);
    CHECK(p.error >= std::abs(p.peak - ref.digest.coordinates[c].peak));
  }
}

}  // namespace

TEST_CASE("the peaks are those of every step: output.sample_dt changes the rows only") {
  for (const std::string method : {"moreau", "event_driven", "compliance"}) {
    CAPTURE(method);
    const RunRecord fine = exc7(method, "1e-4");
    const RunRecord coarse = exc7(method, "1.0");
    const RunRecord every = exc7(method, "0");
    REQUIRE(integrators::succeeded(fine.result.status));
    CHECK(coarse.history.rows() < fine.history.rows());
    // The deck strikes the abutments within the window: impacts under every method (docs/
    // outputs.md, "One event vocabulary").
    CHECK(fine.digest.count(integrators::EventKind::kImpact) > 0);
    REQUIRE(fine.digest.peaks.size() == coarse.digest.peaks.size());
    for (std::size_t i = 0; i < fine.digest.peaks.size(); ++i) {
      const ColumnPeak& a = fine.digest.peaks[i];
      const ColumnPeak& b = coarse.digest.peaks[i];
      CAPTURE(a.column);
      CHECK(same(a.max, b.max));
      CHECK(same(a.t_max, b.t_max));
      CHECK(same(a.min, b.min));
      CHECK(same(a.t_min, b.t_min));
      CHECK(same(a.abs_max, b.abs_max));
      CHECK(same(a.t_abs_max, b.t_abs_max));
      // Against the rows of the run that records every step.
      const ColumnPeak rows = peak_of_rows(every.history, i + 1);
      CHECK(same(a.max, rows.max));
      CHECK(same(a.min, rows.min));
      CHECK(same(a.t_max, rows.t_max));
      CHECK(same(a.t_min, rows.t_min));
    }
    for (std::size_t i = 0; i < fine.digest.coordinates.size(); ++i) {
      CHECK(fine.digest.coordinates[i].peak == coarse.digest.coordinates[i].peak);
    }
    CHECK(fine.digest.max_penetration == coarse.digest.max_penetration);
    CHECK(fine.digest.warnings == coarse.digest.warnings);
  }
}

TEST_CASE("the companion of each method and Richardson's factor 1 / (r^p - 1)") {
  integrators::MoreauJeanOptions mj;
  mj.step = 1e-3;
  mj.end_time = 10.0;
  const auto m = companion_plan(mj, 10.0);
  REQUIRE(m.has_value());
  CHECK(m->setting == "step");
  CHECK(std::get<integrators::MoreauJeanOptions>(m->config).step == 2e-3);
  CHECK(m->order == kMoreauPeakOrder);
  // p = 1/2: factor 1 / (sqrt(2) - 1) = sqrt(2) + 1 = 2.41421.
  CHECK(m->factor == doctest::Approx(2.41421).epsilon(1e-5));
  CHECK_FALSE(companion_plan(mj, 1.5e-3).has_value());  // 2 h beyond the run's duration

  integrators::EventDrivenOptions ed;
  ed.tolerance = 1e-8;
  const auto e = companion_plan(ed, 10.0);
  REQUIRE(e.has_value());
  CHECK(std::get<integrators::EventDrivenOptions>(e->config).tolerance == doctest::Approx(1e-6));
  // p = ln 2 / ln 100: 100^p = 2, factor 1 / (2 - 1) = 1, |p_tol - p_100tol| itself.
  CHECK(e->factor == doctest::Approx(1.0).epsilon(1e-12));
  ed.tolerance = 0.6;  // already above half the range's top: no looser companion
  CHECK_FALSE(companion_plan(ed, 10.0).has_value());

  integrators::ComplianceOptions co;
  co.tolerance = 1e-8;
  const auto c = companion_plan(co, 10.0);
  REQUIRE(c.has_value());
  CHECK(c->factor == doctest::Approx(1.0).epsilon(1e-12));  // |p_tol - p_100tol| itself
  co.tolerance = 1e-3;  // 100 tol = 0.1 is the range's open top: the companion takes 0.05
  CHECK(std::get<integrators::ComplianceOptions>(companion_plan(co, 10.0)->config).tolerance ==
        0.05);
}

TEST_CASE("errors from a companion's digest, and the verdict against the accuracy") {
  // Run: |x| 2.0, |theta| 1e-3, first impact at 0.30 s; companion: |x| 1.9, |theta| 1.5e-3,
  // first impact at 0.32 s, one impact more. p = 1, r = 2: factor 1.
  testsupport::TwoCornerBody s({});
  integrators::Recorder run_history(s, 0.0), companion_history(s, 0.0);
  run_history.event(0.30, 1, integrators::EventKind::kImpact);
  companion_history.event(0.32, 1, integrators::EventKind::kImpact);
  companion_history.event(0.40, 2, integrators::EventKind::kImpact);
  Digest run = make_digest(run_history, {});
  Digest companion = make_digest(companion_history, {});
  run.coordinates = {{"x", 2.0, 0.0}, {"theta", 1e-3, 0.0}};
  companion.coordinates = {{"x", 1.9, 0.0}, {"theta", 1.5e-3, 0.0}};
  run.peaks[0].abs_max = 2.0;
  companion.peaks[0].abs_max = 2.5;
  const CompanionPlan plan{integrators::MoreauJeanOptions{}, "step", 1e-3, 2e-3, 1.0, 1.0};
  run.estimate.enabled = true;
  apply_estimate(run, run_history, companion, companion_history, plan);
  CHECK(run.estimate.computed);
  CHECK(run.peaks[0].error == 0.5);
  CHECK(run.coordinates[0].error == doctest::Approx(0.1).epsilon(1e-12));
  CHECK(run.coordinates[1].error == doctest::Approx(5e-4).epsilon(1e-12));
  CHECK(run.estimate.impacts == 1);
  CHECK(run.estimate.impacts_error == 1.0);
  CHECK(run.estimate.first_impact == 0.30);
  CHECK(run.estimate.first_impact_error == doctest::Approx(0.02).epsilon(1e-9));

  // |x|: 0.1 / 2 = 5 %; |theta|: 5e-4 / 1e-3 = 50 %, the worst.
  run.accuracy = judge_accuracy(run, 0.6);
  CHECK(run.accuracy.judged);
  CHECK(run.accuracy.met);
  CHECK(accuracy_warning(run).empty());
  run.accuracy = judge_accuracy(run, 0.1);
  CHECK_FALSE(run.accuracy.met);
  CHECK(run.accuracy.worst == "theta");
  CHECK(run.accuracy.worst_relative == doctest::Approx(0.5));
  CHECK(accuracy_warning(run) ==
        "accuracy: the peak |theta| 0.001 has an estimated error of 0.0005 (50 % of it), above "
        "solver.accuracy = 10 %; reduce solver.step (now 0.001)");

  // A deck that does not turn: |theta| 4.7e-19 rad of round-off with an error of 1.1e-18 (the
  // measured run of a symmetric skew deck) against |x| 0.2 m. The round-off of the largest
  // peak is kRoundOff x 0.2 = 1024 x 2.22e-16 x 0.2 = 4.55e-14, so theta's relative error is
  // 1.1e-18 / 4.55e-14 = 2.4e-5, not 234 %, and the run meets 1 %.
  Digest level = run;
  level.coordinates = {{"x", 0.2, 0.0, 1e-4}, {"theta", 4.7e-19, 0.0, 1.1e-18}};
  CHECK(judged_peak(level, level.coordinates[1]) ==
        doctest::Approx(1024.0 * std::numeric_limits<double>::epsilon() * 0.2));
  CHECK(judged_peak(level, level.coordinates[0]) == 0.2);
  level.accuracy = judge_accuracy(level, 0.01);
  CHECK(level.accuracy.met);
  CHECK(level.accuracy.worst == "x");
  CHECK(level.accuracy.worst_relative == doctest::Approx(5e-4));

  // Without an estimate there is no verdict; a companion that failed says so.
  Digest plain = make_digest(run_history, {});
  plain.estimate.enabled = true;
  plain.estimate.companion_status = "diverged";
  plain.accuracy = judge_accuracy(plain, 0.01);
  CHECK_FALSE(plain.accuracy.judged);
  CHECK(accuracy_warning(plain).rfind("accuracy: no error estimate: the companion run ended "
                                      "diverged", 0) == 0);
  plain.estimate.enabled = false;
  CHECK(accuracy_warning(plain).empty());
}

// One accepted step of a two-contact history at t: the contacts' gaps [m] and gap rates [m/s]
// (the rates as the contacts' rheonomic parts, u = 0), nothing else.
void observe_gaps(integrators::Recorder& h, double t, double g1, double g2, double rate1,
                  double rate2) {
  std::vector<integrators::ContactData> c(2);
  c[0].gap_normal = g1, c[1].gap_normal = g2;
  c[0].w_normal = c[1].w_normal = integrators::Vector::Zero(3);
  c[0].what_normal = rate1, c[1].what_normal = rate2;
  using integrators::Vector;
  const Vector zero = Vector::Zero(3), none = Vector::Zero(2);
  h.observe(t, zero, zero, c, none, none, 0.0);
}

TEST_CASE("an impact whose order against another contact's closing is not resolved") {
  // Both contacts close at 0.1 m/s. Run: at 0.999 s gaps 1e-4 and 3e-4 m, contact 1 strikes
  // at 1.000 s; extrapolated over the 1 ms step the gaps are 0 and 2e-4: separation
  // s = 2e-4 m. Companion: at 0.9985 s gaps 1.5e-4 and 2e-4, contact 1 strikes at 1.000 s:
  // s' = 0.5e-4. |s - s'| = 1.5e-4; with the factor 1 the uncertainty 1.5e-4 < s (resolved),
  // with the factor 2.41 it is 3.615e-4 > s (not resolved).
  testsupport::TwoCornerBody body({});
  const auto histories = [&](bool closed, double rate2, double companion_step) {
    std::pair<integrators::Recorder, integrators::Recorder> h{{body, 0.0}, {body, 0.0}};
    observe_gaps(h.first, 0.999, 1e-4, 2e-4 - rate2 * 1e-3, -0.1, rate2);
    if (closed) h.first.event(0.5, 2, integrators::EventKind::kClose);
    h.first.impact(1.0, 1, 1.0, 0.0);
    const double t0 = 1.0 - companion_step;
    observe_gaps(h.second, t0, 0.1 * companion_step, 0.5e-4 - rate2 * companion_step, -0.1,
                 rate2);
    h.second.impact(1.0, 1, 1.0, 0.0);
    return h;
  };
  const auto [run_history, companion_history] = histories(false, -0.1, 1.5e-3);
  REQUIRE(run_history.events().size() == 1);
  CHECK(run_history.events()[0].gaps[0] == doctest::Approx(0.0).epsilon(1e-12));
  CHECK(run_history.events()[0].gaps[1] == doctest::Approx(2e-4).epsilon(1e-12));
  CHECK(run_history.events()[0].gap_interval == doctest::Approx(1e-3).epsilon(1e-9));
  CHECK_FALSE(impact_order(run_history, companion_history, {}, 1.0, false).found);
  const UnresolvedImpactOrder o = impact_order(run_history, companion_history, {}, 2.41, false);
  REQUIRE(o.found);
  CHECK(o.time == 1.0);
  CHECK(o.contact == 1);
  CHECK(o.other == 2);
  CHECK(o.separation == doctest::Approx(2e-4).epsilon(1e-9));
  CHECK(o.uncertainty == doctest::Approx(3.615e-4).epsilon(1e-9));
  // Stepped: contact 2 closes 2e-4 / 0.1 = 2 ms after contact 1, beyond the companion's
  // 1.5 ms step (found) and within a 2.5 ms one (left out: one impact problem).
  CHECK(impact_order(run_history, companion_history, {}, 2.41, true).found);
  const auto [long_run, long_companion] = histories(false, -0.1, 2.5e-3);
  CHECK(impact_order(long_run, long_companion, {}, 2.41, false).found);
  CHECK_FALSE(impact_order(long_run, long_companion, {}, 2.41, true).found);
  // Corners of two faces (diagonal corners at two abutments) are not a pair.
  const std::vector<ContactLabel> two_faces{{"abutment", "left", 0}, {"abutment", "right", 1}};
  CHECK_FALSE(impact_order(run_history, companion_history, two_faces, 2.41, false).found);
  // A corner that contact 1's impact nearly stops (0.01 m/s at the next step, below half
  // contact 1's 0.1 m/s) is no second impact of its size.
  auto [stopped_run, stopped_companion] = histories(false, -0.1, 1.5e-3);
  observe_gaps(stopped_run, 1.001, 0.0, 2e-4, 0.0, -0.01);
  CHECK_FALSE(impact_order(stopped_run, stopped_companion, {}, 2.41, false).found);
  // A contact already closed, or opening, is not closing with the impact.
  const auto [closed_run, closed_companion] = histories(true, -0.1, 1.5e-3);
  CHECK_FALSE(impact_order(closed_run, closed_companion, {}, 2.41, false).found);
  const auto [opening_run, opening_companion] = histories(false, 0.1, 1.5e-3);
  CHECK_FALSE(impact_order(opening_run, opening_companion, {}, 2.41, false).found);

  // Through the estimate: every peak's error is at least the peak, and the warning says why.
  Digest run = make_digest(run_history, {});
  Digest companion = make_digest(companion_history, {});
  run.coordinates = {{"x", 2.0, 0.0}};
  companion.coordinates = {{"x", 2.0, 0.0}};
  const CompanionPlan plan{integrators::MoreauJeanOptions{}, "step", 1e-3, 2e-3, 0.5, 2.41};
  run.estimate.enabled = true;
  apply_estimate(run, run_history, companion, companion_history, plan);
  REQUIRE(run.estimate.impact_order.found);
  CHECK(run.coordinates[0].error == 2.0);
  run.accuracy = judge_accuracy(run, 0.01);
  CHECK_FALSE(run.accuracy.met);
  CHECK(accuracy_warning(run) ==
        "accuracy: at 1 s contact 1 strikes while contact 2 is 0.0002 m from closing, within "
        "the estimate's uncertainty of that distance (0.000362 m): which closes first is not "
        "resolved, and no peak after it is bounded; reduce solver.step (now 0.001)");
}

TEST_CASE("the traced system keeps q on its grid, interpolated between accepted steps") {
  // The body starts at rest at q = 0; accepted steps of 0.03 s with x = t^2. Each grid time
  // of 0.1 s gets the chord between its two steps: at 0.1 s, between 0.09 s (0.0081) and
  // 0.12 s (0.0144): 0.0081 + (0.1 - 0.09) / 0.03 * 0.0063 = 0.0102; at 0.2 s, between 0.18 s
  // (0.0324) and 0.21 s (0.0441): 0.0402; at 0.3 s, the step at 0.3 s itself: 0.09.
  testsupport::TwoCornerBody body({});
  TracedSystem traced(body, 0.1, 0.3);
  CHECK(traced.dofs() == 3);
  integrators::Vector q = integrators::Vector::Zero(3), u = integrators::Vector::Zero(3);
  for (int k = 1; k <= 10; ++k) {
    const double t = 0.03 * k;
    q[0] = t * t;
    CHECK(traced.accept_step({t, 0.03, &q, &u, nullptr}) == integrators::StepVerdict::kContinue);
  }
  const CoordinateTrace& trace = traced.trace();
  REQUIRE(trace.rows() == 4);
  CHECK(trace.q[0] == 0.0);
  CHECK(trace.q[3] == doctest::Approx(0.0102));
  CHECK(trace.q[6] == doctest::Approx(0.0402));
  CHECK(trace.q[9] == doctest::Approx(0.09));
  CHECK(trace.q[4] == 0.0);  // y stays 0
}

TEST_CASE("the trajectory bound: two runs that peak at different instants") {
  // Run a: |x| peaks at 1.0 at t = 0.2 s; run b: at 1.0 at t = 0.4 s, and is 0.6 at 0.2 s.
  // The peaks agree (difference 0) while the trajectories differ by 0.4 at 0.2 s and 0.5 at
  // 0.4 s (a is 0.5 there): the bound is 0.5, times the factor 1.
  CoordinateTrace a{0.0, 0.1, 1, {0.0, 0.3, 1.0, 0.7, 0.5, 0.2}};
  CoordinateTrace b{0.0, 0.1, 1, {0.0, 0.2, 0.6, 0.8, -1.0, 0.4}};
  CHECK(trace_difference(a, b, 0, 0.2, 0.4) == doctest::Approx(0.5));
  CHECK(trace_difference(a, b, 0, 0.15, 0.25) == doctest::Approx(0.4));
  CHECK(trace_difference(a, b, 0, 0.51, 0.9) == 0.0);  // no common grid time
  CoordinateTrace other_grid = b;
  other_grid.dt = 0.05;
  CHECK(trace_difference(a, other_grid, 0, 0.0, 1.0) == 0.0);

  testsupport::TwoCornerBody s({});
  integrators::Recorder history(s, 0.0);
  Digest run = make_digest(history, {});
  Digest companion = make_digest(history, {});
  run.coordinates = {{"x", 1.0, 0.0}};
  companion.coordinates = {{"x", 1.0, 0.0}};
  run.peaks[0].abs_max = 1.0, run.peaks[0].t_abs_max = 0.2, run.peaks[0].error = 0.0;
  companion.peaks[0].abs_max = 1.0, companion.peaks[0].t_abs_max = 0.4;
  run.coordinates[0].error = 0.0;  // what apply_estimate gives: |1.0 - 1.0|
  // An adaptive method's plan: no floor h |u|max.
  const CompanionPlan plan{integrators::EventDrivenOptions{}, "tolerance", 1e-8, 1e-6, 1.0, 1.0};
  bound_by_trajectories(run, history, a, companion, b, plan);
  CHECK(run.coordinates[0].error == doctest::Approx(0.5));
  CHECK(run.peaks[0].error == doctest::Approx(0.5));
}

// Excitation 7's first 4.5 s (five poundings from 3.96 s) under Moreau–Jean at 10, 20 and 40
// times the scene's step: every generalized coordinate's estimate is at least its true error,
// against event-driven at tolerance 1e-10 (the reference of moreau_order_check, whose own
// error is below 1e-8 of these peaks). The difference of the peaks alone falls short here:
// at 1e-3 s |theta|'s is half its true error, at 2e-3 s |x|'s a fifth.
TEST_CASE("the estimates bound the true errors of the deck's peaks on excitation 7") {
  const std::string scene = kScenes + "/bridge-exc7.toml";
  const RunRecord ref = execute(
      {scene, {"solver.end_time=4.5", "solver.tolerance=1e-10", "solver.error_estimate=false"},
       "event_driven", {}});
  REQUIRE(integrators::succeeded(ref.result.status));
  for (const std::string step : {"1e-3", "2e-3", "4e-3"}) {
    CAPTURE(step);
    const RunRecord r =
        execute({scene, {"solver.end_time=4.5", "solver.step=" + step}, "moreau", {}});
    REQUIRE(r.digest.estimate.computed);
    check_estimates_cover(r, ref);
  }
}

// Excitation 7's whole record at 100 times the scene's step (1e-2 s): the deck's rotation
// peaks at 11.4 s, where event-driven at tolerance 1e-10 peaks at 12.2 s, 5.2e-4 rad apart.
// Each impact is dated up to a step late, and an eccentric impact can reverse the rotation,
// so the rotation after it is off by up to 2 h |omega|max. Without the reversal, the bound of
// one step's travel h |omega|max (3.6e-4 rad) is the estimate, and it falls short; with it
// the estimate is 7.2e-4 rad.
TEST_CASE("a coarse step's estimate covers an impact that reverses the rotation") {
  const std::string scene = kScenes + "/bridge-exc7.toml";
  const RunRecord ref = execute(
      {scene, {"solver.tolerance=1e-10", "solver.error_estimate=false"}, "event_driven", {}});
  REQUIRE(integrators::succeeded(ref.result.status));
  const RunRecord r = execute({scene, {"solver.step=1e-2"}, "moreau", {}});
  REQUIRE(r.digest.estimate.computed);
  check_estimates_cover(r, ref);
}

TEST_CASE("a shipped scene's estimate: errors of every peak, its cost, summary.json's keys") {
  const RunRecord r = execute(
      {kScenes + "/bridge-exc7.toml", {"solver.end_time=10", "solver.step=1e-3"}, {}, {}});
  REQUIRE(integrators::succeeded(r.result.status));
  const ErrorEstimate& e = r.digest.estimate;
  CHECK(e.enabled);
  REQUIRE(e.computed);
  CHECK(e.companion_value == 2e-3);
  CHECK(e.companion_status == "completed");
  for (const ColumnPeak& p : r.digest.peaks) {
    CAPTURE(p.column);
    CHECK(p.error >= 0.0);
  }
  for (const CoordinatePeak& c : r.digest.coordinates) CHECK(c.error >= 0.0);
  CHECK(e.companion_cpu_seconds > 0.0);
  CHECK(e.run_cpu_seconds > 0.0);
  CHECK(r.digest.accuracy.judged);
  const bool warned = std::any_of(r.digest.warnings.begin(), r.digest.warnings.end(),
                                  [](const std::string& w) { return w.rfind("accuracy:", 0) == 0; });
  CHECK(warned == !r.digest.accuracy.met);
  const std::string json = summary_json(r);
  CHECK(json.find("\"error_estimate\": {\"enabled\": true, \"computed\": true") != std::string::npos);
  CHECK(json.find("\"accuracy\": {\"target\": 0.01, \"met\": ") != std::string::npos);
  CHECK(json.find("\"step\": 0.001") != std::string::npos);

  // Off: no companion, no error, no verdict.
  const RunRecord off = execute({kScenes + "/bridge-exc7.toml",
                                 {"solver.end_time=2", "solver.error_estimate=false"}, {}, {}});
  CHECK_FALSE(off.digest.estimate.enabled);
  CHECK(std::isnan(off.digest.peaks[0].error));
  CHECK(off.digest.estimate.companion_cpu_seconds == 0.0);
  CHECK(summary_json(off).find("\"met\": null") != std::string::npos);
}

TEST_CASE("solver.accuracy and solver.error_estimate are checked like every key") {
  CHECK_THROWS_WITH_AS(execute({kScenes + "/bouncing-ball.toml", {"solver.accuracy=0"}, {}, {}}),
                       doctest::Contains("solver.accuracy"), std::invalid_argument);
  CHECK_THROWS_WITH_AS(
      execute({kScenes + "/bouncing-ball.toml", {"solver.error_estimate=2"}, {}, {}}),
      doctest::Contains("solver.error_estimate"), std::invalid_argument);
}

}  // namespace nsb::runs
