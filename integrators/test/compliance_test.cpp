#include "integrators/compliance.hpp"
#include "integrators/closure_bound.hpp"
#include "integrators/rosenbrock.hpp"
#include "testsupport/systems.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace {

using nsb::integrators::compliance;
using nsb::integrators::ComplianceOptions;
using nsb::integrators::ContactData;
using nsb::integrators::DampingLaw;
using nsb::integrators::EventKind;
using nsb::integrators::Matrix;
using nsb::integrators::Recorder;
using nsb::integrators::RunResult;
using nsb::integrators::Vector;

namespace ts = nsb::testsupport;

// One body of mass m on the line against a wall at x_w = V t: g_N = x - V t.
ts::SpringMass::Parameters against_wall(double m, double x0, double v0, double e,
                                        double wall_velocity = 0.0) {
  return {.mass = m, .initial_position = x0, .initial_velocity = v0, .wall = true,
          .wall_velocity = wall_velocity, .restitution = e};
}

// Integration tolerance of the impact runs: e_effective is then exact to ~1e-7.
constexpr double kTightTolerance = 1e-11;
// e_effective of a single impact against the closed form (Hunt–Crossley relation):
// integration error plus the bisection of the closed form's root.
constexpr double kRestitutionTolerance = 1e-5;

// One body of mass m hits the wall at speed v0 from x = 0.01 m; returns -u(end)/v0 (the
// body flies freely after the impact) and the stats.
double wall_restitution(DampingLaw law, double e, double k, double m = 1.0, double v0 = 1.0,
                        RunResult* stats = nullptr, Recorder* rec_out = nullptr) {
  ts::SpringMass s(against_wall(m, 0.01, -v0, e));
  ComplianceOptions o;
  o.law = law;
  o.stiffness = k;
  o.tolerance = kTightTolerance;
  o.max_step = 1.0;
  // The slowest separation (hunt_crossley_exact at the e floor) leaves at ~1e-3 v0 from a
  // penetration of ~(5 m v0^2 / 4 k)^0.4: end time 40 s covers it for k >= 1e4.
  o.end_time = 40.0;
  Recorder rec(s, 0.0);
  const RunResult st = compliance(s, o, rec);
  REQUIRE(st.completed);
  if (stats) *stats = st;
  if (rec_out) *rec_out = rec;
  const auto v = rec.series("vx");
  return -v.back() / (-v0);
}

}  // namespace

TEST_CASE("compliance: normal and tangential force derivatives match finite differences") {
  // Points away from the kinks (delta = 0, the zero-force clamp, |gdot_T| = eps_v).
  const double k = 2.0e6, chi = 0.6, v = 0.3;
  for (double delta : {1e-4, 3e-3}) {
    for (double rate : {-0.1, 0.05, 0.4}) {
      const auto f = nsb::integrators::hertz_damp_force(k, chi, v, delta, rate);
      REQUIRE(f.force > 0.0);
      const double hd = 1e-7 * delta, hr = 1e-7;
      const double dd = (nsb::integrators::hertz_damp_force(k, chi, v, delta + hd, rate).force -
                         nsb::integrators::hertz_damp_force(k, chi, v, delta - hd, rate).force) /
                        (2 * hd);
      const double dr = (nsb::integrators::hertz_damp_force(k, chi, v, delta, rate + hr).force -
                         nsb::integrators::hertz_damp_force(k, chi, v, delta, rate - hr).force) /
                        (2 * hr);
      CHECK(f.d_penetration == doctest::Approx(dd).epsilon(1e-6));
      CHECK(f.d_rate == doctest::Approx(dr).epsilon(1e-6));
      // Hand value: k delta^1.5 (1 + chi rate / v).
      CHECK(f.force == doctest::Approx(k * std::pow(delta, 1.5) * (1 + chi * rate / v)));
    }
  }
  // Open gap and the no-adhesion clamp give zero force and zero derivatives.
  CHECK(nsb::integrators::hertz_damp_force(k, chi, v, -1e-3, -1.0).force == 0.0);
  const auto pulled = nsb::integrators::hertz_damp_force(k, chi, v, 1e-3, -10.0);
  CHECK(pulled.force == 0.0);
  CHECK(pulled.d_rate == 0.0);

  const double mu = 0.5, eps = 1e-3, ln = 100.0;
  for (double slip : {-5e-3, -4e-4, 2e-4, 7e-3}) {
    const auto t = nsb::integrators::regularized_coulomb(mu, ln, slip, eps);
    const double h = 1e-9;
    const double ds = (nsb::integrators::regularized_coulomb(mu, ln, slip + h, eps).force -
                       nsb::integrators::regularized_coulomb(mu, ln, slip - h, eps).force) /
                      (2 * h);
    const double dn = (nsb::integrators::regularized_coulomb(mu, ln + 1e-3, slip, eps).force -
                       nsb::integrators::regularized_coulomb(mu, ln - 1e-3, slip, eps).force) /
                      2e-3;
    CHECK(t.d_slip == doctest::Approx(ds).epsilon(1e-6));
    CHECK(t.d_normal == doctest::Approx(dn).epsilon(1e-9));
    // Eq. (10): opposes the slip, |lambda_T| = mu lambda_N once |gdot_T| >= eps.
    CHECK(t.force * slip < 0.0);
    if (std::abs(slip) >= eps) CHECK(std::abs(t.force) == doctest::Approx(mu * ln));
  }
}

TEST_CASE("compliance: the Hunt–Crossley restitution relation and the laws' factors") {
  using nsb::integrators::damping_factor;
  using nsb::integrators::hunt_crossley_restitution;
  // Small chi: e = 1 - 2 chi / 3 + O(chi^2) (expand 1 - chi e = (1 + chi) e^{-chi (1 + e)}
  // to third order in chi with e = 1 - a chi: a = 2/3; Lankarani–Nikravesh's
  // chi = 3 (1 - e^2) / 4 ~ 3 (1 - e) / 2 is the same first-order result).
  const double chi = 1e-4;
  CHECK(hunt_crossley_restitution(chi) == doctest::Approx(1.0 - 2.0 * chi / 3.0).epsilon(1e-7));
  CHECK(hunt_crossley_restitution(0.0) == 1.0);
  // Large chi: e -> 1/chi from below (1 - chi e ~ (1 + chi) e^{-chi} is negligible).
  CHECK(hunt_crossley_restitution(1e3) == doctest::Approx(1e-3).epsilon(1e-9));
  // The exact law inverts the relation; the floor applies at e = 0.
  for (double e : {nsb::integrators::kMinLawRestitution, 0.2, 0.5, 0.8, 0.95}) {
    const double c = damping_factor(DampingLaw::kHuntCrossleyExact, e);
    CHECK(hunt_crossley_restitution(c) == doctest::Approx(e).epsilon(1e-9));
  }
  CHECK(damping_factor(DampingLaw::kHuntCrossleyExact, 0.0) ==
        damping_factor(DampingLaw::kHuntCrossleyExact, nsb::integrators::kMinLawRestitution));
  CHECK(damping_factor(DampingLaw::kHertzDamp, 0.0) == doctest::Approx(0.75));
  CHECK(damping_factor(DampingLaw::kFlores, 0.5) == doctest::Approx(1.6));  // 8 * 0.5 / 2.5
  CHECK_THROWS_AS(damping_factor(DampingLaw::kHertzDamp, 1.5), std::invalid_argument);
  CHECK_THROWS_AS(hunt_crossley_restitution(-1.0), std::invalid_argument);
}

TEST_CASE("compliance: damping law names and option validation") {
  using nsb::integrators::parse_damping_law;
  for (const auto& name : nsb::integrators::damping_law_names()) {
    CHECK(nsb::integrators::to_string(parse_damping_law(name)) == name);
  }
  CHECK_THROWS_WITH_AS(parse_damping_law("kelvin"), doctest::Contains("hertzdamp"),
                       std::invalid_argument);
  ComplianceOptions o;
  CHECK_NOTHROW(o.validate());
  auto bad = [](auto mutate, const char* field) {
    ComplianceOptions b;
    mutate(b);
    CHECK_THROWS_WITH_AS(b.validate(), doctest::Contains(field), std::invalid_argument);
  };
  bad([](ComplianceOptions& b) { b.tolerance = 0.0; }, "tolerance");
  bad([](ComplianceOptions& b) { b.stiffness = -1.0; }, "stiffness");
  bad([](ComplianceOptions& b) { b.stiffness = std::nan(""); }, "stiffness");
  bad([](ComplianceOptions& b) { b.stick_slip_velocity = 0.0; }, "stick_slip_velocity");
  bad([](ComplianceOptions& b) { b.max_step = 0.0; }, "max_step");
  bad([](ComplianceOptions& b) { b.min_impact_velocity = -1.0; }, "min_impact_velocity");
  bad([](ComplianceOptions& b) { b.law = static_cast<DampingLaw>(99); }, "law");
  bad([](ComplianceOptions& b) { b.reference_mass = -1.0; }, "reference_mass");
  ts::SpringMass s(against_wall(1.0, 0.0, 0.0, 0.5));
  Recorder rec(s, 0.0);
  o.end_time = 0.0;  // not after the initial time
  CHECK_THROWS_AS(compliance(s, o, rec), std::invalid_argument);
}

TEST_CASE("compliance: a contact's stiffness, its own or the default scaled to its mass") {
  // docs/compliance.md, "A default stiffness that scales with the bridge": k = contact_stiffness
  // * m_c / reference_mass * stiffness_factor where the contact gives no k of its own.
  using nsb::integrators::contact_stiffness;
  ComplianceOptions o;
  o.stiffness = 2.0e7;
  o.stiffness_factor = 3.0;
  o.reference_mass = 100.0;
  ContactData c;
  CHECK(contact_stiffness(o, c) == 6.0e7);  // no mass, no k: the run's, 2e7 * 3
  c.colliding_mass = 250.0;
  CHECK(contact_stiffness(o, c) == doctest::Approx(2.0e7 * 2.5 * 3.0).epsilon(1e-15));
  // At the reference mass the ratio is exactly 1: the run's k to the last bit.
  c.colliding_mass = 100.0;
  CHECK(contact_stiffness(o, c) == o.effective_stiffness());
  // A family's own k wins over the default, scaled by stiffness_factor only.
  c.stiffness = 5.0e6;
  CHECK(contact_stiffness(o, c) == 1.5e7);
  // reference_mass = 0 turns the scaling off.
  c.stiffness = 0.0;
  c.colliding_mass = 250.0;
  o.reference_mass = 0.0;
  CHECK(contact_stiffness(o, c) == 6.0e7);
  // The benchmark's: k0 * 140.5 / 140.5 is k0 exactly, so every shipped benchmark run keeps it.
  ComplianceOptions d;
  c.colliding_mass = 140.5;
  CHECK(contact_stiffness(d, c) == 2.747e7);
}

TEST_CASE("compliance: effective restitution of a wall impact equals the closed form") {
  // Each law's chi(e) gives e_effective = hunt_crossley_restitution(chi) exactly (the
  // closed form of the single impact, independent of k, m, v0): docs/compliance.md.
  for (DampingLaw law : {DampingLaw::kHertzDamp, DampingLaw::kFlores,
                         DampingLaw::kHuntCrossleyExact}) {
    for (double e : {0.0, 0.5, 0.95}) {
      CAPTURE(nsb::integrators::to_string(law));
      CAPTURE(e);
      const double expected =
          nsb::integrators::hunt_crossley_restitution(nsb::integrators::damping_factor(law, e));
      CHECK(wall_restitution(law, e, 1e6) == doctest::Approx(expected).epsilon(
                                                 kRestitutionTolerance).scale(1.0));
    }
  }
  // The exact law reproduces e_set, down to its floor at e = 0.
  CHECK(wall_restitution(DampingLaw::kHuntCrossleyExact, 0.2, 1e6) ==
        doctest::Approx(0.2).epsilon(kRestitutionTolerance));
  CHECK(wall_restitution(DampingLaw::kHuntCrossleyExact, 0.0, 1e6) <=
        nsb::integrators::kMinLawRestitution + kRestitutionTolerance);
}

TEST_CASE("compliance: a free-body impact gives the same restitution for every k, m, v0") {
  // Scaling delta = D s, t = T tau with D = (m v0^2 / k)^(2/5), T = D / v0 removes k, m and
  // v0 from m deltaddot = -k delta^1.5 (1 + chi deltadot / v0).
  const double ref = wall_restitution(DampingLaw::kHertzDamp, 0.5, 1e6);
  for (double k : {1e4, 1e8, 1e10}) {
    CAPTURE(k);
    CHECK(wall_restitution(DampingLaw::kHertzDamp, 0.5, k) ==
          doctest::Approx(ref).epsilon(kRestitutionTolerance));
  }
  CHECK(wall_restitution(DampingLaw::kHertzDamp, 0.5, 1e6, 140.5, 0.3) ==
        doctest::Approx(ref).epsilon(kRestitutionTolerance));
}

TEST_CASE("compliance: undamped Hertz impact duration and peak force (Goldsmith 1960)") {
  // m deltaddot = -k delta^1.5 conserves m v0^2 / 2 = (2/5) k delta^2.5, so
  // delta_max = (5 m v0^2 / (4 k))^(2/5), F_max = k delta_max^1.5, and
  // t_c = 2 int_0^dmax ddelta / (v0 sqrt(1 - (delta/dmax)^2.5)) = 2.94328 delta_max / v0
  // (the integral is (2/5) B(2/5, 1/2) = 1.47164).
  const double m = 2.0, k = 1e7, v0 = 0.8;
  const double dmax = std::pow(5.0 * m * v0 * v0 / (4.0 * k), 0.4);
  const double tc = 2.0 * 0.4 * std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9) * dmax / v0;
  ts::SpringMass s(against_wall(m, 1e-3, -v0, 1.0));  // e = 1: chi = 0 for every law
  ComplianceOptions o;
  o.stiffness = k;
  o.tolerance = kTightTolerance;
  o.max_step = tc / 400.0;  // resolves the force peak in the recorded samples
  o.end_time = 1e-3 / v0 + 1.5 * tc;
  Recorder rec(s, 0.0);
  const RunResult st = compliance(s, o, rec);
  REQUIRE(st.completed);
  REQUIRE(rec.count(EventKind::kClose) == 1);
  REQUIRE(rec.count(EventKind::kOpen) == 1);
  // The episode closes at 0.8 m/s, above min_impact_velocity: an impact, logged at its onset.
  REQUIRE(rec.count(EventKind::kImpact) == 1);
  double t_close = 0, t_open = 0, t_impact = -1;
  for (const auto& ev : rec.events()) {
    if (ev.kind == EventKind::kClose) t_close = ev.t;
    if (ev.kind == EventKind::kOpen) t_open = ev.t;
    if (ev.kind == EventKind::kImpact) t_impact = ev.t;
  }
  CHECK(t_impact == t_close);
  // Event times are located on the step interpolant to ~1e-12 of a step.
  CHECK(t_close == doctest::Approx(1e-3 / v0).epsilon(1e-9));
  CHECK(t_open - t_close == doctest::Approx(tc).epsilon(1e-6));
  double peak = 0.0;
  for (double f : rec.series("lambdaN1")) peak = std::max(peak, f);
  // Sampling at tc/400 misses the peak by at most ~ (pi/400)^2 / 2 relative.
  CHECK(peak == doctest::Approx(k * std::pow(dmax, 1.5)).epsilon(1e-4));
  CHECK(-rec.series("vx").back() == doctest::Approx(-v0).epsilon(1e-7));
  // Elastic contact: the energy balance closes (kinetic <-> contact potential).
  CHECK(st.energy.error < 1e-7);
  CHECK(std::abs(st.energy.impacts) < 1e-9);
}

TEST_CASE("compliance: two free bodies follow the reduced-mass wall result") {
  // Central impact of m1 = 2 (v = +1) on m2 = 1 (v = -0.5), gap 0.01: with
  // e = hunt_crossley_restitution(chi) the post-impact velocities are
  // v1' = v1 - (1 + e) m2 / (m1 + m2) (v1 - v2), v2' = v2 + (1 + e) m1 / (m1 + m2) (v1 - v2).
  ts::TwoMasses s({.mass1 = 2.0, .mass2 = 1.0, .position1 = 0.0, .position2 = 0.01,
                   .velocity1 = 1.0, .velocity2 = -0.5, .restitution = 0.3});
  ComplianceOptions o;
  o.law = DampingLaw::kFlores;
  o.stiffness = 1e7;
  o.tolerance = kTightTolerance;
  o.max_step = 1.0;
  o.end_time = 0.5;
  Recorder rec(s, 0.0);
  REQUIRE(compliance(s, o, rec).completed);
  const double e = nsb::integrators::hunt_crossley_restitution(
      nsb::integrators::damping_factor(DampingLaw::kFlores, 0.3));
  const double vrel = 1.5;
  CHECK(rec.series("v1").back() ==
        doctest::Approx(1.0 - (1 + e) * 1.0 / 3.0 * vrel).epsilon(kRestitutionTolerance));
  CHECK(rec.series("v2").back() ==
        doctest::Approx(-0.5 + (1 + e) * 2.0 / 3.0 * vrel).epsilon(kRestitutionTolerance));
}

TEST_CASE("compliance: a closure is never stepped over, however large max_step") {
  // Free flight from x = 1 at -1 m/s: with nothing acting, the error estimate is zero and
  // the controller would step straight through the wall at x = 0.
  ts::SpringMass s(against_wall(1.0, 1.0, -1.0, 0.5));
  ComplianceOptions o;
  o.law = DampingLaw::kHuntCrossleyExact;
  o.stiffness = 1e8;
  o.max_step = 100.0;
  o.end_time = 3.0;
  Recorder rec(s, 0.0);
  const RunResult st = compliance(s, o, rec);
  REQUIRE(st.completed);
  CHECK(rec.count(EventKind::kClose) == 1);
  CHECK(rec.count(EventKind::kOpen) == 1);
  CHECK(rec.events().front().t == doctest::Approx(1.0).epsilon(1e-9));
  CHECK(rec.series("vx").back() == doctest::Approx(0.5).epsilon(1e-4));
  // The step that crossed the wall was retaken to end at the closure (free flight has no
  // error-control rejections, so every rejected step here is such a retake).
  CHECK(st.rejected_steps >= 1);
  // One commit at the start and one per accepted step.
  CHECK(s.commits == st.steps + 1);
  CHECK(st.factorizations == st.steps + st.rejected_steps);
}

TEST_CASE("compliance: an episode is an impact when it closes faster than min_impact_velocity") {
  // docs/outputs.md, "One event vocabulary": below min_impact_velocity (1e-3 m/s) the law of
  // eq. (9) floors v_minus and treats the closure as a contact from rest ("close" alone);
  // above it the episode is an impact, an "impact" row at the onset before the "close", both
  // carrying the episode's impulse (group impulses).
  for (const double v0 : {0.5e-3, 2e-3}) {
    CAPTURE(v0);
    ts::SpringMass s(against_wall(1.0, 1e-4, -v0, 0.5));
    ComplianceOptions o;
    o.stiffness = 1e7;
    o.tolerance = kTightTolerance;
    // Onset at 1e-4 / v0; the episode lasts 2.94 delta_max / v0 < 0.03 s (Goldsmith, above).
    o.end_time = 1e-4 / v0 + 0.1;
    nsb::integrators::OutputGroups groups;
    groups.add(nsb::integrators::OutputGroup::kImpulses);
    Recorder rec(s, 0.0, groups);
    REQUIRE(compliance(s, o, rec).completed);
    REQUIRE(rec.count(EventKind::kClose) == 1);
    REQUIRE(rec.count(EventKind::kOpen) == 1);
    const bool impact = v0 > o.min_impact_velocity;
    REQUIRE(rec.count(EventKind::kImpact) == (impact ? 1U : 0U));
    const auto& ev = rec.events();
    const std::size_t close = impact ? 1 : 0;
    CHECK(ev[close].kind == EventKind::kClose);
    // The impulse is the momentum the wall gave the body, m (u_end + v0); the trapezoidal
    // rule over the episode's steps (max_step 1e-3 s, some 25 a contact) stands for the
    // integral: measured 7.1e-5 (v0 = 0.5e-3) and 2.0e-5 relative, 2e-4 allowed.
    const double momentum = rec.series("vx").back() + v0;
    CHECK(ev[close].impulse_normal == doctest::Approx(momentum).epsilon(2e-4).scale(0.0));
    if (impact) {
      CHECK(ev[0].kind == EventKind::kImpact);
      CHECK(ev[0].t == ev[close].t);
      CHECK(ev[0].impulse_normal == ev[close].impulse_normal);
    }
  }
}

TEST_CASE("compliance: the gap bound never clears a cubic gap that goes negative") {
  using nsb::integrators::gap_stays_open;
  // Cubic gaps on a step of length h from their end values and rates, over a grid of end data
  // and steps: wherever the bound says "stays open", the cubic is positive at every one of
  // 1001 points of the step.
  int cleared = 0;
  for (double h : {1e-6, 1e-4, 1e-3, 1e-2}) {
    for (double g0 : {1e-7, 1e-5, 1e-4, 1e-3, 1e-2}) {
      for (double g1 : {1e-7, 1e-5, 1e-4, 1e-3, 1e-2}) {
        for (double d0 : {-2.0, -0.1, -1e-3, 0.0, 1e-3, 0.1, 2.0}) {
          for (double d1 : {-2.0, -0.1, -1e-3, 0.0, 1e-3, 0.1, 2.0}) {
            if (!gap_stays_open(g0, d0, g1, d1, h)) continue;
            ++cleared;
            double lowest = std::min(g0, g1);
            for (int j = 0; j <= 1000; ++j) {
              const double s = j / 1000.0;
              const double g = (2 * s * s * s - 3 * s * s + 1) * g0 +
                               (s * s * s - 2 * s * s + s) * h * d0 +
                               (-2 * s * s * s + 3 * s * s) * g1 + (s * s * s - s * s) * h * d1;
              lowest = std::min(lowest, g);
            }
            CHECK(lowest > 0.0);
          }
        }
      }
    }
  }
  CHECK(cleared > 1000);  // the bound clears most open gaps: the probes are rarely needed
  // A gap that closes and reopens within the step, positive at both ends, is not cleared.
  CHECK_FALSE(gap_stays_open(1e-4, -1.0, 1e-4, 1.0, 1e-3));
  // Nor a negative or NaN end.
  CHECK_FALSE(gap_stays_open(-1e-9, 0.0, 1.0, 0.0, 1e-3));
  CHECK_FALSE(gap_stays_open(std::nan(""), 0.0, 1.0, 0.0, 1e-3));
  CHECK(gap_stays_open(1e-2, -0.1, 1e-2, 0.1, 1e-3));
}

TEST_CASE("compliance: contact-free harmonic oscillator matches the closed form") {
  // m = 2, spring 8 kN/m: omega = 2 rad/s, x(t) = 0.1 cos(2 t); a second body 10 m away
  // keeps the gap open, so the run is the smooth integrator alone (with its Jacobian K).
  ComplianceOptions o;
  o.tolerance = 1e-10;
  o.end_time = 2.0;
  o.max_step = 0.05;
  ts::TwoMasses two({.mass1 = 2.0, .mass2 = 1.0, .stiffness1 = 8.0, .position1 = 0.1,
                     .position2 = 10.0});
  Recorder rec(two, 0.0);
  const RunResult st = compliance(two, o, rec);
  REQUIRE(st.completed);
  CHECK(rec.series("x1").back() == doctest::Approx(0.1 * std::cos(4.0)).epsilon(1e-7));
  CHECK(st.energy.error < 1e-8);
  CHECK(rec.count(EventKind::kClose) == 0);
}

TEST_CASE("compliance: a block sliding on a compliant floor stops where Coulomb says") {
  // Block of mass 1 resting on the floor (g_N = y) at its static penetration
  // (m g / k)^(2/3), so that lambda_N = m g from the start, pushed along x at
  // v0 = 1 m/s, mu = 0.4: it decelerates at mu g and stops
  // after t = v0 / (mu g), x = v0^2 / (2 mu g). Below eps_v the regularised law creeps on
  // for ~eps_v / (mu g) s, adding at most eps_v^2 / (mu g) to x.
  ComplianceOptions o;
  o.stiffness = 1e6;
  ts::Block s({.mass = 1.0, .friction = 0.4, .initial_velocity = 1.0,
               .initial_height = -std::pow(9.81 / o.stiffness, 2.0 / 3.0), .restitution = 0.5});
  o.tolerance = 1e-9;
  o.end_time = 0.5;
  Recorder rec(s, 0.0);
  const RunResult st = compliance(s, o, rec);
  REQUIRE(st.completed);
  const double g = 9.81, stop = 1.0 / (0.4 * g), dist = 1.0 / (2 * 0.4 * g);
  const auto t = rec.series("t");
  const auto x = rec.series("x");
  const auto v = rec.series("vx");
  // Time at which |v| first falls below eps_v: the sliding phase ends within eps_v/(mu g).
  double t_stop = -1.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (v[i] < o.stick_slip_velocity) {
      t_stop = t[i];
      break;
    }
  }
  const double creep = o.stick_slip_velocity / (0.4 * g);
  CHECK(t_stop == doctest::Approx(stop).epsilon(2 * creep / stop));
  CHECK(x.back() == doctest::Approx(dist).epsilon(creep * o.stick_slip_velocity / dist + 1e-6));
  CHECK(std::abs(v.back()) < 1e-3 * o.stick_slip_velocity);
  // Friction did the work that removed the sliding kinetic energy.
  CHECK(-st.energy.friction == doctest::Approx(0.5).epsilon(1e-3));
  CHECK(st.energy.error < 1e-4);
}

TEST_CASE("compliance: a moving wall (rheonomic contact) strikes a body at rest") {
  // The wall x_w = V t reaches the body (at rest at x = 0.01) at t = 0.01 / V. In the wall's
  // frame the body approaches at V and leaves at e V, so afterwards u = V (1 + e). The
  // exact law makes e_effective = e_set. The moving wall's work is `ground`.
  const double V = 1.0, e = 0.5, m = 2.0;
  ts::SpringMass s(against_wall(m, 0.01, 0.0, e, V));
  ComplianceOptions o;
  o.law = DampingLaw::kHuntCrossleyExact;
  o.stiffness = 1e7;
  o.tolerance = kTightTolerance;
  o.max_step = 1e-3;
  o.end_time = 0.2;
  Recorder rec(s, 0.0);
  const RunResult st = compliance(s, o, rec);
  REQUIRE(st.completed);
  REQUIRE(rec.count(EventKind::kClose) == 1);
  CHECK(rec.events().front().t == doctest::Approx(0.01 / V).epsilon(1e-9));
  const double u_after = V * (1 + e);
  CHECK(rec.series("vx").back() == doctest::Approx(u_after).epsilon(kRestitutionTolerance));
  // Energy: kinetic gain = work of the wall - dashpot loss; the balance closes.
  CHECK(st.energy.kinetic == doctest::Approx(0.5 * m * u_after * u_after).epsilon(1e-5));
  CHECK(st.energy.ground > st.energy.kinetic);
  CHECK(st.energy.impacts < 0.0);
  CHECK(st.energy.error < 1e-5);
}

TEST_CASE("SmallLu solves bit for bit as Eigen's PartialPivLU") {
  // The Rosenbrock step's LU for n <= 8 must give the very numbers of Eigen's, so that the
  // compliance results do not depend on which of the two solved: random, ill-scaled and
  // pivoting matrices, and a right-hand side with exact zeros (skipped by both).
  std::srand(2017);
  for (int n = 1; n <= nsb::integrators::SmallLu::kMaxSize; ++n) {
    for (int trial = 0; trial < 50; ++trial) {
      CAPTURE(n);
      CAPTURE(trial);
      Matrix a = Matrix::Random(n, n);
      if (trial % 3 == 0) a.row(0) *= 1e-9;                  // forces row exchanges
      if (trial % 5 == 0) a.diagonal().array() += 1e6;       // the stiff I / (gamma h) term
      Vector b = Vector::Random(n);
      if (trial % 2 == 0) b[0] = 0.0;
      nsb::integrators::SmallLu lu;
      lu.compute(a);
      Vector x = b;
      lu.solve_in_place(x);
      const Vector y = Eigen::PartialPivLU<Matrix>(a).solve(b);
      for (int i = 0; i < n; ++i) CHECK(x[i] == y[i]);
    }
  }
}
