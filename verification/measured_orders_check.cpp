// Measured orders of convergence, asserted: for each case at least four refinements, the
// least-squares slope of log(error) against log(parameter), and the error constant C of
// error = C parameter^p, each against a derived or measured value with a stated margin.
// The numbers are tabulated in docs/verification.md.
//
//  1. Moreau–Jean with Coulomb friction: the sliding block against its closed form.
//  2. Moreau–Jean with two simultaneous contacts: a free deck striking a seat with both
//     corners of one end, against the exact impact (eq. 6 by case enumeration) and free flight.
//  3. Event-driven: the error against its tolerance, down to 1e-10, on the impact oscillator.
//  4. Compliance against the nonsmooth answer as the Hertz stiffness k grows: undamped
//     (e = 1, derived constant) and Lankarani–Nikravesh damping with the nonsmooth restitution
//     set to the law's effective restitution (docs/compliance.md).
#include "integrators/run.hpp"
#include "models/analytic.hpp"
#include "models/bridge_parts.hpp"
#include "models/simple_systems.hpp"
#include "verification/convergence.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

namespace ni = nsb::integrators;
namespace nm = nsb::models;
namespace na = nsb::models::analytic;

namespace {

using Fit = nsb::verification::PowerFit;
constexpr auto fit = nsb::verification::fit_power_law;

void report(const char* name, const char* parameter, const std::vector<double>& x,
            const std::vector<double>& e, const Fit& f) {
  std::printf("%s\n", name);
  for (std::size_t i = 0; i < x.size(); ++i) {
    std::printf("  %s = %-10.4g error = %.4e\n", parameter, x[i], e[i]);
  }
  std::printf("  slope %.4f, constant %.4e\n", f.slope, f.constant);
}

// |value - target| <= rel |target| (doctest's Approx adds 1 to the scale, which hides
// relative errors of numbers below 1).
bool within(double value, double target, double rel) {
  return std::abs(value - target) <= rel * std::abs(target);
}

ni::Recorder run(ni::System& s, const ni::RunConfig& config) {
  ni::Recorder rec(s, 0.0);
  const auto result = ni::integrate(s, config, rec);
  REQUIRE(ni::succeeded(result.status));
  return rec;
}

double last(const ni::Recorder& r, const char* column) { return r.series(column).back(); }

// Section 3's measured error constant (see the test).
constexpr double kEventConstant = 1.89;
// Section 4's measured constant of the damped case at k = k0 [m] (see the test).
constexpr double kDampedConstant = 3.038e-3;

}  // namespace

// ------------------------------------------------------------------------------------------
// 1. Sliding block, v0 = 2 m/s, mu = 0.5, g = 9.81: stops at t_s = v0 / (mu g) = 0.4077 s,
// x_s = v0^2 / (2 mu g). With y = 0 resting, every step solves the frictional problem with
// Lambda_N = m g h, and while sliding Lambda_T = -mu m g h: u_k+1 = u_k - mu g h exactly.
// The steps are h = t_s / (N + 1/2), so the stop falls at tau = h/2 into its step:
//  - theta = 1: x_k+1 = x_k + h u_k+1 loses mu g h^2 / 2 per sliding step against the exact
//    x_k + h u_k - mu g h^2 / 2, N (mu g h^2 / 2) = (mu g h / 2)(t_s - h/2) in all, and the stop
//    step adds mu g tau^2 / 2 = mu g h^2 / 8. Final error (v0 / 2) h - mu g h^2 / 8:
//    order 1, C = v0 / 2 = 1.0 m/s.
//  - theta = 1/2: the trapezoidal update is exact while sliding; in the stop step it gives
//    x_k + (h/2) u_k against x_k + u_k^2 / (2 mu g), u_k = mu g tau: error mu g tau (h - tau) / 2
//    = mu g h^2 / 8 at tau = h/2: order 2, C = mu g / 8 = 0.6131 m/s^2.
TEST_CASE("Moreau–Jean with friction: sliding block, orders 1 (theta = 1) and 2 (theta = 1/2)") {
  nm::SlidingBlock::Parameters p;
  p.friction = 0.5;
  p.initial_velocity = 2.0;
  const double mu_g = p.friction * p.gravity;
  const double t_s = p.initial_velocity / mu_g;
  const double x_s = p.initial_velocity * p.initial_velocity / (2.0 * mu_g);
  struct Case {
    double theta, order, constant;
  };
  for (const Case c : {Case{1.0, 1.0, p.initial_velocity / 2.0}, Case{0.5, 2.0, mu_g / 8.0}}) {
    std::vector<double> hs, errors, derived;
    for (int n : {10, 20, 40, 80, 160}) {
      const double h = t_s / (n + 0.5);
      nm::SlidingBlock block(p);
      ni::MoreauJeanOptions o;
      o.end_time = 0.5;  // after the stop: the block rests at x_s
      o.step = h;
      o.theta = c.theta;
      const auto rec = run(block, o);
      hs.push_back(h);
      errors.push_back(std::abs(last(rec, "x") - x_s));
      derived.push_back(c.theta == 1.0 ? c.constant * h - mu_g * h * h / 8.0 : c.constant * h * h);
    }
    const Fit f = fit(hs, errors);
    const Fit g = fit(hs, derived);
    report(c.theta == 1.0 ? "sliding block, theta = 1: |x(T) - x_s| against h"
                          : "sliding block, theta = 1/2: |x(T) - x_s| against h",
           "h", hs, errors, f);
    std::printf("  derived: slope %.4f, constant %.4e (leading constant %.4e)\n", g.slope,
                g.constant, c.constant);
    // The fit of the derived errors: for theta = 1 its h^2 term bends the fit over these h
    // to slope 0.992, C = 0.955 (leading C = 1); for theta = 1/2 it is exact. Measured
    // against it: slope within 1e-4, C within 1e-3 (round-off of x_s ~ 0.4 m is 1e-16).
    CHECK(within(g.slope, c.order, 0.01));
    CHECK(within(f.slope, g.slope, 1e-4));
    CHECK(within(f.constant, g.constant, 1e-3));
  }
}

// ------------------------------------------------------------------------------------------
// 2. Free deck, both corners of the right end striking the seat together (theta = 0, no
// rotation before the impact, so W_N and W_T are those of analytic::deck_contact_columns and
// the step's contact problem is the impact problem of eq. (6) with two contacts). The exact
// motion: free flight to t_hit = gap cos(a) / (closing speed), the impact u- -> u+ (case
// enumeration), free flight again: q(T) = q0 + u- t_hit + u+ (T - t_hit).
// Moreau–Jean takes the impact in the step whose start has g + (h/2) gdot <= 0, i.e. at
// tau = t_hit - t_k in (-h/2, h/2]. Its end position is q_k + h ((1 - theta) u- + theta u+)
// against the exact q_k + tau u- + (h - tau) u+; the difference, carried unchanged by the free
// flight, is ((1 - theta) h - tau) (u- - u+). The steps are h = t_hit / (N - 1/4), so
// tau = -h/4 and the error is (5/4 - theta) h |u- - u+|: order 1, C = (5/4 - theta) |du|,
// exact up to round-off (|.| weighs theta by L/2).
TEST_CASE("Moreau–Jean with two simultaneous contacts: free deck on a seat, order 1") {
  nm::BridgeDesign p = nm::BridgeDesign::free_deck();
  p.mass = 140.5;
  p.inertia = 13090.0;
  p.deck.length = 33.35;
  p.deck.width = 2.44;
  p.deck.skew_deg = 20.0;
  p.deck.gap_right = 0.01;
  p.deck.gap_left = 1.0;
  p.restitution = 0.5;  // the corners leave the seat: one impact in the window
  p.friction = 0.3;
  p.initial_velocity = Eigen::Vector3d(0.5, 0.1, 0.0);
  const double a = p.deck.skew_deg * std::numbers::pi / 180.0;
  const Eigen::Vector3d u0 = p.initial_velocity;
  const double closing = u0.x() * std::cos(a) - u0.y() * std::sin(a);
  const double t_hit = p.deck.gap_right * std::cos(a) / closing;
  const auto impact = na::deck_impact({p.mass, p.inertia, p.deck}, {3, 4},
                                      u0, p.restitution, p.friction);
  REQUIRE(impact.solutions == 1);
  const double end = 0.1;
  const Eigen::Vector3d q_exact = u0 * t_hit + impact.velocity_after * (end - t_hit);
  const Eigen::Vector3d weight(1.0, 1.0, p.deck.length / 2.0);
  const double du = (u0 - impact.velocity_after).cwiseProduct(weight).norm();
  for (double theta : {0.5, 1.0}) {
    std::vector<double> hs, errors;
    for (int n : {10, 20, 40, 80, 160}) {
      const double h = t_hit / (n - 0.25);
      nm::Assembly deck(nm::bridge_parts(p));
      ni::MoreauJeanOptions o;
      o.end_time = end;
      o.step = h;
      o.theta = theta;
      const auto rec = run(deck, o);
      const Eigen::Vector3d q(last(rec, "x"), last(rec, "y"), last(rec, "theta"));
      hs.push_back(h);
      errors.push_back((q - q_exact).cwiseProduct(weight).norm());
    }
    const Fit f = fit(hs, errors);
    report(theta == 0.5 ? "free deck two-corner impact, theta = 1/2: |q(T) - q_exact| against h"
                        : "free deck two-corner impact, theta = 1: |q(T) - q_exact| against h",
           "h", hs, errors, f);
    // Exact to round-off by the derivation: slope within 1e-6 of 1, C within 1e-6.
    CHECK(within(f.slope, 1.0, 1e-6));
    CHECK(within(f.constant, (1.25 - theta) * du, 1e-6));
  }
}

// ------------------------------------------------------------------------------------------
// 3. Event-driven against its tolerance: the impact oscillator (m = k = 1, stop at 0.1 m,
// e = 0.5, v0 = 0.3 m/s; 4 impacts in 20 s) against the closed form of analytic.hpp. The
// error of the end state |x - x_exact| + |v - v_exact| / w for tolerances 1e-4 ... 1e-10.
// Dormand–Prince with Odeint's controller keeps the global error proportional to the
// tolerance (tolerance proportionality, Hairer, Norsett & Wanner I, sec. II.4), and the events
// are located to 1e-13 s, far below: expected slope 1.
TEST_CASE("event-driven: error proportional to the tolerance down to 1e-10") {
  nm::ImpactOscillator::Parameters p;
  p.gap = 0.1;
  p.restitution = 0.5;
  p.initial_velocity = 0.3;
  const double end = 20.0;
  const auto exact = na::oscillator_state(p, end);
  std::vector<double> tols, errors;
  for (double tol : {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10}) {
    nm::ImpactOscillator s(p);
    ni::EventDrivenOptions o;
    o.end_time = end;
    o.tolerance = tol;
    const auto rec = run(s, o);
    tols.push_back(tol);
    errors.push_back(std::abs(last(rec, "x") - exact.position) +
                     std::abs(last(rec, "vx") - exact.velocity));
  }
  const Fit f = fit(tols, errors);
  report("event-driven, impact oscillator: end-state error against the tolerance", "tol", tols,
         errors, f);
  // Measured (Release, this machine): slope 0.912, C = 1.89; error / tolerance between 7.6
  // (1e-4) and 12.3 (1e-10). Asserted: slope 1 within 0.12, C within a factor 1.5 of 1.89,
  // and every error below 20 times its tolerance.
  CHECK(within(f.slope, 1.0, 0.12));
  CHECK(f.constant >= kEventConstant / 1.5);
  CHECK(f.constant <= kEventConstant * 1.5);
  for (std::size_t i = 0; i < tols.size(); ++i) CHECK(errors[i] <= 20.0 * tols[i]);
}

// ------------------------------------------------------------------------------------------
// 4. Compliance against the nonsmooth answer as k grows: the bouncing ball (m = 1 t, from 1 m
// at rest, impact speed V = sqrt(2 g) = 4.43 m/s) at T = t_hit + 0.3 s, between the first and
// second impacts, against the closed form (analytic::ball_state) with e = the compliance
// law's effective restitution, for k = 1e-2 ... 1e2 k0 (k0 = 2.747e7 kN/m^1.5), tolerance
// 1e-10 (its error is below 1e-7 m, against model errors of 1e-3 m and more).
// Undamped (e = 1, chi = 0): the Hertz contact lasts t_c = 3.2181 (m^2 / (k^2 V))^(1/5)
// (docs/compliance.md) and returns the ball at speed V, so after it the ball follows the
// rigid trajectory delayed by t_c: y_c(t) = y_r(t - t_c), |y_c - y_r| = t_c |v_r(T)| (1 +
// O(g t_c / V)) with v_r(T) = V - 0.3 g: order -2/5 in k, C = t_c(k0) |V - 0.3 g|.
// Damped (hertzdamp, e_set = 0.8, e_effective = 0.8471, docs/compliance.md): the contact is
// shorter in restitution than in compression; the order is the same, the constant measured.
TEST_CASE("compliance converges to the nonsmooth answer as k grows, order 2/5 in k") {
  struct Case {
    const char* name;
    ni::DampingLaw law;
    double e_set;
  };
  const double k0 = 2.747e7;
  for (const Case c : {Case{"undamped, e = 1", ni::DampingLaw::kHertzDamp, 1.0},
                       Case{"hertzdamp, e_set = 0.8", ni::DampingLaw::kHertzDamp, 0.8}}) {
    nm::BouncingBall::Parameters p;
    p.height = 1.0;
    p.restitution = c.e_set;
    const double e_eff = ni::hunt_crossley_restitution(ni::damping_factor(c.law, c.e_set));
    nm::BouncingBall::Parameters reference = p;
    reference.restitution = e_eff;
    const double t_hit = na::ball_first_impact_time(p);
    const double speed = na::ball_first_impact_speed(p);
    const double end = t_hit + 0.3;
    const auto exact = na::ball_state(reference, end);
    std::vector<double> ks, errors;
    for (double factor : {1e-2, 1e-1, 1.0, 1e1, 1e2}) {
      nm::BouncingBall ball(p);
      ni::ComplianceOptions o;
      o.end_time = end;
      o.tolerance = 1e-10;
      o.stiffness = factor * k0;
      o.law = c.law;
      const auto rec = run(ball, o);
      ks.push_back(factor);
      errors.push_back(std::abs(last(rec, "y") - exact.position));
    }
    const Fit f = fit(ks, errors);
    std::printf("compliance, ball, %s (e_effective %.4f): |y(T) - y_nonsmooth(T)| against k/k0\n",
                c.name, e_eff);
    report("", "k/k0", ks, errors, f);
    if (c.e_set == 1.0) {
      const double t_c = 3.2181 * std::pow(p.mass * p.mass / (k0 * k0 * speed), 0.2);
      const double derived = t_c * std::abs(speed - 0.3 * p.gravity);
      std::printf("  derived t_c |v(T)| at k0: %.4e\n", derived);
      // Measured: slope -0.4056, C 1.8 % above the derivation (the gravity acting during the
      // contact, O(g t_c / V), grows to a few % at 1e-2 k0). Asserted: slope within 0.015
      // of -0.4, C within 3 %.
      CHECK(std::abs(f.slope + 0.4) <= 0.015);
      CHECK(within(f.constant, derived, 0.03));
    } else {
      // Measured: slope -0.4059, C = 3.038e-3 m. Asserted: slope within 0.015 of -0.4, C
      // within 5 % of the measured value.
      CHECK(std::abs(f.slope + 0.4) <= 0.015);
      CHECK(within(f.constant, kDampedConstant, 0.05));
    }
  }
}
