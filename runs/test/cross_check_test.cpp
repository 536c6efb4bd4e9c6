// Tests of the cross-check (runs::RunRequest::cross_check, docs/error-estimates.md,
// "Cross-checks"): the comparison and its warning from hand-made digests; a shipped bridge
// under Moreau–Jean and event-driven at its own settings agrees; the compliance method with a
// contact stiffness 1e-4 of its default against Moreau–Jean does not, and says so with both
// numbers; every pair of methods runs; an unknown method is bad input.
#include "runs/estimate.hpp"
#include "runs/files.hpp"
#include "runs/run.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace nsb::runs {
namespace {

const std::string kScenes = NSB_SCENES_DIR;

// Excitation 7's first 4.5 s: the deck strikes the abutments from 3.96 s on, so the peaks
// include impacts, and each run lasts a fraction of a second.
RunRecord exc7(const std::string& method, const std::string& cross,
               std::vector<std::string> more = {}) {
  std::vector<std::string> o{"solver.end_time=4.5"};
  o.insert(o.end(), more.begin(), more.end());
  RunRequest r{kScenes + "/bridge-exc7.toml", o, method, {}};
  r.cross_check = cross;
  return execute(r);
}

std::size_t count_prefix(const std::vector<std::string>& warnings, const std::string& prefix) {
  std::size_t n = 0;
  for (const auto& w : warnings) n += w.rfind(prefix, 0) == 0 ? 1 : 0;
  return n;
}

Digest digest_of(double peak, double error) {
  Digest d;
  d.coordinates.push_back({"theta", peak, 0.0, error});
  return d;
}

}  // namespace

TEST_CASE("compare_runs: a difference within the two estimates and the floor agrees") {
  // Peaks 1.00 ± 0.01 and 1.05 ± 0.02, accuracy 0.01: allowed = 0.01 + 0.02 + 0.01 x 1.00 =
  // 0.04 < 0.05 = |difference|: they differ. With accuracy 0.025 allowed = 0.055: they agree.
  const Digest run = digest_of(1.00, 0.01);
  const Digest other = digest_of(1.05, 0.02);
  CrossCheck x = compare_runs(run, other, 3.0, 3.5, "event_driven", "completed", 0.01);
  REQUIRE(x.coordinates.size() == 1);
  CHECK(x.compared);
  CHECK(x.coordinates[0].peak == 1.05);
  CHECK(x.coordinates[0].difference == doctest::Approx(-0.05));
  CHECK(x.coordinates[0].allowed == doctest::Approx(0.04));
  CHECK_FALSE(x.coordinates[0].agrees);
  CHECK(x.first_impact_difference == doctest::Approx(-0.5));
  const std::vector<std::string> w = cross_check_warnings(run, "moreau", x);
  REQUIRE(w.size() == 1);
  CHECK(w[0] == "cross_check: the peak |theta| is 1 under moreau and 1.05 under event_driven, "
                "a difference of 0.05 beyond the two estimates (0.01 and 0.02) and the floor "
                "0.01 (solver.accuracy x the peak)");
  x = compare_runs(run, other, 3.0, 3.5, "event_driven", "completed", 0.025);
  CHECK(x.coordinates[0].agrees);
  CHECK(cross_check_warnings(run, "moreau", x).empty());
  // Without estimates (NaN errors) the floor alone decides: 0.05 > 0.02 x 1.00.
  x = compare_runs(digest_of(1.0, NAN), digest_of(1.05, NAN), NAN, NAN, "compliance",
                   "completed", 0.02);
  CHECK_FALSE(x.coordinates[0].agrees);
  CHECK(x.coordinates[0].allowed == doctest::Approx(0.02));
}

TEST_CASE("a cross-check whose run is not a result warns that nothing was compared") {
  CrossCheck x;
  x.method = "compliance";
  x.status = "diverged";
  const std::vector<std::string> w = cross_check_warnings(digest_of(1.0, 0.0), "moreau", x);
  REQUIRE(w.size() == 1);
  CHECK(w[0] == "cross_check: the run under compliance ended diverged; the peaks are not "
                "cross-checked");
}

TEST_CASE("Moreau–Jean and event-driven agree on a shipped bridge at its own settings") {
  const RunRecord r = exc7("moreau", "event_driven");
  const CrossCheck& x = r.digest.cross_check;
  CHECK(x.method == "event_driven");
  CHECK(x.compared);
  REQUIRE(x.coordinates.size() == 3);
  for (const CrossPeak& p : x.coordinates) {
    CAPTURE(p.name);
    CHECK(p.agrees);
    // The two methods converge to one answer (verification/moreau_order_check.cpp): measured
    // differences 1.4e-4 (x), 1.8e-4 (y) and 6.0e-4 (theta) of the peaks; 3e-3 is 5 x the
    // largest.
    const double peak = r.digest.coordinates[&p - x.coordinates.data()].peak;
    CHECK(std::abs(p.difference) <= 3e-3 * peak);
  }
  // Both count the deck's five poundings of this window; Moreau–Jean dates the first at the
  // end of its step: measured 1.47e-4 s apart, 3e-4 s is twice that.
  CHECK(x.impacts == r.digest.count(integrators::EventKind::kImpact));
  CHECK(std::abs(x.first_impact_difference) <= 3e-4);
  CHECK(count_prefix(r.digest.warnings, "cross_check:") == 0);
  const std::string json = summary_json(r);
  CHECK(json.find("\"cross_check\": {\"method\": \"event_driven\"") != std::string::npos);
}

TEST_CASE("compliance at 1e-4 of its contact stiffness disagrees with Moreau–Jean, and warns") {
  // The soft contact lets the deck into the abutments: theta's peak is 0.00171 against
  // Moreau–Jean's 0.00134 (27 %), far beyond the estimates (about 1e-6) and the 1 % floor.
  const RunRecord r = exc7("compliance", "moreau", {"solver.stiffness_factor=1e-4"});
  const CrossCheck& x = r.digest.cross_check;
  REQUIRE(x.compared);
  CHECK_FALSE(x.coordinates[2].agrees);
  const std::size_t warned = count_prefix(r.digest.warnings, "cross_check: the peak |");
  CHECK(warned >= 1);
  bool names_theta = false;
  for (const auto& w : r.digest.warnings) {
    if (w.rfind("cross_check: the peak |theta| is ", 0) == 0) {
      names_theta = w.find(" under compliance and ") != std::string::npos &&
                    w.find(" under moreau") != std::string::npos;
    }
  }
  CHECK(names_theta);
  // The warnings reach result.warnings too, which --strict counts.
  CHECK(count_prefix(r.result.warnings, "cross_check:") == warned);
}

TEST_CASE("the cross-check runs between every pair of methods") {
  // A 1 s window (before the first impact): every pair ends with a comparison.
  const char* methods[] = {"moreau", "event_driven", "compliance"};
  for (const char* a : methods) {
    for (const char* b : methods) {
      if (std::string(a) == b) continue;
      CAPTURE(a);
      CAPTURE(b);
      std::vector<std::string> o{"solver.end_time=1"};
      RunRequest req{kScenes + "/bridge-exc7.toml", o, a, {}};
      req.cross_check = b;
      const RunRecord r = execute(req);
      CHECK(r.digest.cross_check.method == b);
      CHECK(r.digest.cross_check.compared);
      CHECK(r.digest.cross_check.coordinates.size() == r.digest.coordinates.size());
    }
  }
}

TEST_CASE("an unknown cross-check method is bad input, before any run") {
  RunRequest req{kScenes + "/bridge-exc7.toml", {}, "moreau", {}};
  req.cross_check = "runge_kutta";
  CHECK_THROWS_WITH_AS(prepare(req),
                       "cross_check: unknown method \"runge_kutta\"; expected one of moreau, "
                       "event_driven, compliance",
                       std::invalid_argument);
}

}  // namespace nsb::runs
