// Moreau–Jean on the bouncing ball (models::BouncingBall) against the closed form
// (models/analytic.hpp) and against Siconos's own reference output.
#include "integrators/moreau_jean.hpp"
#include "models/analytic.hpp"
#include "models/simple_systems.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

namespace nsb {
namespace {

using integrators::EventKind;
using integrators::MoreauJeanOptions;
using integrators::Recorder;
using integrators::RunResult;

struct Run {
  RunResult stats;
  std::vector<double> t, y, v, lambda;
  std::vector<double> impacts;  // impact event times
};

Run run_ball(const models::BouncingBall::Parameters& p, double h, double end_time,
             double theta = 0.5) {
  models::BouncingBall ball(p);
  Recorder rec(ball, 0.0);
  MoreauJeanOptions o;
  o.step = h;
  o.end_time = end_time;
  o.theta = theta;
  Run r;
  r.stats = integrators::moreau_jean(ball, o, rec);
  r.t = rec.series("t");
  r.y = rec.series("y");
  r.v = rec.series("vy");
  r.lambda = rec.series("lambdaN1");
  for (const auto& e : rec.events()) {
    if (e.kind == EventKind::kImpact) r.impacts.push_back(e.t);
  }
  return r;
}

}  // namespace

TEST_CASE("Siconos's bouncing-ball output is reproduced to 1e-10 by models::BouncingBall") {
  // data/siconos-bouncing-ball/result.ref: Siconos 4.4, m = 1, g = 9.81, e = 0.9,
  // theta = 0.5, h = 0.005, 2000 steps from y = 1 at rest; columns t, q, v, impulse p and
  // lambda (both the impulse in that output; ours is lambda = p / h).
  constexpr double kTolerance = 1e-10;
  std::ifstream f(std::string(NSB_DATA_DIR) + "/siconos-bouncing-ball/result.ref");
  REQUIRE(f.good());
  int rows = 0, cols = 0;
  f >> rows >> cols;
  REQUIRE(rows == 2001);
  REQUIRE(cols == 5);
  models::BouncingBall::Parameters p;  // defaults: m 1, height 1, at rest, e 0.9, g 9.81
  const double h = 0.005;
  const Run r = run_ball(p, h, 10.0);
  REQUIRE(r.t.size() == 2001);
  double worst = 0.0;
  for (std::size_t i = 0; i < r.t.size(); ++i) {
    double ref[5];
    for (double& x : ref) f >> x;
    const double impulse = r.lambda[i] * h;
    worst = std::max({worst, std::abs(r.t[i] - ref[0]), std::abs(r.y[i] - ref[1]),
                      std::abs(r.v[i] - ref[2]), std::abs(impulse - ref[3]),
                      std::abs(impulse - ref[4])});
  }
  CHECK(f.good());
  CHECK(worst <= kTolerance);
}

TEST_CASE("bouncing-ball impact times are within O(h) of the closed form") {
  // e = 0.8 from 1 m: impacts at t1 = sqrt(2/g) = 0.4515 s, then t_k+1 = t_k + 2 e V_k / g.
  // Moreau–Jean records an impact at the end of the step whose index set first holds the
  // contact (g + (h/2) gdot <= 0), up to one step off; each impact also shifts the next
  // flight by O(h), so over six impacts the error is a few h (about 4 h measured).
  models::BouncingBall::Parameters p;
  p.restitution = 0.8;
  const auto exact = models::analytic::ball_impacts(p, 6);
  constexpr double kStepsOfError = 6.0;  // one step per impact of carried O(h) error
  double previous_worst = 0.0;
  for (double h : {2e-3, 1e-3, 5e-4}) {
    const Run r = run_ball(p, h, 3.0);
    REQUIRE(r.impacts.size() >= exact.size());
    double worst = 0.0;
    for (std::size_t k = 0; k < exact.size(); ++k) {
      worst = std::max(worst, std::abs(r.impacts[k] - exact[k].time));
    }
    INFO("h = ", h, ": largest impact-time error ", worst);
    CHECK(worst <= kStepsOfError * h);
    // O(h): halving h at least roughly halves the error.
    if (previous_worst > 0.0) CHECK(worst < 0.75 * previous_worst);
    previous_worst = worst;
  }
}

TEST_CASE("the ball reaches the accumulation point, then rests with no drift") {
  // e = 0.5 from 1 m: accumulation at t_inf = sqrt(2 h0 / g) (1 + e) / (1 - e) = 1.3550 s.
  // Moreau–Jean reaches rest within a few tenths of a second of it (the last small
  // bounces are shorter than h); afterwards y must not move and lambda_N = m g.
  models::BouncingBall::Parameters p;
  p.restitution = 0.5;
  const double t_inf = models::analytic::ball_accumulation_time(p);
  CHECK(t_inf == doctest::Approx(std::sqrt(2.0 / 9.81) * 3.0));
  const double h = 1e-3;
  const Run r = run_ball(p, h, 4.0);
  CHECK(r.stats.completed);
  // Rest is reached: the last impact is near t_inf.
  REQUIRE(!r.impacts.empty());
  CHECK(r.impacts.back() <= t_inf + 0.1);
  CHECK(r.impacts.back() >= t_inf - 0.1);
  const std::size_t from = static_cast<std::size_t>(std::ceil((t_inf + 0.2) / h));
  const double y_rest = r.y[from];
  // Resting at most (h/2) |v| below the ground, |v| the last approach speed (< 1 m/s here).
  CHECK(y_rest <= 0.0);
  CHECK(y_rest >= -0.5 * h * 1.0);
  for (std::size_t i = from; i < r.y.size(); ++i) {
    CHECK(std::abs(r.y[i] - y_rest) <= 1e-14);  // no drift
    CHECK(std::abs(r.v[i]) <= 1e-12);
    CHECK(r.lambda[i] == doctest::Approx(p.mass * p.gravity));
  }
  // The energy lost equals the work of the impacts; the balance closes.
  CHECK(r.stats.energy.error <= 1e-12);
  CHECK(r.stats.energy.impacts == doctest::Approx(-p.mass * p.gravity * (1.0 - y_rest))
                                      .epsilon(1e-9));
}

}  // namespace nsb
