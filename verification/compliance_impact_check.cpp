// The compliance method on single central impacts of two free bodies: the effective
// restitution of each damping law for e_set in {0, 0.2, 0.5, 0.8, 0.95} (the table of
// docs/compliance.md), its independence of k and of the masses, and the undamped Hertz
// impact against Goldsmith's closed form at the bridge's scale.
#include "integrators/compliance.hpp"
#include "testsupport/systems.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <vector>

namespace {

using nsb::integrators::compliance;
using nsb::integrators::ComplianceOptions;
using nsb::integrators::ContactData;
using nsb::integrators::DampingLaw;
using nsb::integrators::EventKind;
using nsb::integrators::Matrix;
using nsb::integrators::Recorder;
using nsb::integrators::Vector;

// Two free point masses on a line, x_1 < x_2, one contact g_N = x_2 - x_1 (touching at
// the start is avoided by a small initial gap). No other forces.
constexpr double kInitialGap = 1e-3;  // [m]
nsb::testsupport::TwoMasses two_bodies(double m1, double m2, double v1, double v2, double e) {
  return nsb::testsupport::TwoMasses({.mass1 = m1, .mass2 = m2, .position1 = 0.0,
                                      .position2 = kInitialGap, .velocity1 = v1,
                                      .velocity2 = v2, .restitution = e});
}

// The bridge's deck mass against an equal body; default Hertz k of the scene.
constexpr double kDeckMass = 140.5;         // [t], paper §3
constexpr double kBaseStiffness = 2.747e7;  // [kN/m^1.5], Muthukumar & DesRoches 2006
constexpr double kTolerance = 1e-11;        // integration tolerance of these runs
// e_effective against the closed form: integration and root-bisection error.
constexpr double kRestitutionTolerance = 1e-5;

// The restitution values of the table and the stiffness factors of the k-independence study.
const std::vector<double> kRestitutions{0.0, 0.2, 0.5, 0.8, 0.95};
const std::vector<double> kFactors{1e-4, 1e-2, 1.0, 1e2};

struct Impact {
  double e_effective = 0.0;
  double duration = 0.0;       // close -> open [s]
  double peak_force = 0.0;     // [kN]
  double max_penetration = 0.0;  // [m]
  long steps = 0;
};

Impact central_impact(DampingLaw law, double e, double k, double m1 = kDeckMass,
                      double m2 = kDeckMass, double v1 = 0.2, double v2 = -0.1,
                      double max_step = 1.0, double end_time = 0.0) {
  auto s = two_bodies(m1, m2, v1, v2, e);
  ComplianceOptions o;
  o.law = law;
  o.stiffness = k;
  o.tolerance = kTolerance;
  o.max_step = max_step;
  // Long enough for the slowest separation (hunt_crossley_exact at its e floor separates at
  // ~1e-3 of the approach speed from a penetration of (5 m v^2 / 4 k)^(2/5)).
  const double dmax = std::pow(5.0 * (m1 * m2 / (m1 + m2)) * (v1 - v2) * (v1 - v2) / (4.0 * k), 0.4);
  o.end_time = end_time > 0.0
                   ? end_time
                   : kInitialGap / (v1 - v2) + 5.0 * dmax / (1e-3 * (v1 - v2)) + 1.0;
  Recorder rec(s, 0.0);
  const auto st = compliance(s, o, rec);
  REQUIRE(st.completed);
  REQUIRE(rec.count(EventKind::kOpen) == 1);
  Impact r;
  const double rel_after = rec.series("v2").back() - rec.series("v1").back();
  r.e_effective = rel_after / (v1 - v2);
  double t_close = 0, t_open = 0;
  for (const auto& ev : rec.events()) {
    if (ev.kind == EventKind::kClose) t_close = ev.t;
    if (ev.kind == EventKind::kOpen) t_open = ev.t;
  }
  r.duration = t_open - t_close;
  for (double f : rec.series("lambdaN1")) r.peak_force = std::max(r.peak_force, f);
  for (double g : rec.series("gN1")) r.max_penetration = std::max(r.max_penetration, -g);
  r.steps = st.steps;
  return r;
}

}  // namespace

TEST_CASE("compliance: effective restitution of each damping law (two free bodies)") {
  const DampingLaw laws[] = {DampingLaw::kHertzDamp, DampingLaw::kFlores,
                             DampingLaw::kHuntCrossleyExact};
  std::printf("# e_effective, central impact of two %.1f t bodies, k = %.4g kN/m^1.5\n",
              kDeckMass, kBaseStiffness);
  std::printf("%-8s %-22s %-10s %-12s %-12s\n", "e_set", "law", "chi", "e_effective",
              "closed_form");
  for (double e : kRestitutions) {
    for (DampingLaw law : laws) {
      CAPTURE(e);
      CAPTURE(nsb::integrators::to_string(law));
      const double chi = nsb::integrators::damping_factor(law, e);
      const double closed = nsb::integrators::hunt_crossley_restitution(chi);
      const Impact r = central_impact(law, e, kBaseStiffness);
      std::printf("%-8.2f %-22s %-10.4g %-12.6f %-12.6f %8ld\n", e,
                  std::string(nsb::integrators::to_string(law)).c_str(), chi, r.e_effective,
                  closed, r.steps);
      // Measured against the closed form derived in docs/compliance.md.
      CHECK(r.e_effective == doctest::Approx(closed).epsilon(kRestitutionTolerance).scale(1.0));
      if (law == DampingLaw::kHuntCrossleyExact) {
        // The exact law reproduces e_set; at e_set = 0 its floor.
        CHECK(r.e_effective == doctest::Approx(std::max(e, nsb::integrators::kMinLawRestitution))
                                   .epsilon(kRestitutionTolerance)
                                   .scale(1.0));
      }
    }
  }
  // Lankarani–Nikravesh at the paper's e = 0: e_effective = 0.663 (docs/compliance.md), far
  // from a plastic impact.
  CHECK(central_impact(DampingLaw::kHertzDamp, 0.0, kBaseStiffness).e_effective ==
        doctest::Approx(0.66296).epsilon(1e-4));
}

TEST_CASE("compliance: post-impact velocities do not depend on k or on the masses") {
  // delta = D s, t = (D / v) tau with D = (m v^2 / k)^(2/5) scales k, the reduced mass m and
  // v out of m deltaddot = -k delta^1.5 (1 + chi deltadot / v).
  for (DampingLaw law : {DampingLaw::kHertzDamp, DampingLaw::kHuntCrossleyExact}) {
    const double ref = central_impact(law, 0.5, kBaseStiffness).e_effective;
    std::printf("# %s, e_set = 0.5: e_effective by stiffness factor\n",
                std::string(nsb::integrators::to_string(law)).c_str());
    for (double factor : kFactors) {
      const double e = central_impact(law, 0.5, factor * kBaseStiffness).e_effective;
      std::printf("  k = %8.0e k0: e_effective = %.8f\n", factor, e);
      CHECK(e == doctest::Approx(ref).epsilon(kRestitutionTolerance));
    }
    CHECK(central_impact(law, 0.5, kBaseStiffness, 140.5, 20.0, 0.3, 0.0).e_effective ==
          doctest::Approx(ref).epsilon(kRestitutionTolerance));
  }
}

TEST_CASE("compliance: undamped Hertz impact of the deck mass against Goldsmith (1960)") {
  // Reduced mass m = m1 m2 / (m1 + m2), approach speed v0: delta_max = (5 m v0^2 / 4 k)^(2/5),
  // F_max = k delta_max^1.5, t_c = 2.94328 delta_max / v0 = 3.2181 (m^2 / (k^2 v0))^(1/5)
  // (docs/compliance.md; 2.94328 = 2 (2/5) B(2/5, 1/2)).
  const double m = 0.5 * kDeckMass, v0 = 0.3, k = kBaseStiffness;
  const double dmax = std::pow(5.0 * m * v0 * v0 / (4.0 * k), 0.4);
  const double tc = 2.94328 * dmax / v0;
  // Sampled every tc / 400 until half a contact time after the separation.
  const Impact r = central_impact(DampingLaw::kHertzDamp, 1.0, k, kDeckMass, kDeckMass, 0.2,
                                  -0.1, tc / 400.0, kInitialGap / v0 + 1.5 * tc);
  std::printf("# undamped Hertz: t_c = %.6e s (closed form %.6e), F_max = %.6e kN (%.6e), "
              "delta_max = %.6e m (%.6e)\n",
              r.duration, tc, r.peak_force, k * std::pow(dmax, 1.5), r.max_penetration, dmax);
  CHECK(r.duration == doctest::Approx(tc).epsilon(1e-5));
  CHECK(r.peak_force == doctest::Approx(k * std::pow(dmax, 1.5)).epsilon(1e-4));
  CHECK(r.max_penetration == doctest::Approx(dmax).epsilon(1e-4));
  CHECK(r.e_effective == doctest::Approx(1.0).epsilon(1e-6));
}
