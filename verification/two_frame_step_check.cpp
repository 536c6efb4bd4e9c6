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
// 5e-5, 6e-5 and 1e-4 to 5e-4 s Moreau–Jean misses a pounding of frame 1 and |theta1| is 17 %
// low, and at 1e-4 s the companion at 2 h misses it too, so the estimate cannot tell
// (docs/error-estimates.md, "Effectivity on the bridge"); the step is what keeps this scene
// right. Measured at 2e-5 s: the largest difference is y2's, 0.21 % (a difference between the
// methods: Moreau–Jean gives it within 3e-5 m at every step from 5e-6 to 4.5e-5 s).
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

// At ten times its step (2e-4 s) the run strikes hinge corner 4 first at 11.5504 s and
// corner 3 0.6 ms later, where event-driven at tolerance 1e-10 strikes corner 3 alone at
// 11.5503 s (printed by the check: the reference's first hinge impact after 11.5 s); |theta1|
// then peaks 16 % low. The run's companion (4e-4 s) strikes in the run's order, so the
// extrapolation cannot see it; the impact-order check must (docs/error-estimates.md, "Impacts
// in an unresolved order"): measured separation 0.155 mm against an uncertainty of 0.393 mm.
TEST_CASE("the two-frame bridge at ten times its step: the hinge impact's order is unresolved") {
  const std::string scene = kScenes + "/bridge-two-frame.toml";
  const RunRecord ref = execute({scene,
                                 {"solver.end_time=12.5", "solver.error_estimate=false",
                                  "solver.tolerance=1e-10"},
                                 "event_driven",
                                 {}});
  REQUIRE(integrators::succeeded(ref.result.status));
  int first_hinge_contact = 0;
  double first_hinge_time = 0.0;
  for (const auto& e : ref.history.events()) {
    const bool hinge = e.contact == 3 || e.contact == 4;
    if (e.kind == integrators::EventKind::kImpact && e.t > 11.5 && hinge) {
      first_hinge_contact = e.contact;
      first_hinge_time = e.t;
      break;
    }
  }
  CAPTURE(first_hinge_time);
  CHECK(first_hinge_contact == 3);

  const RunRecord r =
      execute({scene, {"solver.end_time=12.5", "solver.step=2e-4"}, "moreau", {}});
  REQUIRE(integrators::succeeded(r.result.status));
  const UnresolvedImpactOrder& o = r.digest.estimate.impact_order;
  REQUIRE(o.found);
  CHECK(o.contact == 4);
  CHECK(o.other == 3);
  CHECK(std::abs(o.time - first_hinge_time) < 1e-3);
  CHECK_FALSE(r.digest.accuracy.met);
  for (const CoordinatePeak& c : r.digest.coordinates) CHECK(c.error >= c.peak);
}

}  // namespace
}  // namespace nsb::runs
