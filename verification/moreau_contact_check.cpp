// Moreau–Jean on the impact oscillator, the sliding block and a friction oscillator, against
// the closed forms of models/analytic.hpp.
#include "integrators/moreau_jean.hpp"
#include "models/analytic.hpp"
#include "models/simple_systems.hpp"
#include "testsupport/systems.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace nsb {
namespace {

using integrators::ContactData;
using integrators::EnergyState;
using integrators::EventKind;
using integrators::Matrix;
using integrators::MoreauJeanOptions;
using integrators::PowerTerms;
using integrators::Recorder;
using integrators::RunResult;
using integrators::Vector;

RunResult run(integrators::System& s, Recorder& rec, double h, double end_time) {
  MoreauJeanOptions o;
  o.step = h;
  o.end_time = end_time;
  return integrators::moreau_jean(s, o, rec);
}

// m x'' + k x = -mu m g sgn(x') on the ground: 2 DOF (x, y), spring k along x, contact
// g_N = y with W_N = (0, 1), W_T = (1, 0), gravity along -y. Released from rest at x0.
testsupport::Block friction_oscillator(double m, double k, double mu, double g, double x0) {
  return testsupport::Block(
      {.mass = m, .gravity = g, .friction = mu, .stiffness = k, .initial_position = x0});
}

}  // namespace

TEST_CASE("impact oscillator: impact speeds, rebounds and amplitudes") {
  // Undamped, unforced, w = 2 pi, stop at 0.05 m, e = 0.5, from x = 0 at 1 m/s (A = 0.159 m).
  models::ImpactOscillator::Parameters p;
  p.stiffness = 4.0 * std::numbers::pi * std::numbers::pi;
  p.gap = 0.05;
  p.restitution = 0.5;
  p.initial_velocity = 1.0;
  const double w = 2.0 * std::numbers::pi;
  const auto exact = models::analytic::oscillator_impacts(p, 4);
  REQUIRE(exact.size() == 4);
  const double h = 1e-4;
  models::ImpactOscillator s(p);
  Recorder rec(s, 0.0);
  const RunResult stats = run(s, rec, h, 3.0);
  CHECK(stats.completed);
  const auto t = rec.series("t"), x = rec.series("x"), v = rec.series("vx");
  std::vector<std::size_t> rows;  // history row of each impact (the step that applies it)
  for (const auto& e : rec.events()) {
    if (e.kind == EventKind::kImpact) rows.push_back(static_cast<std::size_t>(std::llround(e.t / h)));
  }
  REQUIRE(rows.size() >= exact.size());
  // O(h) errors: the impact is applied up to one step early or late, during which the
  // velocity changes by at most w^2 A h and the time by h; amplitudes follow the speeds.
  const double a0 = 1.0 / w;
  const double speed_tolerance = 3.0 * w * w * a0 * h;
  for (std::size_t k = 0; k < exact.size(); ++k) {
    const std::size_t r = rows[k];
    INFO("impact ", k + 1, " at t = ", t[r], " (exact ", exact[k].time, ")");
    CHECK(std::abs(t[r] - exact[k].time) <= 2.0 * h * (k + 1));
    CHECK(std::abs(v[r - 1] - exact[k].speed_before) <= speed_tolerance * (k + 1));
    CHECK(std::abs(-v[r] - exact[k].speed_after) <= speed_tolerance * (k + 1));
    // The amplitude after the impact: sqrt(x^2 + (v/w)^2) is invariant on the free orbit.
    const double amplitude = std::hypot(x[r + 10], v[r + 10] / w);
    CHECK(std::abs(amplitude - exact[k].amplitude_after) <= speed_tolerance / w * (k + 1) + w * a0 * h);
  }
  CHECK(stats.energy.error <= 1e-6);
}

TEST_CASE("sliding block: stopping time and distance") {
  // v0 = 2 m/s, mu = 0.4: t_s = v0 / (mu g), d = v0^2 / (2 mu g). Each step removes exactly
  // mu g h of velocity, so the stop is within one step and the distance within v0 h.
  models::SlidingBlock::Parameters p;
  p.initial_velocity = 2.0;
  p.friction = 0.4;
  const double ts = models::analytic::block_stopping_time(2.0, 0.4, p.gravity);
  const double ds = models::analytic::block_stopping_distance(2.0, 0.4, p.gravity);
  for (double h : {1e-3, 1e-4}) {
    models::SlidingBlock s(p);
    Recorder rec(s, 0.0);
    const RunResult stats = run(s, rec, h, 1.0);
    CHECK(stats.completed);
    const auto t = rec.series("t"), x = rec.series("x"), vx = rec.series("vx");
    std::size_t stop = 0;
    while (stop < t.size() && vx[stop] > 1e-12) ++stop;
    REQUIRE(stop < t.size());
    CHECK(std::abs(t[stop] - ts) <= h);
    CHECK(std::abs(x.back() - ds) <= 2.0 * h);
    CHECK(std::abs(x.back() - x[stop]) <= 1e-12);  // stuck after the stop
    CHECK(rec.count(EventKind::kStick) >= 1);
    CHECK(stats.lcp_status.at("solved") == stats.lcp_solves);
  }
}

TEST_CASE("friction oscillator: turning points decay by 2 mu g / w^2, then stick") {
  // m = 1, k = 100 (w = 10), mu = 0.3, released at x0 = 0.1: delta = mu g / w^2 = 0.02943;
  // turning points x_{n+1} = sgn(x_n)(2 delta - |x_n|) until |x_n| <= delta.
  const double m = 1.0, k = 100.0, mu = 0.3, g = 9.81, x0 = 0.1;
  models::analytic::FrictionOscillator fo;
  fo.omega = std::sqrt(k / m);
  fo.friction = mu;
  fo.gravity = g;
  fo.initial_position = x0;
  const auto turning = models::analytic::friction_oscillator_turning_points(fo);
  REQUIRE(turning.size() >= 3);
  const double h = 1e-4;
  auto s = friction_oscillator(m, k, mu, g, x0);
  Recorder rec(s, 0.0);
  const RunResult stats = run(s, rec, h, 2.0);
  CHECK(stats.completed);
  const auto x = rec.series("x"), vx = rec.series("vx");
  // Numerical turning points: where vx changes sign or comes to rest after moving (|vx| below
  // 1e-9 m/s counts as rest: a stuck block keeps round-off velocities).
  auto sign = [](double v) { return std::abs(v) <= 1e-9 ? 0 : (v > 0.0 ? 1 : -1); };
  std::vector<double> found{x.front()};
  for (std::size_t r = 1; r < x.size(); ++r) {
    if (sign(vx[r - 1]) != 0 && sign(vx[r]) != sign(vx[r - 1])) found.push_back(x[r]);
  }
  REQUIRE(found.size() >= turning.size());
  // Near a turning point the velocity is O(w |x| h) per step: x is within w |x| h^2-ish of
  // the turning point, and the slip-to-stick switch shifts it by O(h): bound by w x0 h.
  const double tolerance = fo.omega * x0 * h;
  for (std::size_t n = 0; n < turning.size(); ++n) {
    INFO("turning point ", n, ": ", found[n], " vs ", turning[n]);
    CHECK(std::abs(found[n] - turning[n]) <= tolerance);
  }
  // It stays stuck at the last turning point.
  CHECK(std::abs(x.back() - turning.back()) <= tolerance);
  CHECK(std::abs(vx.back()) <= 1e-12);
}

}  // namespace nsb
