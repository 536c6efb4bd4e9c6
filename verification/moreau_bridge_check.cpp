// Moreau–Jean on the benchmark bridge (scenes/bridge-exc7.toml): the energy balance closes to
// the scheme's accuracy, every contact problem is solved, and the deck never sinks into an
// abutment by more than the scheme's O(h) velocity-level penetration.
#include "integrators/moreau_jean.hpp"
#include "scene/scene.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>

namespace nsb {

namespace {
struct BridgeRun {
  integrators::RunResult stats;
  double deepest_gap = 0.0;  // most negative g_N over the run [m]
  double peak_speed = 0.0;   // largest |vx| [m/s]
};

BridgeRun run_bridge(double h, double end_time) {
  scene::Scene scene = scene::load_scene(std::string(NSB_SCENES_DIR) + "/bridge-exc7.toml",
                                           {"solver.end_time=" + std::to_string(end_time)});
  integrators::Recorder rec(*scene.system, 0.0);
  integrators::MoreauJeanOptions o;
  o.step = h;
  o.end_time = end_time;
  BridgeRun r;
  r.stats = integrators::moreau_jean(*scene.system, o, rec);
  for (int c = 1; c <= 4; ++c) {
    for (double g : rec.series("gN" + std::to_string(c))) r.deepest_gap = std::min(r.deepest_gap, g);
  }
  for (double v : rec.series("vx")) r.peak_speed = std::max(r.peak_speed, std::abs(v));
  return r;
}
}  // namespace

TEST_CASE("bridge, excitation 7: the energy balance closes and converges with h") {
  // Excitation 7 reaches the abutments (pounding within the first 12 s). The balance error
  // is relative to the largest energy term (recorder.hpp); it is O(h) for the impacts' work
  // and O(h^2) for the smooth terms, so it must shrink when h does.
  constexpr double kEnd = 12.0;
  const BridgeRun fine = run_bridge(1e-4, kEnd);
  const BridgeRun coarse = run_bridge(4e-4, kEnd);
  REQUIRE(fine.stats.completed);
  REQUIRE(coarse.stats.completed);
  CHECK(fine.stats.steps_with_lcp > 0);  // it pounds
  CHECK(fine.stats.energy.impacts < 0.0);  // and the impacts dissipate (e = 0)
  CHECK(fine.stats.energy.friction <= 0.0);
  for (const auto& [status, count] : fine.stats.lcp_status) {
    INFO(status, ": ", count);
    CHECK(status == "solved");
  }
  MESSAGE("balance error: h = 1e-4: ", fine.stats.energy.error, ", h = 4e-4: ",
          coarse.stats.energy.error, "; deepest gap ", fine.deepest_gap, " m");
  constexpr double kBalance = 5e-3;  // relative, at h = 1e-4 (measured about 1e-3)
  CHECK(fine.stats.energy.error <= kBalance);
  CHECK(fine.stats.energy.error < coarse.stats.energy.error);
  // Penetration: at most about (h/2) times the approach speed per contact step.
  CHECK(fine.deepest_gap >= -2.0 * 1e-4 * fine.peak_speed);
}

}  // namespace nsb
