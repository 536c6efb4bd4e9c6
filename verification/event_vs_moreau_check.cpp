// Event-driven against Moreau–Jean: Moreau–Jean converges to the event-driven solution as
// h -> 0 on the analytic scenes and on the benchmark bridge, and both agree on the bridge's
// peak rotation at h = 1e-4. The spread of the event-driven peak rotation under a 1e-9 m
// perturbation of the initial state and under a change of tolerance is measured and printed
// beside the Moreau–Jean difference.
#include "integrators/event_driven.hpp"
#include "integrators/moreau_jean.hpp"
#include "models/analytic.hpp"
#include "models/simple_systems.hpp"
#include "scene/scene.hpp"
#include "verification/convergence.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace ni = nsb::integrators;
namespace nm = nsb::models;
namespace na = nsb::models::analytic;

namespace {

// The bridge window: both impacts of excitation 5 and the peak rotation lie before 4 s.
constexpr double kBridgeEnd = 6.0;
constexpr double kSampleDt = 0.005;
// Required agreement of the peak rotation at h = 1e-4.
constexpr double kPeakAgreement = 0.05;


ni::RunResult run_event(ni::System& s, double end, double tol, ni::Recorder& r) {
  ni::EventDrivenOptions o;
  o.end_time = end;
  o.tolerance = tol;
  return ni::event_driven(s, o, r);
}

ni::RunResult run_moreau(ni::System& s, double end, double h, ni::Recorder& r) {
  ni::MoreauJeanOptions o;
  o.end_time = end;
  o.step = h;
  return ni::moreau_jean(s, o, r);
}

std::filesystem::path bridge_scene() {
  return std::filesystem::path(NSB_SCENES_DIR) / "bridge-exc5.toml";
}

}  // namespace

TEST_CASE("bouncing ball: Moreau–Jean converges to the event-driven history") {
  nm::BouncingBall::Parameters p;
  p.restitution = 0.8;
  const double end = 2.0;  // 3 impacts, well before the accumulation at 4.06 s
  nm::BouncingBall ball_ed(p);
  ni::Recorder ed(ball_ed, kSampleDt);
  REQUIRE(run_event(ball_ed, end, 1e-10, ed).completed);
  // The event-driven history is the closed form to far below the Moreau–Jean errors.
  for (std::size_t i = 0; i < ed.rows(); ++i) {
    const double t = ed.at(i, ed.column("t"));
    CHECK(std::abs(ed.at(i, ed.column("y")) - na::ball_state(p, t).position) < 1e-8);
  }
  std::vector<double> errors;
  for (double h : {1e-2, 1e-3, 1e-4}) {
    nm::BouncingBall ball(p);
    ni::Recorder mj(ball, kSampleDt);
    REQUIRE(run_moreau(ball, end, h, mj).completed);
    errors.push_back(nsb::verification::history_error(ed, mj, "y"));
    MESSAGE("ball: h = ", h, "  max |y_MJ - y_ED| = ", errors.back(), " m");
  }
  // First order in h: each decade of h gains close to a decade (at least a factor 3).
  CHECK(errors[1] < errors[0] / 3.0);
  CHECK(errors[2] < errors[1] / 3.0);
}

TEST_CASE("bridge, excitation 5: convergence of Moreau–Jean and agreement on peak rotation") {
  auto scene = nsb::scene::load_scene(bridge_scene());
  ni::Recorder ed(*scene.system, kSampleDt);
  const auto sed = run_event(*scene.system, kBridgeEnd, 1e-8, ed);
  REQUIRE(sed.completed);
  const double peak_ed = nsb::verification::peak_abs(ed, "theta");
  REQUIRE(peak_ed > 0.0);

  std::vector<double> errors;
  double peak_mj_1e4 = 0.0;
  for (double h : {1e-2, 1e-3, 1e-4}) {
    auto s = nsb::scene::load_scene(bridge_scene());
    ni::Recorder mj(*s.system, kSampleDt);
    REQUIRE(run_moreau(*s.system, kBridgeEnd, h, mj).completed);
    errors.push_back(nsb::verification::history_error(ed, mj, "theta"));
    const double peak = nsb::verification::peak_abs(mj, "theta");
    if (h == 1e-4) peak_mj_1e4 = peak;
    MESSAGE("bridge: h = ", h, "  max |theta_MJ - theta_ED| = ", errors.back(),
            " rad, peak |theta| MJ = ", peak, ", ED = ", peak_ed);
  }
  CHECK(errors[2] < errors[0]);
  CHECK(errors[2] <= errors[1]);
  CHECK(std::abs(peak_mj_1e4 - peak_ed) <= kPeakAgreement * peak_ed);

  // The response's own spread: initial x perturbed by 1e-9 m, and tolerance 1e-6 / 1e-10.
  std::vector<double> peaks{peak_ed};
  const std::vector<std::string> perturbed{"model.deck.initial_position=[1e-9, 0.0, 0.0]"};
  struct Variant {
    std::vector<std::string> overrides;
    double tolerance;
  };
  for (const auto& v : {Variant{perturbed, 1e-8}, Variant{{}, 1e-6}, Variant{{}, 1e-10}}) {
    auto s = nsb::scene::load_scene(bridge_scene(), v.overrides);
    ni::Recorder r(*s.system, kSampleDt);
    REQUIRE(run_event(*s.system, kBridgeEnd, v.tolerance, r).completed);
    peaks.push_back(nsb::verification::peak_abs(r, "theta"));
  }
  const auto [lo, hi] = std::minmax_element(peaks.begin(), peaks.end());
  MESSAGE("bridge: event-driven peak |theta| spread over perturbations = ", *hi - *lo,
          " rad; Moreau–Jean (h = 1e-4) differs by ", std::abs(peak_mj_1e4 - peak_ed), " rad");
  CHECK(*hi - *lo < kPeakAgreement * peak_ed);
}
