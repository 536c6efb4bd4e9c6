// The limit states a bridge watches (docs/limit-states.md) against values read from the run's
// own history, not from the watcher:
//  (a) unseating: the benchmark bridge under excitation 5 with a seat too long to be lost
//      gives the peak opening o* of the abutment joints (max over steps and corners of g_N,
//      every step recorded); a seat of o* (1 - 1e-6) is lost at the first step whose opening
//      exceeds it, and the run stops there with status "unseated"; a seat of o* (1 + 1e-6) is
//      kept and the run completes with margin seat - o*;
//  (b) drift and closure on a short free vibration (no ground motion: the bent tops' drift is
//      the deck's displacement at the bent, |(x, y + s theta)| / H): the peak drift ratio and
//      the first time it reaches the limit, and each joint's first closure (a gap <= 0 or an
//      impact event of one of its corners), from the history and the events.
#include "integrators/recorder.hpp"
#include "integrators/run.hpp"
#include "models/bridge_parts.hpp"
#include "scene/scene.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace {

namespace ni = nsb::integrators;
namespace nm = nsb::models;

const std::string kScene = std::string(NSB_SCENES_DIR) + "/bridge-exc5.toml";
// Lengths of O(0.01 m) from a few subtractions: round-off ~ 1e-17 m.
constexpr double kLengthTol = 1e-15;

struct Run {
  ni::RunResult result;
  ni::Recorder history;
  std::map<std::string, ni::LimitStateValue> limits;
};

Run run(std::vector<std::string> overrides) {
  overrides.push_back("output.sample_dt=0");  // every accepted step is a sample
  nsb::scene::Scene scene = nsb::scene::load_scene(kScene, overrides);
  ni::Recorder history(*scene.system, scene.output.sample_dt);
  ni::RunResult result = ni::integrate(*scene.system, scene.run, history, {});
  Run r{std::move(result), std::move(history), {}};
  for (const auto& v : scene.system->limit_states()) r.limits[v.name] = v;
  return r;
}

// History column of contact c's gap (0-based contact index).
std::size_t gap_column(const ni::Recorder& h, int c) {
  const auto& info = h.column_info();
  for (std::size_t k = 0; k < info.size(); ++k) {
    if (info[k].kind == ni::ColumnKind::kGap && info[k].index == c) return k;
  }
  FAIL("no gap column of contact " << c);
  return 0;
}

std::size_t column(const ni::Recorder& h, const std::string& name) {
  const auto& cols = h.columns();
  const auto it = std::find(cols.begin(), cols.end(), name);
  REQUIRE(it != cols.end());
  return static_cast<std::size_t>(it - cols.begin());
}

// The opening of the joint of contacts (a, b) at sample r: the larger gap.
double opening(const ni::Recorder& h, std::size_t r, int a, int b) {
  return std::max(h.at(r, gap_column(h, a)), h.at(r, gap_column(h, b)));
}

std::string seat(double length) {
  char text[64];
  std::snprintf(text, sizeof text, "model.abutments.seat_length=%.17g", length);
  return text;
}

}  // namespace

TEST_CASE("unseating: a seat 1e-6 shorter than the peak opening is lost, 1e-6 longer kept") {
  const Run free = run({seat(100.0)});
  REQUIRE(free.result.status == ni::RunStatus::kCompleted);
  const ni::Recorder& h = free.history;
  // Contacts 0, 1: the left abutment joint; 2, 3: the right one (models/bridge_parts.hpp).
  double peak = 0.0;
  for (std::size_t r = 0; r < h.rows(); ++r) {
    peak = std::max({peak, opening(h, r, 0, 1), opening(h, r, 2, 3)});
  }
  MESSAGE("peak opening of the abutment joints " << peak << " m");
  REQUIRE(peak > 0.0127);  // the joints open beyond their 0.0127 m at rest
  const double margin = std::min(free.limits.at("unseating_left").margin,
                                 free.limits.at("unseating_right").margin);
  CHECK(margin == doctest::Approx(100.0 - peak).epsilon(kLengthTol / 100.0));

  const double short_seat = peak * (1.0 - 1e-6);
  double t_lost = std::numeric_limits<double>::quiet_NaN();
  std::string lost;
  for (std::size_t r = 0; r < h.rows() && std::isnan(t_lost); ++r) {
    if (opening(h, r, 0, 1) > short_seat) t_lost = h.at(r, 0), lost = "unseating_left";
    else if (opening(h, r, 2, 3) > short_seat) t_lost = h.at(r, 0), lost = "unseating_right";
  }
  MESSAGE("seat " << short_seat << " m lost at t = " << t_lost << " s (" << lost << ")");
  const Run cut = run({seat(short_seat)});
  CHECK(cut.result.status == ni::RunStatus::kUnseated);
  CHECK(ni::to_string(cut.result.status) == std::string("unseated"));
  CHECK(cut.result.end_time == t_lost);
  CHECK(cut.result.failure_time == t_lost);
  CHECK(cut.limits.at(lost).exceeded);
  CHECK(cut.limits.at(lost).time == t_lost);
  CHECK(cut.limits.at(lost).margin < 0.0);

  const double long_seat = peak * (1.0 + 1e-6);
  const Run kept = run({seat(long_seat)});
  CHECK(kept.result.status == ni::RunStatus::kCompleted);
  CHECK(!kept.limits.at("unseating_left").exceeded);
  CHECK(!kept.limits.at("unseating_right").exceeded);
  const double kept_margin = std::min(kept.limits.at("unseating_left").margin,
                                      kept.limits.at("unseating_right").margin);
  CHECK(kept_margin == doctest::Approx(long_seat - peak).epsilon(1e-6));
  CHECK(kept_margin > 0.0);
}

TEST_CASE("drift and closure: first times and peaks from the history and the events") {
  const double limit = 0.004;
  const Run r = run({"model.excitation.scale=0", "model.deck.initial_velocity=[1.0, 0.4, 0.01]",
                     "solver.end_time=3", "model.limit_states.drift_ratio=0.004"});
  REQUIRE(r.result.status == ni::RunStatus::kCompleted);
  const ni::Recorder& h = r.history;
  const nm::BridgeDesign bp = nm::BridgeDesign::benchmark();
  const double heights[3] = {1.83, 2.44, 1.52};  // scenes/bridge-exc5.toml
  const std::size_t cx = column(h, "x"), cy = column(h, "y"), ct = column(h, "theta");
  for (std::size_t j = 0; j < 3; ++j) {
    const double s = bp.bents[j].position;
    double peak = 0.0, first = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t k = 0; k < h.rows(); ++k) {
      const double ratio = std::hypot(h.at(k, cx), h.at(k, cy) + s * h.at(k, ct)) / heights[j];
      peak = std::max(peak, ratio);
      if (std::isnan(first) && ratio >= limit) first = h.at(k, 0);
    }
    const auto& v = r.limits.at("drift_bent_" + std::to_string(j + 1));
    MESSAGE("bent " << j + 1 << ": peak drift ratio " << peak << ", first >= limit at " << first);
    CHECK(v.margin == doctest::Approx(limit - peak).epsilon(1e-12));
    CHECK(v.exceeded == !std::isnan(first));
    if (v.exceeded) CHECK(v.time == first);
  }
  // Closure: the first sample with a gap <= 0 or an impact event of the joint's corners.
  const std::pair<const char*, int> joints[] = {{"closure_left", 0}, {"closure_right", 2}};
  for (const auto& [name, c0] : joints) {
    double first = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < h.rows() && !std::isfinite(first); ++k) {
      if (std::min(h.at(k, gap_column(h, c0)), h.at(k, gap_column(h, c0 + 1))) <= 0.0) {
        first = h.at(k, 0);
      }
    }
    for (const auto& e : h.events()) {
      if (e.kind == ni::EventKind::kImpact && (e.contact == c0 + 1 || e.contact == c0 + 2)) {
        first = std::min(first, e.t);
      }
    }
    const auto& v = r.limits.at(name);
    MESSAGE(std::string(name) << ": first closure at " << first << " s");
    CHECK(v.exceeded == std::isfinite(first));
    if (v.exceeded) CHECK(v.time == first);
    CHECK(v.margin <= (std::isfinite(first) ? 0.0 : 0.0127));
  }
  // vx > 0: the deck strikes the right abutment.
  CHECK(r.limits.at("closure_right").exceeded);
}
