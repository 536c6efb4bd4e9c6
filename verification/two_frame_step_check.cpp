// The two-frame bridge at its shipped step against event-driven (docs/error-estimates.md,
// "Effectivity on the bridge"): a cross-method check on a whole scene, too long for the unit
// tests under the sanitizers.
#include "runs/run.hpp"

#include "integrators/run.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

namespace nsb::runs {
namespace {

const std::string kScenes = NSB_SCENES_DIR;

// The two-frame bridge at its shipped step, to 12.5 s (frame 1's rotation peaks at 12.28 s):
// every deck peak within the scene's accuracy (1 %) of event-driven at tolerance 1e-10. At
// 1e-4 and 2e-4 s Moreau–Jean misses a pounding of frame 1 and |theta1| is 16 % low, and the
// companion at 2 h misses it too, so the estimate cannot tell (docs/error-estimates.md,
// "Effectivity on the bridge"); the step is what keeps this scene right. Measured at 2.5e-5 s:
// the largest difference is y2's, 0.20 % (a difference between the methods: Moreau–Jean gives
// it within 1e-5 m at every step from 1e-5 to 5e-5 s).
TEST_CASE("the two-frame bridge at its own step: every deck peak within 1 % of the reference") {
  const std::string scene = kScenes + "/bridge-two-frame.toml";
  const std::vector<std::string> window{"solver.end_time=12.5", "solver.error_estimate=false"};
  std::vector<std::string> reference = window;
  reference.push_back("solver.tolerance=1e-10");
  const RunRecord ref = execute({scene, reference, "event_driven", {}});
  const RunRecord r = execute({scene, window, "moreau", {}});
  REQUIRE(integrators::succeeded(ref.result.status));
  REQUIRE(integrators::succeeded(r.result.status));
  REQUIRE(r.digest.coordinates.size() == 6);
  for (std::size_t c = 0; c < r.digest.coordinates.size(); ++c) {
    const double expected = ref.digest.coordinates[c].peak;
    CAPTURE(r.digest.coordinates[c].name);
    CAPTURE(expected);
    CAPTURE(r.digest.coordinates[c].peak);
    // Relative: doctest's Approx adds 1 to its scale, which would admit 1e-2 rad on theta.
    CHECK(std::abs(r.digest.coordinates[c].peak - expected) <= 0.01 * expected);
  }
}

}  // namespace
}  // namespace nsb::runs
