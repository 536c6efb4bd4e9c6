// solver.adapt when a refinement fails (runs::run, docs/error-estimates.md, "Choosing the
// step"): the search ends with the last attempt that reached a result. A whole-scene run of
// event-driven at three tolerances, too long for the unit tests under the sanitizers.
#include "runs/run.hpp"

#include "integrators/run.hpp"

#include <doctest/doctest.h>

#include <string>

namespace nsb::runs {
namespace {

const std::string kScenes = NSB_SCENES_DIR;

TEST_CASE("adapt: a refinement that stalls ends the search with the result before it") {
  // Recorded on the base revision: event-driven on the unequal-skew bridge completes at
  // tolerances 1e-8 and 1e-9 and stalls at 1e-10 (more than 4000 events within 0.01 s at
  // 15.1 s). A target of 1e-7 is beyond the estimates of 1e-8 and 1e-9 (4.2e-5 and 1.3e-4 of
  // |theta1|), so the search refines to 1e-10, which stalls, and the run is the one at 1e-9.
  const RunRecord r = execute({kScenes + "/bridge-unequal-skew.toml",
                               {"solver.end_time=16", "solver.adapt=true", "solver.accuracy=1e-7"},
                               "event_driven",
                               {}});
  const Adaptation& ad = r.digest.adaptation;
  REQUIRE(ad.attempts.size() == 3);
  CHECK(ad.attempts[0].value == doctest::Approx(1e-8));
  CHECK(ad.attempts[1].value == doctest::Approx(1e-9));
  CHECK(ad.attempts[2].value == doctest::Approx(1e-10));
  CHECK(ad.attempts[2].status == "stalled");
  CHECK(integrators::is_result(r.result.status));
  CHECK(r.digest.estimate.value == doctest::Approx(1e-9));
  CHECK_FALSE(r.digest.accuracy.met);
  bool warned = false;
  for (const std::string& w : r.digest.warnings) warned = warned || w.rfind("accuracy: ", 0) == 0;
  CHECK(warned);
}

}  // namespace
}  // namespace nsb::runs
