// Tests of the closed-form references: hand-derived numbers (derivation beside each), the
// defining conditions of each solution, and the rotation criterion against the two-corner
// impact solved by case analysis.
#include "models/analytic.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

namespace {

namespace an = nsb::models::analytic;
using nsb::models::BouncingBall;
using nsb::models::ImpactOscillator;
using nsb::models::SlidingBlock;
constexpr double kPi = std::numbers::pi;

// Closed forms against hand values evaluated in a different order: a few ulps.
constexpr double kExact = 1e-12;
// Results of the case enumeration: linear solves of size <= 8 with O(1) data.
constexpr double kSolve = 1e-9;
// Independent numerical integration in these tests (RK4 / fine quadrature) is accurate to
// about 1e-9; compare with margin.
constexpr double kQuadrature = 1e-7;
// The slip distance from the same quadrature (trapezoid with end correction, step 1e-5 s,
// plus the linearly interpolated last step): about 1e-8 relative; compare with margin.
constexpr double kQuadratureDisplacement = 1e-6;
// Mechanical energy recomputed from ball_state: a handful of operations on O(10) numbers.
constexpr double kEnergy = 1e-10;
// The oscillator state is sampled kBeforeImpact ahead of an impact: it moves O(V) * 1e-9,
// so position and velocity agree with the impact values to kNearImpact.
constexpr double kBeforeImpact = 1e-9;
constexpr double kNearImpact = 1e-7;
// The impact times with d < 0 shrink geometrically (ratio ~ e); after 40 impacts the last
// interval is far below this.
constexpr double kAccumulated = 1e-9;

}  // namespace

// ---------------------------------------------------------------------------------------
TEST_CASE("bouncing ball from rest: impact times, accumulation, energy") {
  // h = 1, g = 9.81, e = 0.5: t1 = sqrt(2h/g); V1 = sqrt(2gh); the first rebound arc lasts
  // 2 e V1 / g = sqrt(2h/g) = t1, the next t1/2, ... so t2 = 2 t1, t3 = 2.5 t1, and
  // t_inf = t1 (1 + e)/(1 - e) = 3 t1.
  const BouncingBall::Parameters p{.mass = 2.0, .height = 1.0, .velocity = 0.0,
                                   .restitution = 0.5, .gravity = 9.81};
  const double t1 = std::sqrt(2.0 / 9.81);
  const double v1 = std::sqrt(2.0 * 9.81);
  CHECK(an::ball_first_impact_time(p) == doctest::Approx(t1).epsilon(kExact));
  CHECK(an::ball_first_impact_speed(p) == doctest::Approx(v1).epsilon(kExact));
  const auto imp = an::ball_impacts(p, 3);
  REQUIRE(imp.size() == 3);
  CHECK(imp[1].time == doctest::Approx(2.0 * t1).epsilon(kExact));
  CHECK(imp[2].time == doctest::Approx(2.5 * t1).epsilon(kExact));
  CHECK(imp[2].speed_before == doctest::Approx(0.25 * v1).epsilon(kExact));
  CHECK(imp[2].speed_after == doctest::Approx(0.125 * v1).epsilon(kExact));
  CHECK(an::ball_accumulation_time(p) == doctest::Approx(3.0 * t1).epsilon(kExact));
  // E_k = m g h e^(2k): 19.62, 4.905, 1.22625.
  CHECK(an::ball_energy_after(p, 0) == doctest::Approx(19.62).epsilon(kExact));
  CHECK(an::ball_energy_after(p, 1) == doctest::Approx(4.905).epsilon(kExact));
  CHECK(an::ball_energy_after(p, 2) == doctest::Approx(1.22625).epsilon(kExact));
  // State: on the ground at the impact times; apex of the first arc at t1 + t1/2 with
  // height e^2 h = 0.25; at rest after accumulation.
  CHECK(std::abs(an::ball_state(p, 2.0 * t1).position) <= kExact);
  CHECK(an::ball_state(p, 1.5 * t1).position == doctest::Approx(0.25).epsilon(kExact));
  CHECK(std::abs(an::ball_state(p, 1.5 * t1).velocity) <= kExact * v1);
  CHECK(an::ball_state(p, 3.5 * t1).position == 0.0);
  CHECK(an::ball_state(p, 3.5 * t1).velocity == 0.0);
}

TEST_CASE("bouncing ball with initial velocity and the limiting restitutions") {
  // From the ground moving up at 2 m/s: t1 = 2 v0 / g, V1 = 2.
  const BouncingBall::Parameters up{.height = 0.0, .velocity = 2.0, .restitution = 0.8};
  CHECK(an::ball_first_impact_time(up) == doctest::Approx(4.0 / 9.81).epsilon(kExact));
  CHECK(an::ball_first_impact_speed(up) == doctest::Approx(2.0).epsilon(kExact));
  // t_inf = t1 + 2 e V1 / (g (1 - e)) = 4/g + 3.2/(0.2 g) = 20/g.
  CHECK(an::ball_accumulation_time(up) == doctest::Approx(20.0 / 9.81).epsilon(kExact));
  // Thrown down from h = 1 at 3 m/s: 1 - 3 t - g t^2/2 = 0.
  const BouncingBall::Parameters down{.height = 1.0, .velocity = -3.0};
  const double t = an::ball_first_impact_time(down);
  CHECK(1.0 - 3.0 * t - 0.5 * 9.81 * t * t == doctest::Approx(0.0).scale(1.0).epsilon(kExact));
  // e = 1 never accumulates; e = 0 stops at the first impact.
  CHECK(std::isinf(an::ball_accumulation_time({.restitution = 1.0})));
  const BouncingBall::Parameters dead{.height = 1.0, .restitution = 0.0};
  CHECK(an::ball_accumulation_time(dead) == doctest::Approx(std::sqrt(2.0 / 9.81)));
  CHECK(an::ball_impacts(dead, 5).size() == 1);
  CHECK_THROWS_AS(an::ball_impacts(dead, -1), std::invalid_argument);
  CHECK_THROWS_AS(an::ball_first_impact_time({.velocity = -1.0, .gravity = 0.0}),
                  std::invalid_argument);
  CHECK_THROWS_AS(an::ball_state(dead, -1.0), std::invalid_argument);
}

TEST_CASE("bouncing ball state conserves energy between impacts") {
  const BouncingBall::Parameters p{.mass = 1.5, .height = 2.0, .velocity = 1.0,
                                   .restitution = 0.7};
  const auto imp = an::ball_impacts(p, 6);
  for (std::size_t k = 0; k + 1 < imp.size(); ++k) {
    const double tm = 0.5 * (imp[k].time + imp[k + 1].time);
    const auto s = an::ball_state(p, tm);
    const double e = 0.5 * p.mass * s.velocity * s.velocity + p.mass * p.gravity * s.position;
    CHECK(e == doctest::Approx(an::ball_energy_after(p, static_cast<int>(k) + 1)).epsilon(kEnergy));
  }
}

// ---------------------------------------------------------------------------------------
TEST_CASE("impact oscillator: hand-derived impact sequences") {
  SUBCASE("stop at the equilibrium (d = 0): impacts every half period") {
    // w = 1, x0 = -1 from rest: x = -cos t reaches 0 at t = pi/2 with V = 1; with d = 0 the
    // rebound arc is a half sine of duration pi; speeds e^k.
    const ImpactOscillator::Parameters p{.mass = 1.0, .stiffness = 1.0, .gap = 0.0,
                                         .restitution = 0.5, .initial_position = -1.0};
    const auto imp = an::oscillator_impacts(p, 4);
    REQUIRE(imp.size() == 4);
    for (int k = 0; k < 4; ++k) {
      CHECK(imp[k].time == doctest::Approx(kPi / 2.0 + k * kPi).epsilon(kExact));
      CHECK(imp[k].speed_before == doctest::Approx(std::pow(0.5, k)).epsilon(kExact));
      CHECK(imp[k].amplitude_after == doctest::Approx(std::pow(0.5, k + 1)).epsilon(kExact));
    }
    // Midway through the second arc: x = -0.5 sin(pi/2) = -0.5.
    CHECK(an::oscillator_state(p, kPi).position == doctest::Approx(-0.5).epsilon(kExact));
  }
  SUBCASE("stop beyond the equilibrium (d = 0.5), elastic") {
    // w = 2 (k = 4, m = 1), x0 = 0, v0 = 2: x = sin(2t) reaches 0.5 at t = pi/12 with
    // V = 2 cos(pi/6) = sqrt(3). With e = 1 the orbit leaves at phase pi/3 and returns at
    // 5 pi/3: T = (4 pi/3)/2 = 2 pi/3.
    const ImpactOscillator::Parameters p{.mass = 1.0, .stiffness = 4.0, .gap = 0.5,
                                         .restitution = 1.0, .initial_velocity = 2.0};
    const auto imp = an::oscillator_impacts(p, 3);
    REQUIRE(imp.size() == 3);
    CHECK(imp[0].time == doctest::Approx(kPi / 12.0).epsilon(kExact));
    CHECK(imp[0].speed_before == doctest::Approx(std::sqrt(3.0)).epsilon(kExact));
    CHECK(imp[1].time - imp[0].time == doctest::Approx(2.0 * kPi / 3.0).epsilon(kExact));
    CHECK(imp[0].amplitude_after == doctest::Approx(1.0).epsilon(kExact));
    CHECK(an::oscillator_time_between_impacts(2.0, std::sqrt(3.0), 0.5, 1.0) ==
          doctest::Approx(2.0 * kPi / 3.0).epsilon(kExact));
    CHECK(an::oscillator_impact_speed(2.0, 1.0, 0.5) == doctest::Approx(std::sqrt(3.0)));
  }
  SUBCASE("stop before the equilibrium (d < 0): impacts accumulate, then rest on the stop") {
    // w = 1, x0 = -1 from rest, d = -0.5: x = -cos t reaches -0.5 at t = pi/3, V = sqrt(3)/2.
    const ImpactOscillator::Parameters p{.mass = 1.0, .stiffness = 1.0, .gap = -0.5,
                                         .restitution = 0.5, .initial_position = -1.0};
    const auto imp = an::oscillator_impacts(p, 40);
    REQUIRE(imp.size() == 40);
    CHECK(imp[0].time == doctest::Approx(kPi / 3.0).epsilon(kExact));
    CHECK(imp[0].speed_before == doctest::Approx(std::sqrt(3.0) / 2.0).epsilon(kExact));
    // Each arc from the stop at speed eV: phase phi = atan2(eV, d) in (pi/2, pi), duration
    // 2 (pi - phi) -> 0 geometrically: the impact times converge.
    CHECK(imp[39].time - imp[38].time < kAccumulated);
    const auto s = an::oscillator_state(p, imp[39].time + 1.0);
    CHECK(s.position == -0.5);
    CHECK(s.velocity == 0.0);
  }
}

TEST_CASE("impact oscillator state: at the stop at impacts, energy amplitude in between") {
  const ImpactOscillator::Parameters p{.mass = 2.0, .stiffness = 8.0, .gap = 0.3,
                                       .restitution = 0.8, .initial_position = -0.2,
                                       .initial_velocity = 1.5};
  const double w = 2.0;
  const auto imp = an::oscillator_impacts(p, 6);
  REQUIRE(imp.size() == 6);
  for (std::size_t k = 0; k < imp.size(); ++k) {
    const auto before = an::oscillator_state(p, imp[k].time - kBeforeImpact);
    CHECK(before.position == doctest::Approx(0.3).epsilon(kNearImpact));
    CHECK(before.velocity == doctest::Approx(imp[k].speed_before).epsilon(kNearImpact));
    if (k + 1 < imp.size()) {
      const auto mid = an::oscillator_state(p, 0.5 * (imp[k].time + imp[k + 1].time));
      CHECK(mid.position <= 0.3);
      CHECK(std::hypot(mid.position, mid.velocity / w) ==
            doctest::Approx(imp[k].amplitude_after).epsilon(kEnergy));
    }
  }
  CHECK_THROWS_AS(an::oscillator_impacts({.damping_ratio = 0.1}, 1), std::invalid_argument);
  CHECK_THROWS_AS(an::oscillator_impacts({.force_amplitude = 1.0}, 1), std::invalid_argument);
  // Out of reach: amplitude 0.05 < gap 0.1.
  CHECK(an::oscillator_impacts({.initial_position = 0.05}, 3).empty());
}

// ---------------------------------------------------------------------------------------
TEST_CASE("block with Coulomb friction: stopping, sticking and slipping") {
  // v0 = 3, mu = 0.5, g = 9.81: t_s = 3 / 4.905, x_s = 9 / 9.81.
  CHECK(an::block_stopping_time(3.0, 0.5, 9.81) == doctest::Approx(3.0 / 4.905).epsilon(kExact));
  CHECK(an::block_stopping_distance(3.0, 0.5, 9.81) == doctest::Approx(9.0 / 9.81).epsilon(kExact));
  const SlidingBlock::Parameters free{.mass = 2.0, .friction = 0.5, .initial_velocity = 3.0};
  const auto at_stop = an::block_state(free, 3.0 / 4.905);
  CHECK(at_stop.position == doctest::Approx(9.0 / 9.81).epsilon(kExact));
  CHECK(std::abs(at_stop.velocity) <= kExact);
  CHECK(an::block_state(free, 5.0).position == doctest::Approx(9.0 / 9.81).epsilon(kExact));
  // A force below mu m g (= 9.81 kN) keeps it stuck after stopping; the stop comes later:
  // deceleration (mu m g - F)/m = (9.81 - 4)/2.
  SlidingBlock::Parameters pushed = free;
  pushed.force = 4.0;
  const double a = (9.81 - 4.0) / 2.0;
  CHECK(an::block_state(pushed, 10.0).position == doctest::Approx(9.0 / (2.0 * a)).epsilon(kExact));
  CHECK(an::block_sticks(4.0, 0.5, 19.62));
  CHECK_FALSE(an::block_sticks(10.0, 0.5, 19.62));
  // A force above mu m g: slides forever with (F - mu m g)/m = (12 - 9.81)/2.
  SlidingBlock::Parameters hard = free;
  hard.force = 12.0;
  hard.initial_velocity = 0.0;
  CHECK(an::block_state(hard, 2.0).velocity == doctest::Approx(2.0 * 2.19 / 2.0).epsilon(kExact));
  // Incline 30 deg with mu = 0.3 < tan 30: from rest slides downhill (-x) with
  // a = g (sin 30 - 0.3 cos 30) = 9.81 (0.5 - 0.259808) = 2.356283.
  const SlidingBlock::Parameters slope{.mass = 1.0, .friction = 0.3, .incline_deg = 30.0};
  CHECK(an::block_state(slope, 1.0).velocity ==
        doctest::Approx(-9.81 * (0.5 - 0.3 * std::sqrt(3.0) / 2.0)).epsilon(kExact));
  // mu = 0.7 > tan 30: stays.
  const SlidingBlock::Parameters steep_mu{.mass = 1.0, .friction = 0.7, .incline_deg = 30.0};
  CHECK(an::block_state(steep_mu, 1.0).velocity == 0.0);
  CHECK_THROWS_AS(an::block_state({.force_amplitude = 1.0}, 1.0), std::invalid_argument);
}

TEST_CASE("block under a harmonic force: first slip against numerical quadrature") {
  // F0 = 2 mu m g: breakaway when sin(W t) = 1/2, t_b = (pi/6)/W (hand).
  const double m = 1.0, mu = 0.4, g = 9.81, f = 1.0, om = 2.0 * kPi * f;
  const SlidingBlock::Parameters p{.mass = m, .friction = mu, .gravity = g,
                                   .force_amplitude = 2.0 * mu * m * g, .force_frequency = f};
  const auto slip = an::block_harmonic_first_slip(p);
  REQUIRE(slip.slips);
  CHECK(slip.direction == 1.0);
  CHECK(slip.start_time == doctest::Approx(kPi / 6.0 / om).epsilon(kExact));
  // Independent check: RK4 on m v' = F0 sin(W t) - mu m g, x' = v from t_b until v < 0.
  const double dt = 1e-5;
  double t = slip.start_time, v = 0.0, x = 0.0;
  auto acc = [&](double tt) { return (2.0 * mu * m * g * std::sin(om * tt) - mu * m * g) / m; };
  for (;;) {
    // v' depends on t only: Simpson's rule is exact RK4 here.
    const double v1 = v + dt * (acc(t) + 4.0 * acc(t + dt / 2) + acc(t + dt)) / 6.0;
    if (v1 <= 0.0) {
      const double frac = v / (v - v1);  // linear interpolation of the zero crossing
      x += frac * dt * v / 2.0;
      t += frac * dt;
      break;
    }
    x += dt * (v + v1) / 2.0 + dt * dt * (acc(t) - acc(t + dt)) / 12.0;
    v = v1;
    t += dt;
  }
  CHECK(slip.end_time == doctest::Approx(t).epsilon(kQuadrature));
  CHECK(slip.displacement == doctest::Approx(x).epsilon(kQuadratureDisplacement));
  // Below the threshold it never slips.
  SlidingBlock::Parameters weak = p;
  weak.force_amplitude = 0.9 * mu * m * g;
  CHECK_FALSE(an::block_harmonic_first_slip(weak).slips);
}

TEST_CASE("friction oscillator: decay of 4 mu g / w^2 per cycle and the stick position") {
  // w = 1, mu g = 0.1 -> delta = 0.1; from x0 = 1: 1, -0.8, 0.6, -0.4, 0.2, 0 (stops: |0| <=
  // delta). Two half cycles (one cycle) reduce the amplitude by 4 delta = 0.4.
  const an::FrictionOscillator p{.omega = 1.0, .friction = 0.1 / 9.81, .gravity = 9.81,
                                 .initial_position = 1.0};
  const auto x = an::friction_oscillator_turning_points(p);
  const std::vector<double> expected{1.0, -0.8, 0.6, -0.4, 0.2, 0.0};
  REQUIRE(x.size() == expected.size());
  for (std::size_t i = 0; i < x.size(); ++i) CHECK(x[i] == doctest::Approx(expected[i]).scale(1.0));
  // First half cycle about c = 0.1: x(pi/2) = 0.1, v(pi/2) = -0.9.
  const auto s = an::friction_oscillator_state(p, kPi / 2.0);
  CHECK(s.position == doctest::Approx(0.1).epsilon(kExact));
  CHECK(s.velocity == doctest::Approx(-0.9).epsilon(kExact));
  // Stuck after 5 half cycles.
  CHECK(an::friction_oscillator_state(p, 5.0 * kPi + 0.1).position == doctest::Approx(0.0).scale(1.0));
  // A start inside the stick band +-delta does not move.
  const an::FrictionOscillator band{.omega = 2.0, .friction = 0.5, .gravity = 9.81,
                                    .initial_position = 1.0};  // delta = 1.22625
  CHECK(an::friction_oscillator_turning_points(band).size() == 1);
}

// ---------------------------------------------------------------------------------------
namespace {
// The defining conditions of eqs. (3)-(7) for a solution of an impact problem, checked
// directly (independently of how the solution was found).
void check_impact_conditions(const an::ImpactProblem& p, const an::ImpactSolution& s) {
  const auto m = p.restitution.size();
  Eigen::VectorXd z(2 * m);
  z << s.lambda_n, s.lambda_t;
  const Eigen::VectorXd gp = p.delassus * z + p.gdot_minus;
  const double tol = kSolve * (1.0 + p.gdot_minus.cwiseAbs().maxCoeff());
  const double itol = tol / p.delassus.cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < m; ++i) {
    const double gn0 = gp(i) + p.restitution(i) * p.gdot_minus(i);
    CHECK(s.lambda_n(i) >= -itol);
    CHECK(gn0 >= -tol);
    CHECK(std::abs(gn0 * s.lambda_n(i)) <= tol * (1.0 + s.lambda_n(i)));
    CHECK(std::abs(s.lambda_t(i)) <= p.friction(i) * s.lambda_n(i) + itol);
    // Sliding => full friction opposite to the sliding velocity.
    if (std::abs(gp(m + i)) > tol) {
      CHECK(s.lambda_t(i) == doctest::Approx(-p.friction(i) * s.lambda_n(i) *
                                             (gp(m + i) > 0 ? 1.0 : -1.0)).scale(itol * 1e3));
    }
  }
}
}  // namespace

TEST_CASE("deck impact: hand-solved frictionless cases") {
  const an::DeckBody g{.mass = 2.0, .inertia = 3.0, .deck = {.length = 4.0, .width = 1.0}};
  SUBCASE("straight deck, both right corners, central: u+ = (-e v, 0, 0)") {
    const auto r = an::deck_impact(g, {3, 4}, Eigen::Vector3d(1.5, 0.0, 0.0), 0.6, 0.0);
    CHECK(r.solutions == 1);
    CHECK(r.velocity_after(0) == doctest::Approx(-0.9).epsilon(kSolve));
    CHECK(std::abs(r.velocity_after(1)) <= kSolve);
    CHECK(std::abs(r.velocity_after(2)) <= kSolve);
    // Each corner takes half of m (1 + e) v = 4.8.
    CHECK(r.contact.lambda_n(0) == doctest::Approx(2.4).epsilon(kSolve));
    CHECK(r.contact.lambda_n(1) == doctest::Approx(2.4).epsilon(kSolve));
  }
  SUBCASE("straight deck, corner 3 alone") {
    // r = (2, 0.5), n = (-1, 0): W_N = (-1, 0, r x n = 0.5). G = 1/2 + 0.25/3 = 7/12.
    // gdot_N- = -v = -1; Lambda = (1 + e) v / G = 1.5 * 12/7 = 18/7 for e = 0.5.
    // u+ = u- + M^-1 W_N Lambda = (1 - 9/7, 0, 0.5 * 18/7 / 3) = (-2/7, 0, 3/7).
    const auto r = an::deck_impact(g, {3}, Eigen::Vector3d(1.0, 0.0, 0.0), 0.5, 0.0);
    CHECK(r.contact.lambda_n(0) == doctest::Approx(18.0 / 7.0).epsilon(kSolve));
    CHECK(r.velocity_after(0) == doctest::Approx(-2.0 / 7.0).epsilon(kSolve));
    CHECK(r.velocity_after(2) == doctest::Approx(3.0 / 7.0).epsilon(kSolve));
    // Newton: the corner's normal velocity after = -e * before = 0.5.
    CHECK(r.contact.gdot_n_plus(0) == doctest::Approx(0.5).epsilon(kSolve));
  }
  SUBCASE("corner geometry of the contract") {
    const nsb::models::DeckGeometry sk{.length = 4.0, .width = 2.0, .skew_deg = 45.0};
    // tan 45 = 1: corners (+-2 +- 1, +-1) with (end, side).
    CHECK(an::deck_corner(sk, 1).isApprox(Eigen::Vector2d(-1.0, 1.0)));
    CHECK(an::deck_corner(sk, 2).isApprox(Eigen::Vector2d(-3.0, -1.0)));
    CHECK(an::deck_corner(sk, 3).isApprox(Eigen::Vector2d(3.0, 1.0)));
    CHECK(an::deck_corner(sk, 4).isApprox(Eigen::Vector2d(1.0, -1.0)));
    // The right face through corners 3, 4 has direction (1, 1)/sqrt2 = +-t and normal
    // n = (-1, 1)/sqrt2.
    const auto c3 = an::deck_contact_columns(sk, 3);
    const double h = std::sqrt(0.5);
    CHECK(c3.w_normal.head<2>().isApprox(Eigen::Vector2d(-h, h)));
    CHECK(c3.w_tangent.head<2>().isApprox(Eigen::Vector2d(-h, -h)));
    // r x n = 3 h + 1 h = 4h; r x t = -3h + h = -2h = -(L/2) cos a.
    CHECK(c3.w_normal(2) == doctest::Approx(4.0 * h));
    CHECK(c3.w_tangent(2) == doctest::Approx(-2.0 * h));
    const auto c1 = an::deck_contact_columns(sk, 1);
    CHECK(c1.w_normal.head<2>().isApprox(Eigen::Vector2d(h, -h)));
  }
}

TEST_CASE("deck impact: one corner with friction, stick and slide by hand") {
  // Straight deck, corner 3 at r = (L/2, W/2) = (2, 0.5), m = 2, I = 3. n = (-1, 0),
  // t = (0, -1): W_N = (-1, 0, 0.5), W_T = (0, -1, -2).
  // G_NN = 1/2 + 0.25/3 = 7/12, G_NT = 0.5*(-2)/3 = -1/3, G_TT = 1/2 + 4/3 = 11/6.
  const an::DeckBody g{.mass = 2.0, .inertia = 3.0, .deck = {.length = 4.0, .width = 1.0}};
  SUBCASE("stick (e = 0, mu large)") {
    // u- = (1, 0, 0): gdot_N- = -1, gdot_T- = 0. Stick: G [LN; LT] = [1; 0]
    // -> det = 77/72 - 1/9 = 69/72; LN = (11/6)/(69/72) = 132/69, LT = (1/3)/(69/72) = 24/69.
    // |LT|/LN = 24/132 = 0.1818: sticks for mu >= 0.1818.
    const auto r = an::deck_impact(g, {3}, Eigen::Vector3d(1.0, 0.0, 0.0), 0.0, 0.5);
    REQUIRE(r.solutions == 1);
    CHECK(r.contact.cases[0] == an::ImpactCase::kStick);
    CHECK(r.contact.lambda_n(0) == doctest::Approx(132.0 / 69.0).epsilon(kSolve));
    CHECK(r.contact.lambda_t(0) == doctest::Approx(24.0 / 69.0).epsilon(kSolve));
    CHECK(std::abs(r.contact.gdot_t_plus(0)) <= kSolve);
    check_impact_conditions(r.problem, r.contact);
  }
  SUBCASE("slide (e = 0, mu = 0.1 < 0.1818)") {
    // The sticking impulse ratio would need 0.1818 > mu: slide. The stick solution has
    // LT > 0; sliding keeps that sign: LT = +mu LN, i.e. slide with gdot_T+ < 0.
    // Normal: (G_NN + mu G_NT) LN = 1 -> LN = 1/(7/12 - 1/30) = 60/33;
    // gdot_T+ = (G_TN + mu G_TT) LN = (-1/3 + 11/60)(60/33) = -9/33 < 0. Consistent.
    const auto r = an::deck_impact(g, {3}, Eigen::Vector3d(1.0, 0.0, 0.0), 0.0, 0.1);
    REQUIRE(r.solutions == 1);
    CHECK(r.contact.cases[0] == an::ImpactCase::kSlideNegative);
    CHECK(r.contact.lambda_n(0) == doctest::Approx(60.0 / 33.0).epsilon(kSolve));
    CHECK(r.contact.lambda_t(0) == doctest::Approx(6.0 / 33.0).epsilon(kSolve));
    CHECK(r.contact.gdot_t_plus(0) == doctest::Approx(-9.0 / 33.0).epsilon(kSolve));
    check_impact_conditions(r.problem, r.contact);
  }
  SUBCASE("slide the other way: corner 4, the mirror image") {
    // Corner 4 at r = (2, -0.5): W_N = (-1, 0, -0.5), W_T = (0, -1, -2); G_NT = +1/3.
    // The sticking impulse ratio is -24/132; with mu = 0.1 it slides with LT = -mu LN:
    // LN = 1/(7/12 - 1/30) = 60/33, gdot_T+ = (1/3 - 11/60)(60/33) = +9/33 > 0.
    const auto r = an::deck_impact(g, {4}, Eigen::Vector3d(1.0, 0.0, 0.0), 0.0, 0.1);
    REQUIRE(r.solutions == 1);
    CHECK(r.contact.cases[0] == an::ImpactCase::kSlidePositive);
    CHECK(r.contact.lambda_n(0) == doctest::Approx(60.0 / 33.0).epsilon(kSolve));
    CHECK(r.contact.lambda_t(0) == doctest::Approx(-6.0 / 33.0).epsilon(kSolve));
    CHECK(r.contact.gdot_t_plus(0) == doctest::Approx(9.0 / 33.0).epsilon(kSolve));
    // Mirror symmetry y -> -y: vy and omega change sign, vx is the same as for corner 3.
    const auto r3 = an::deck_impact(g, {3}, Eigen::Vector3d(1.0, 0.0, 0.0), 0.0, 0.1);
    CHECK(r.velocity_after(0) == doctest::Approx(r3.velocity_after(0)).epsilon(kSolve));
    CHECK(r.velocity_after(1) == doctest::Approx(-r3.velocity_after(1)).epsilon(kSolve));
    CHECK(r.velocity_after(2) == doctest::Approx(-r3.velocity_after(2)).epsilon(kSolve));
    check_impact_conditions(r.problem, r.contact);
  }
}

TEST_CASE("impact by cases: random problems satisfy eqs. (3)-(7)") {
  std::mt19937 rng(20170615);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int multiple = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const an::DeckBody g{.mass = 0.5 + 2.0 * u01(rng), .inertia = 0.2 + 3.0 * u01(rng),
                             .deck = {.length = 1.0 + 4.0 * u01(rng), .width = 0.3 + 1.5 * u01(rng),
                             .skew_deg = -60.0 + 120.0 * u01(rng)}};
    const Eigen::Vector3d v(0.2 + u01(rng), -1.0 + 2.0 * u01(rng), -0.5 + u01(rng));
    const double e = u01(rng), mu = 0.8 * u01(rng);
    const std::vector<int> corners = trial % 2 ? std::vector<int>{3, 4} : std::vector<int>{3};
    const auto r = an::deck_impact(g, corners, v, e, mu);
    an::ImpactCases all = an::solve_impact_by_cases(r.problem);
    CAPTURE(trial);
    REQUIRE(!all.solutions.empty());
    if (!all.unique()) ++multiple;
    for (const auto& s : all.solutions) check_impact_conditions(r.problem, s);
  }
  MESSAGE("problems with more than one solution: " << multiple << " of 300");
}

// ---------------------------------------------------------------------------------------
TEST_CASE("rotation criterion: hand values, both branches, the printed eq. (1)") {
  // Straight deck, mu = 0.5, W/L = 0.2: eta = +- mu L/W = +-2.5; printed +-5.
  auto c = an::rotation_criterion({.skew_deg = 0.0, .width = 2.0, .length = 10.0, .friction = 0.5});
  CHECK(c.eta_plus == doctest::Approx(2.5).epsilon(kExact));
  CHECK(c.eta_minus == doctest::Approx(-2.5).epsilon(kExact));
  CHECK(c.printed_eta_plus == doctest::Approx(5.0).epsilon(kExact));
  CHECK(c.rotation);
  // Frictionless skew 45 deg, W/L = 0.4: eta = sin 90 / 0.8 = 1.25 (both branches).
  c = an::rotation_criterion({.skew_deg = 45.0, .width = 4.0, .length = 10.0, .friction = 0.0});
  CHECK(c.eta_plus == doctest::Approx(1.25).epsilon(kExact));
  CHECK(c.eta_minus == doctest::Approx(1.25).epsilon(kExact));
  // Straight, mu = 0.15, W/L = 0.2: derived 0.75 (no rotation), printed 1.5 (rotation).
  c = an::rotation_criterion({.skew_deg = 0.0, .width = 2.0, .length = 10.0, .friction = 0.15});
  CHECK_FALSE(c.rotation);
  CHECK(c.printed_rotation);
  // Skew 30, W/L = 0.5, mu = 0.2: sin 60/1 = 0.866025; mu cos^2 30 / 0.5 = 0.3.
  c = an::rotation_criterion({.skew_deg = 30.0, .width = 5.0, .length = 10.0, .friction = 0.2});
  CHECK(c.eta_plus == doctest::Approx(std::sqrt(3.0) / 2.0 + 0.3).epsilon(kExact));
  CHECK(c.eta_minus == doctest::Approx(std::sqrt(3.0) / 2.0 - 0.3).epsilon(kExact));
  CHECK(c.rotation);
  CHECK_THROWS_AS(an::rotation_criterion({.width = 0.0}), std::invalid_argument);
  CHECK_THROWS_AS(an::rotation_criterion({.friction = -0.1}), std::invalid_argument);
  CHECK_THROWS_AS(an::rotation_criterion({.skew_deg = 90.0}), std::invalid_argument);
  CHECK_THROWS_AS(an::rotation_criterion({.length = NAN}), std::invalid_argument);
}

TEST_CASE("rotation criterion against the two-corner impact solved by cases") {
  // Grid of skew, W/L, mu, e and pre-impact direction; the deck (not rotating before) hits
  // the right abutment with corners 3 and 4 at once. It must rotate after the impact
  // exactly where |eta(k)| > 1 for the impulse ratio k of that impact, and never where
  // max |eta_+-| <= 1. Points within kBand of |eta| = 1 are boundary cases and skipped.
  constexpr double kBand = 1e-6;
  constexpr double kRotating = 1e-9;  // |omega+| L / |v| above round-off of a zero
  int checked = 0, rotating = 0;
  for (double skew : {-50.0, -30.0, -10.0, 0.0, 5.0, 20.0, 35.0, 60.0}) {
    for (double wl : {0.1, 0.2, 0.35, 0.6, 1.0}) {
      for (double mu : {0.0, 0.1, 0.3, 0.5, 0.8}) {
        for (double e : {0.0, 0.6}) {
          for (double vy : {-2.0, -0.5, 0.0, 0.5, 2.0}) {
            const double length = 10.0;
            const an::CriterionInput in{.skew_deg = skew, .width = wl * length,
                                        .length = length, .friction = mu};
            const double vx = 1.0;
            const double a = skew * kPi / 180.0;
            if (-vx * std::cos(a) + vy * std::sin(a) >= 0.0) continue;  // not approaching
            const auto pred = an::predict_right_end_impact(in, vx, vy, e);
            if (std::abs(std::abs(pred.eta) - 1.0) < kBand) continue;
            const an::DeckBody g{.mass = 3.0, .inertia = 3.0 * length * length / 12.0,
                                     .deck = {.length = length, .width = in.width, .skew_deg = skew}};
            const auto r = an::deck_impact(g, {3, 4}, Eigen::Vector3d(vx, vy, 0.0), e, mu);
            CAPTURE(skew);
            CAPTURE(wl);
            CAPTURE(mu);
            CAPTURE(e);
            CAPTURE(vy);
            CAPTURE(pred.eta);
            REQUIRE(r.solutions == 1);
            check_impact_conditions(r.problem, r.contact);
            const bool rot = std::abs(r.velocity_after(2)) * length > kRotating * std::hypot(vx, vy);
            CHECK(rot == pred.rotation);
            if (!an::rotation_criterion(in).rotation) CHECK_FALSE(rot);
            ++checked;
            rotating += rot;
          }
        }
      }
    }
  }
  MESSAGE(checked << " impacts checked, " << rotating << " rotating");
  CHECK(rotating > 50);
  CHECK(checked - rotating > 50);
}

TEST_CASE("the criterion refuses inputs whose eta is not a finite number") {
  // W/L = 1e-300 / 1e300 underflows to 0: eta = sin(2a) / (2 W/L) is inf, mu cos^2(a) / (W/L)
  // inf, their difference NaN. Each input lies in its range, so validate() accepts them.
  const an::CriterionInput in{.skew_deg = 30.0, .width = 1e-300, .length = 1e300, .friction = 0.2};
  CHECK_NOTHROW(in.validate());
  CHECK_FALSE(an::finite_criterion(in, an::rotation_criterion(in)));
  try {
    an::checked_rotation_criterion(in);
    FAIL("accepted");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()) ==
          "width: W = 1e-300 m and L = 1e+300 m (W/L = 0, mu = 0.2) make eta non-finite; "
          "expected W/L, L/W and mu L/W within the range of a double");
  }
  // W/L = 2.44 / 33.35 is normal: the straight deck's eta = +-mu L/W = +-6.834 (mu = 0.5).
  const an::CriterionInput ok{.skew_deg = 0.0, .width = 2.44, .length = 33.35, .friction = 0.5};
  CHECK(an::checked_rotation_criterion(ok).eta_plus == doctest::Approx(0.5 * 33.35 / 2.44));
}
