// Tests of solver.adapt (runs::run, runs/estimate.hpp refined_value, docs/error-estimates.md,
// "Choosing the step"): the next step predicted from the estimate and its bounds; a short
// bridge run that starts 20 times coarser than its scene's step ends meeting 1 % with its
// deck peaks within 1 % of a converged reference; a run that meets its target at once is the
// fixed-step run; adapt without an estimate is bad input.
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

RunRecord exc7(const std::string& method, std::vector<std::string> more) {
  std::vector<std::string> o{"solver.end_time=4.5"};
  o.insert(o.end(), more.begin(), more.end());
  return execute({kScenes + "/bridge-exc7.toml", o, method, {}});
}

}  // namespace

TEST_CASE("refined_value: the step the estimate predicts, at least h/4, h/2 without one") {
  // rel(h') = rel(h) (h'/h)^0.95 = 0.5 x target: h' = h (0.5 x 0.01 / 0.02)^(1/0.95)
  // = h x 0.25^1.0526 = 0.2326 h, below h/4: h/4.
  CHECK(refined_value("step", 1e-3, 0.02, 0.01) == doctest::Approx(2.5e-4));
  // 0.011 against 0.01: (0.5 / 1.1)^(1/0.95) = 0.4357.
  CHECK(refined_value("step", 1e-3, 0.011, 0.01) ==
        doctest::Approx(1e-3 * std::pow(0.5 / 1.1, 1.0 / 0.95)));
  // Barely above: with the safety factor 0.5 the prediction is just below h/2.
  CHECK(refined_value("step", 1e-3, 0.0101, 0.01) ==
        doctest::Approx(1e-3 * std::pow(0.5 / 1.01, 1.0 / 0.95)));
  // No estimate (a failed attempt): h/2.
  CHECK(refined_value("step", 1e-3, NAN, 0.01) == doctest::Approx(5e-4));
  // Tolerances: a decade.
  CHECK(refined_value("tolerance", 1e-6, 0.5, 0.01) == doctest::Approx(1e-7));
}

TEST_CASE("adapt: a coarse Moreau-Jean start ends meeting 1 %, within 1 % of the reference") {
  // Start at 2e-3 s (20 x the scene's 1e-4 s): the estimate of |theta| is above 1 % there.
  const RunRecord r = exc7("moreau", {"solver.step=2e-3", "solver.adapt=true"});
  const Adaptation& ad = r.digest.adaptation;
  REQUIRE(ad.enabled);
  REQUIRE(ad.attempts.size() >= 2);
  CHECK(ad.attempts.front().value == 2e-3);
  CHECK_FALSE(ad.attempts.front().met);
  CHECK(ad.attempts.back().met);
  CHECK(r.digest.accuracy.met);
  CHECK(r.digest.accuracy.worst_relative <= 1e-2);
  CHECK(r.digest.estimate.value == ad.attempts.back().value);
  for (std::size_t k = 1; k < ad.attempts.size(); ++k) {
    CHECK(ad.attempts[k].value <= 0.5 * ad.attempts[k - 1].value);
    CHECK(ad.attempts[k].value >= 0.25 * ad.attempts[k - 1].value * (1 - 1e-12));
  }
  // The reference: event-driven at tolerance 1e-10, whose peaks differ from Moreau–Jean's at
  // 1e-5 s by at most 2e-5 of them (measured: both 0.0782, 0.140, 0.00134) and whose own
  // estimate is below 2e-5 of them.
  const RunRecord ref = exc7("event_driven", {"solver.tolerance=1e-10"});
  REQUIRE(ref.digest.coordinates.size() == r.digest.coordinates.size());
  for (std::size_t c = 0; c < r.digest.coordinates.size(); ++c) {
    CAPTURE(r.digest.coordinates[c].name);
    const double p = r.digest.coordinates[c].peak;
    const double q = ref.digest.coordinates[c].peak;
    CHECK(std::abs(p - q) <= 1e-2 * q);
  }
  const std::string json = summary_json(r);
  CHECK(json.find("\"adapt\": true, \"attempts\": [") != std::string::npos);
  CHECK(json.find("\"total_cpu_seconds\": ") != std::string::npos);
}

TEST_CASE("adapt: a run that meets its target at once is the fixed run") {
  // The scene's own step meets 1 % (docs/error-estimates.md): one attempt, the same peaks.
  const RunRecord fixed = exc7("moreau", {});
  const RunRecord adapted = exc7("moreau", {"solver.adapt=true"});
  REQUIRE(adapted.digest.adaptation.attempts.size() == 1);
  CHECK(adapted.digest.accuracy.met);
  REQUIRE(fixed.digest.peaks.size() == adapted.digest.peaks.size());
  for (std::size_t c = 0; c < fixed.digest.peaks.size(); ++c) {
    CHECK(fixed.digest.peaks[c].abs_max == adapted.digest.peaks[c].abs_max);
    CHECK(fixed.digest.peaks[c].error == adapted.digest.peaks[c].error);
  }
  // Without adapt, summary.json has no attempts.
  CHECK(summary_json(fixed).find("\"attempts\"") == std::string::npos);
}

TEST_CASE("adapt without the error estimate is bad input, at the key") {
  CHECK_THROWS_WITH_AS(exc7("moreau", {"solver.adapt=true", "solver.error_estimate=false"}),
                       doctest::Contains("solver.adapt (override): needs solver.error_estimate = true"),
                       std::invalid_argument);
}

}  // namespace nsb::runs
