// Unit tests of the event-driven integrator on small systems defined here, each with a
// closed-form answer derived in the comments.
#include "integrators/event_driven.hpp"
#include "testsupport/systems.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace ni = nsb::integrators;
using ni::Matrix;
using ni::Vector;

namespace {

// Impact and transition times are located by Brent's method to 1e-13 s on a dense output
// that is exact for piecewise-quadratic motion (Dormand–Prince is exact on polynomials of
// degree <= 4 and its dense output on degree <= 4 too); 1e-9 s leaves room for round-off
// accumulated over many events.
constexpr double kTimeTol = 1e-9;
// Positions after many smooth steps at tolerance 1e-10.
constexpr double kStateTol = 1e-7;

namespace ts = nsb::testsupport;

std::vector<double> times_of(const ni::Recorder& r, ni::EventKind kind) {
  std::vector<double> t;
  for (const auto& e : r.events()) {
    if (e.kind == kind) t.push_back(e.t);
  }
  return t;
}

}  // namespace

TEST_CASE("options are validated") {
  ni::EventDrivenOptions o;
  CHECK_NOTHROW(o.validate());
  o.tolerance = 0.0;
  CHECK_THROWS_AS(o.validate(), std::invalid_argument);
  o = {};
  o.max_events_per_window = 0;
  CHECK_THROWS_AS(o.validate(), std::invalid_argument);
  o = {};
  o.end_time = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(o.validate(), std::invalid_argument);
  ts::Ball::Parameters bp;
  ts::Ball b(bp);
  ni::Recorder r(b, 0.0);
  o = {};
  o.end_time = -1.0;  // before the initial time 0
  CHECK_THROWS_AS(ni::event_driven(b, o, r), std::invalid_argument);
}

TEST_CASE("bouncing ball: impact times, accumulation, rest") {
  // Dropped from y0 with v0 = 0: t1 = sqrt(2 y0 / g), v1 = g t1. Between impacts k and k+1
  // the flight lasts 2 e^k v1 / g, so t_{k+1} = t_k + 2 e^k v1 / g and the impacts
  // accumulate at t_inf = t1 + 2 v1 e / (g (1 - e)).
  ts::Ball::Parameters bp;
  bp.restitution = 0.5;
  ts::Ball b(bp);
  ni::EventDrivenOptions o;
  o.end_time = 3.0;
  o.tolerance = 1e-10;
  ni::Recorder r(b, 0.01);
  const ni::RunResult s = ni::event_driven(b, o, r);
  REQUIRE(s.completed);
  const double t1 = std::sqrt(2.0 * bp.initial_height / bp.gravity), v1 = bp.gravity * t1;
  const auto impacts = times_of(r, ni::EventKind::kImpact);
  REQUIRE(impacts.size() >= 10);
  double tk = t1;
  for (int k = 0; k < 10; ++k) {
    CHECK(std::abs(impacts[static_cast<std::size_t>(k)] - tk) < kTimeTol);
    tk += 2.0 * std::pow(bp.restitution, k + 1) * v1 / bp.gravity;
  }
  const double t_inf = t1 + 2.0 * v1 * bp.restitution / (bp.gravity * (1.0 - bp.restitution));
  const auto closes = times_of(r, ni::EventKind::kClose);
  REQUIRE(!closes.empty());
  // The closing velocity 10 * tolerance = 1e-9 m/s cuts the remaining flights, which last
  // at most 2 v / (g (1 - e)) ~ 4e-10 s in total.
  CHECK(std::abs(closes.back() - t_inf) < 1e-6);
  // At rest on the ground after t_inf.
  const auto y = r.series("y");
  const auto lam = r.series("lambdaN1");
  CHECK(std::abs(y.back()) < kStateTol);
  CHECK(lam.back() == doctest::Approx(bp.mass * bp.gravity));
  // e < 1 dissipates: impacts' work is negative and the balance closes.
  CHECK(s.energy.impacts < 0.0);
  CHECK(s.energy.error < 1e-6);
  CHECK(s.lcp_solves > 0);
}

TEST_CASE("elastic ball keeps its energy; plastic ball stays closed") {
  SUBCASE("eps = 1") {
    // Every flight lasts 2 v1 / g and the apex stays at y0.
    ts::Ball::Parameters bp;
    bp.restitution = 1.0;
    ts::Ball b(bp);
    ni::EventDrivenOptions o;
    o.end_time = 5.0;
    o.tolerance = 1e-10;
    ni::Recorder r(b, 0.0);
    const auto s = ni::event_driven(b, o, r);
    REQUIRE(s.completed);
    const double t1 = std::sqrt(2.0 * bp.initial_height / bp.gravity);
    const auto impacts = times_of(r, ni::EventKind::kImpact);
    REQUIRE(impacts.size() == static_cast<std::size_t>(std::floor((5.0 - t1) / (2 * t1)) + 1));
    for (std::size_t k = 0; k < impacts.size(); ++k) {
      CHECK(std::abs(impacts[k] - (t1 + 2.0 * t1 * static_cast<double>(k))) < kTimeTol);
    }
    CHECK(std::abs(s.energy.impacts) < 1e-6);
    CHECK(s.energy.error < 1e-6);
  }
  SUBCASE("eps = 0") {
    ts::Ball::Parameters bp;
    bp.restitution = 0.0;
    ts::Ball b(bp);
    ni::EventDrivenOptions o;
    o.end_time = 2.0;
    ni::Recorder r(b, 0.0);
    const auto s = ni::event_driven(b, o, r);
    REQUIRE(s.completed);
    CHECK(r.count(ni::EventKind::kImpact) == 1);
    CHECK(r.count(ni::EventKind::kClose) == 1);
    CHECK(r.count(ni::EventKind::kOpen) == 0);
    // The kinetic energy at impact, m g y0, is lost.
    CHECK(s.energy.impacts == doctest::Approx(-bp.mass * bp.gravity * bp.initial_height).epsilon(1e-6));
  }
}

TEST_CASE("lift-off under a growing force") {
  // At rest on the ground, F(t) = ramp t lifts the ball when lambda_N = m g - ramp t = 0.
  ts::Ball::Parameters bp;
  bp.initial_height = 0.0;
  bp.ramp = 20.0;
  ts::Ball b(bp);
  ni::EventDrivenOptions o;
  o.end_time = 1.0;
  ni::Recorder r(b, 0.0);
  const auto s = ni::event_driven(b, o, r);
  REQUIRE(s.completed);
  const auto opens = times_of(r, ni::EventKind::kOpen);
  REQUIRE(opens.size() == 1);
  CHECK(std::abs(opens[0] - bp.mass * bp.gravity / bp.ramp) < kTimeTol);
  // Afterwards y = (ramp/6)(t - t0)^3 - (g/2)(t - t0)^2 ... check at the end:
  // m y'' = ramp t - m g  => y(t) = ramp/(6m) (t^3 - t0^3) - ramp t0/(2m) (t^2 - t0^2)
  //                               ... integrated from rest at t0 = m g / ramp.
  const double t0 = bp.mass * bp.gravity / bp.ramp, T = 1.0;
  const double dt = T - t0;
  const double y_exact = bp.ramp / (6.0 * bp.mass) * dt * dt * dt;  // (ramp t - m g) = ramp (t - t0)
  CHECK(r.series("y").back() == doctest::Approx(y_exact).epsilon(1e-8));
}

TEST_CASE("rheonomic support: the ball leaves a shaking table when it accelerates below -g") {
  // Table yp = A sin(w t) with A w^2 > g. The ball rides on it while the contact force
  // lambda_N = m (g + yp'') = m (g - A w^2 sin(w t)) >= 0: it lifts off at
  // sin(w t) = g / (A w^2).
  ts::Ball::Parameters bp;
  bp.initial_height = 0.0;
  bp.floor_amplitude = 0.05;
  bp.floor_frequency = 20.0;  // A w^2 = 20 m/s^2
  bp.restitution = 0.0;
  ts::Ball b(bp);
  ni::EventDrivenOptions o;
  o.end_time = 0.1;
  ni::Recorder r(b, 0.0);
  const auto s = ni::event_driven(b, o, r);
  REQUIRE(s.completed);
  const auto opens = times_of(r, ni::EventKind::kOpen);
  REQUIRE(!opens.empty());
  const double t_lift = std::asin(bp.gravity / (bp.floor_amplitude * bp.floor_frequency * bp.floor_frequency)) / bp.floor_frequency;
  CHECK(std::abs(opens[0] - t_lift) < kTimeTol);
  // The table does the work on the ball (-lambda_N what_N, booked as ground input); the
  // contact itself does none while closed, and the plastic re-impact (e = 0) dissipates.
  CHECK(s.energy.ground > 0.0);
  CHECK(s.energy.impacts <= 1e-12);
  CHECK(s.energy.error < 1e-6);
}

TEST_CASE("block under a constant force: stick below mu m g, exact slip above") {
  ts::Block::Parameters k;
  ni::EventDrivenOptions o;
  o.end_time = 1.0;
  o.tolerance = 1e-10;
  SUBCASE("stick") {
    k.force = 0.9 * k.friction * k.mass * k.gravity;
    ts::Block block(k);
    ni::Recorder r(block, 0.0);
    const auto s = ni::event_driven(block, o, r);
    REQUIRE(s.completed);
    CHECK(std::abs(r.series("x").back()) < 1e-12);
    // Sticking: lambda_T balances F exactly.
    CHECK(r.series("lambdaT1").back() == doctest::Approx(-k.force));
    CHECK(r.count(ni::EventKind::kStick) == 1);
  }
  SUBCASE("slip") {
    // a = F/m - mu g, x(1) = a / 2.
    k.force = 1.5 * k.friction * k.mass * k.gravity;
    ts::Block block(k);
    ni::Recorder r(block, 0.0);
    const auto s = ni::event_driven(block, o, r);
    REQUIRE(s.completed);
    const double a = k.force / k.mass - k.friction * k.gravity;
    CHECK(r.series("x").back() == doctest::Approx(0.5 * a).epsilon(1e-9));
    CHECK(r.series("lambdaT1").back() == doctest::Approx(-k.friction * k.mass * k.gravity));
    // Friction work = -mu m g x; balance closes.
    CHECK(s.energy.friction == doctest::Approx(-k.friction * k.mass * k.gravity * 0.5 * a).epsilon(1e-8));
    CHECK(s.energy.error < 1e-8);
  }
  SUBCASE("sliding block stops") {
    // No force, vx0 > 0: decelerates at mu g and sticks at t = vx0 / (mu g).
    k.initial_velocity = 2.0;
    ts::Block block(k);
    ni::Recorder r(block, 0.0);
    const auto s = ni::event_driven(block, o, r);
    REQUIRE(s.completed);
    const auto sticks = times_of(r, ni::EventKind::kStick);
    REQUIRE(sticks.size() == 1);
    CHECK(std::abs(sticks[0] - k.initial_velocity / (k.friction * k.gravity)) < kTimeTol);
    CHECK(r.series("x").back() == doctest::Approx(k.initial_velocity * k.initial_velocity / (2 * k.friction * k.gravity)).epsilon(1e-9));
  }
}

TEST_CASE("accumulating impacts terminate and results stay finite") {
  // A very low closing velocity forces many impacts; the event bound must stop the cascade
  // with a warning rather than hang.
  ts::Ball::Parameters bp;
  bp.restitution = 0.95;
  ts::Ball b(bp);
  ni::EventDrivenOptions o;
  o.end_time = 20.0;
  o.closing_velocity = 1e-300;
  o.max_events_per_window = 50;
  o.event_window = 0.5;
  ni::Recorder r(b, 0.05);
  const auto s = ni::event_driven(b, o, r);
  CHECK(r.count(ni::EventKind::kWarning) >= 1);
  for (double v : r.series("y")) CHECK(std::isfinite(v));
  CHECK(s.end_time > 0.0);
}

TEST_CASE("a sliding block stops without chattering at tolerances 1e-11 and 1e-12") {
  // v0 = 2 m/s, mu = 0.5: it sticks at t* = v0 / (mu g) = 0.40775 s after
  // x* = v0^2 / (2 mu g) = 0.40775 m, and stays. At these tolerances the slip indicator's
  // velocity shift (1e-10 (1 + |u|)) exceeded the default stick velocity (10 tolerance), so
  // the contact was taken for sliding backwards at the located event and the reversal fired
  // again at once, until the event bound stopped the run after 4000 slips.
  for (const double tol : {1e-11, 1e-12}) {
    CAPTURE(tol);
    ts::Block::Parameters kp;
    kp.initial_velocity = 2.0;
    ts::Block k(kp);
    ni::EventDrivenOptions o;
    o.end_time = 1.0;
    o.tolerance = tol;
    ni::Recorder r(k, 0.0);
    const auto s = ni::event_driven(k, o, r);
    CHECK(s.status == ni::RunStatus::kCompleted);
    REQUIRE(s.completed);
    const auto sticks = times_of(r, ni::EventKind::kStick);
    REQUIRE(sticks.size() == 1);
    const double v0 = kp.initial_velocity, mu_g = kp.friction * kp.gravity;
    CHECK(std::abs(sticks[0] - v0 / mu_g) < kTimeTol);
    CHECK(r.count(ni::EventKind::kSlip) <= 1);
    CHECK(r.series("x").back() == doctest::Approx(v0 * v0 / (2 * mu_g)).epsilon(1e-9));
  }
}

TEST_CASE("a ball at rest on the ground makes no event after it closes") {
  // e = 0.5 from 1 m: the impacts accumulate at t_inf = sqrt(2 h / g) (1 + e) / (1 - e)
  // = 1.355 s; afterwards the ball rests: no open, impact or close for 10 s, and the gap
  // stays at 0 (the drift projection holds it to round-off of 1 m, far below 1e-12 m).
  ts::Ball::Parameters bp;
  bp.restitution = 0.5;
  ts::Ball b(bp);
  ni::EventDrivenOptions o;
  o.end_time = 12.0;
  o.tolerance = 1e-10;
  ni::Recorder r(b, 0.01);
  const auto s = ni::event_driven(b, o, r);
  REQUIRE(s.status == ni::RunStatus::kCompleted);
  const auto closes = times_of(r, ni::EventKind::kClose);
  REQUIRE_FALSE(closes.empty());
  CHECK(closes.front() == doctest::Approx(std::sqrt(2.0 / bp.gravity) * 3.0).epsilon(1e-6));
  for (const auto& e : r.events()) {
    if (e.t > closes.front()) CHECK(e.kind == ni::EventKind::kWarning);
  }
  CHECK(r.count(ni::EventKind::kClose) == 1);
  const auto t = r.series("t"), gap = r.series("gN1");
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] > closes.front()) CHECK(gap[i] >= -1e-12);
  }
}

TEST_CASE("a non-finite force ends the run as diverged, never as an exception") {
  // A NaN load from the start (ramp = NaN): the first right-hand side is NaN.
  ts::Ball::Parameters bp;
  bp.ramp = std::numeric_limits<double>::quiet_NaN();
  ts::Ball b(bp);
  ni::EventDrivenOptions o;
  o.end_time = 1.0;
  ni::Recorder r(b, 0.0);
  ni::RunResult s;
  CHECK_NOTHROW(s = ni::event_driven(b, o, r));
  CHECK(s.status == ni::RunStatus::kDiverged);
  CHECK_FALSE(s.completed);
  for (double v : r.series("y")) CHECK(std::isfinite(v));
}

TEST_CASE("the progress callback reaches end_time") {
  ts::Ball b(ts::Ball::Parameters{});
  ni::EventDrivenOptions o;
  o.end_time = 2.0;
  ni::Recorder r(b, 0.0);
  std::vector<double> seen;
  ni::event_driven(b, o, r, [&](double t) { seen.push_back(t); });
  REQUIRE_FALSE(seen.empty());
  CHECK(seen.back() == doctest::Approx(2.0));
}
