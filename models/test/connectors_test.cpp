// The connector laws (models/connectors.hpp): a hand-derived force path for each, and the
// energy balance work = stored + dissipated on a random path.
#include "models/connectors.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <stdexcept>

using nsb::models::connectors::Cable;
using nsb::models::connectors::CableParameters;
using nsb::models::connectors::Law;
using nsb::models::connectors::LawParameters;

namespace {

// The hand values are exact binary-representable sums of products of the parameters up to
// the round-off of a few operations on numbers of order 1..1e3.
constexpr double kHand = 1e-9;
// Hand values quoted to 6 significant figures in the derivation comments.
constexpr double kQuoted = 1e-3;
// Trapezoidal F dD with substeps h = 1e-5 m on piecewise-smooth laws: the error comes from
// the substeps that straddle a kink and from the curvature of the hyperbola, O(h^2 F'').
constexpr double kWork = 1e-4;

}  // namespace

TEST_CASE("restrainer cable: slack, tension, yield, permanent set (hand-derived)") {
  // k = 1000 kN/m, slack s = 0.01 m, F_y = 20 kN (DesRoches & Fenves 2000: tension-only
  // spring with slack, elastic-perfectly plastic in tension).
  Cable c({.stiffness = 1000.0, .slack = 0.01, .yield_force = 20.0});
  // e = 0.005 <= s: slack, F = 0.
  CHECK(c.set_trial(0.005) == 0.0);
  CHECK(c.tangent() == 0.0);
  // e = -0.02 (anchors closer than at rest): F = 0, never compression.
  CHECK(c.set_trial(-0.02) == 0.0);
  // e = 0.02: stretch 0.02 - 0.01 = 0.01, F = 1000 * 0.01 = 10 kN.
  CHECK(c.set_trial(0.02) == doctest::Approx(10.0).epsilon(kHand));
  CHECK(c.tangent() == 1000.0);
  c.commit();
  // e = 0.04: elastic trial 1000 * 0.03 = 30 > F_y: F = 20 kN, permanent elongation
  // e_p = 0.03 - 20 / 1000 = 0.01 m, dissipated F_y e_p = 0.2 kJ, stored 20^2 / 2000 = 0.2 kJ.
  CHECK(c.set_trial(0.04) == doctest::Approx(20.0).epsilon(kHand));
  CHECK(c.tangent() == 0.0);
  CHECK(c.permanent_elongation() == doctest::Approx(0.01).epsilon(kHand));
  CHECK(c.dissipated_energy() == doctest::Approx(0.2).epsilon(kHand));
  CHECK(c.stored_energy() == doctest::Approx(0.2).epsilon(kHand));
  c.commit();
  // e = 0.03: stretch 0.03 - 0.01 - 0.01 = 0.01, F = 10 kN (unloading with k).
  CHECK(c.set_trial(0.03) == doctest::Approx(10.0).epsilon(kHand));
  // e = 0.015 < s + e_p = 0.02: slack again, F = 0.
  CHECK(c.set_trial(0.015) == 0.0);
  // revert() restores the committed state: e_p stays 0.01 (it was committed at e = 0.04).
  c.revert();
  CHECK(c.permanent_elongation() == doctest::Approx(0.01).epsilon(kHand));
  // No yield (F_y = 0): linear beyond the slack at any elongation.
  Cable elastic({.stiffness = 1000.0, .slack = 0.0, .yield_force = 0.0});
  CHECK(elastic.set_trial(1.0) == doctest::Approx(1000.0).epsilon(kHand));
  CHECK_THROWS_AS(CableParameters{.stiffness = 0.0}.validate("r."), std::invalid_argument);
}

TEST_CASE("bilinear bearing: kinematic hardening path (hand-derived)") {
  // k = 1000 kN/m, F_y = 10 kN (d_y = 0.01 m), r = 0.1 (Naeim & Kelly 1999):
  // linear spring r k = 100 kN/m in parallel with an elastic-plastic one of 900 kN/m, 9 kN.
  Law b(LawParameters::bilinear(1000.0, 10.0, 0.1));
  // d = 0.005 < d_y: F = k d = 5 kN.
  CHECK(b.set_trial(0.005) == doctest::Approx(5.0).epsilon(kHand));
  // d = 0.02: on the post-yield branch, F = F_y + r k (d - d_y) = 10 + 100 * 0.01 = 11 kN;
  // slip 0.01 m of the plastic component, dissipated 9 * 0.01 = 0.09 kJ.
  CHECK(b.set_trial(0.02) == doctest::Approx(11.0).epsilon(kHand));
  CHECK(b.tangent() == doctest::Approx(100.0).epsilon(kHand));
  CHECK(b.dissipated_energy() == doctest::Approx(0.09).epsilon(kHand));
  b.commit();
  // d = 0: elastic unloading, F = 11 - 1000 * 0.02 = -9 kN, just on the lower yield line
  // F = r k d - (1 - r) F_y = -9.
  CHECK(b.set_trial(0.0) == doctest::Approx(-9.0).epsilon(kHand));
  CHECK(b.tangent() == 1000.0);
  b.commit();
  // d = -0.01: yields in reverse, F = r k d - (1 - r) F_y = -1 - 9 = -10 kN; slip -0.01 m,
  // dissipated 0.09 + 0.09 = 0.18 kJ; stored r k d^2 / 2 + 9^2 / (2 * 900) = 0.005 + 0.045.
  CHECK(b.set_trial(-0.01) == doctest::Approx(-10.0).epsilon(kHand));
  CHECK(b.dissipated_energy() == doctest::Approx(0.18).epsilon(kHand));
  CHECK(b.stored_energy() == doctest::Approx(0.05).epsilon(kHand));
  // Work by hand: 0.5*10*0.01 + 10.5*0.01 - 1*0.02 + 9.5*0.01 = 0.23 = 0.05 + 0.18 kJ.
  CHECK(b.stored_energy() + b.dissipated_energy() == doctest::Approx(0.23).epsilon(kHand));
  // Linear: F = k d, nothing dissipated.
  Law l(LawParameters::linear(500.0));
  CHECK(l.set_trial(0.1) == doctest::Approx(50.0).epsilon(kHand));
  CHECK(l.dissipated_energy() == 0.0);
}

TEST_CASE("backfill: hyperbolic envelope, unloading to a permanent set, reloading") {
  // OpenSees HyperbolicGapMaterial's recommended values (Wilson & Elgamal, UCSD backwall
  // tests, 1.68 m wall, per metre of width): K_max = K_ur = 20300 kN/m, R_f = 0.7,
  // F_ult = 326 kN; compression for d < 0 (a left abutment: the deck pushes its seat to -x).
  Law f(LawParameters::hyperbolic_gap(20300.0, 326.0, 0.7, 20300.0, -1.0));
  // d = +0.01 (away from the backfill): no force.
  CHECK(f.set_trial(0.01) == 0.0);
  // c = 0.0254 m: F = 0.0254 / (1/20300 + 0.7 * 0.0254 / 326)
  //   = 0.0254 / (4.92611e-5 + 5.45399e-5) = 0.0254 / 1.038010e-4 = 244.699 kN, acting
  //   along -d: the law's force is -244.699.
  CHECK(f.set_trial(-0.0254) == doctest::Approx(-244.699).epsilon(kQuoted / 244.0));
  CHECK(-f.force() == doctest::Approx(0.0254 / (1.0 / 20300.0 + 0.7 * 0.0254 / 326.0))
                          .epsilon(kHand));
  f.commit();
  // Unloading to c = 0.0204: F = 244.699 - 20300 * 0.005 = 143.199 kN.
  CHECK(-f.set_trial(-0.0204) == doctest::Approx(143.199).epsilon(kQuoted / 143.0));
  CHECK(f.tangent() == 20300.0);
  f.commit();
  // c = 0: below the permanent set c_p = 0.0254 - 244.699 / 20300 = 0.0133459 m: F = 0.
  CHECK(f.set_trial(0.0) == 0.0);
  CHECK(f.tangent() == 0.0);
  f.commit();
  // Reloading on the same line: c = 0.0204 gives 143.199 kN again.
  CHECK(-f.set_trial(-0.0204) == doctest::Approx(143.199).epsilon(kQuoted / 143.0));
  // Past c_max on the envelope again: c = 0.03, F = 0.03 / (4.92611e-5 + 6.44172e-5)
  //   = 263.903 kN.
  CHECK(-f.set_trial(-0.03) == doctest::Approx(263.903).epsilon(kQuoted / 263.0));
  // Dissipated after the cycle to c_max = 0.0254: W_env(0.0254) - 244.699^2 / (2 * 20300)
  //   = 3.86575 - 1.47482 = 2.39093 kJ, W_env(c) = c/b - a/b^2 ln(1 + b c / a).
  f.revert();
  CHECK(f.dissipated_energy() == doctest::Approx(2.39093).epsilon(kQuoted / 2.0));
  // The asymptote F_ult / R_f = 465.714 kN is approached, never passed.
  CHECK(f.envelope(10.0) < 326.0 / 0.7);
  CHECK(f.envelope(10.0) > 0.99 * 326.0 / 0.7);
}

TEST_CASE("backfill: the recommended curve at the displacements its sources publish") {
  // No source found tabulates force-displacement points of the hyperbolic backfill curve
  // (docs/bridge.md, "Backfill abutments", lists where we looked). What is published:
  //  - the parameters, per metre of a 1.68 m (5.5 ft) backwall: K_max = 20300 kN/m,
  //    F_ult = 326 kN, R_f = 0.7 (OpenSees HyperbolicGapMaterial, source comments and
  //    command manual), in the source's own units kN and m, so no conversion enters;
  //  - that this curve matches Wilson & Elgamal's test data up to 7.64 cm of displacement
  //    (the same OpenSees comments);
  //  - that the measured passive resistance peaked at 2.7-3 % of the backfill height, i.e.
  //    at 0.04536-0.0504 m of the 1.68 m wall (Wilson & Elgamal 2010, J. Geotech.
  //    Geoenviron. Eng. 136(12), abstract).
  // The forces below are the source's closed form F = y / (1/K_max + R_f y / F_ult) at those
  // displacements, quoted to 0.1 kN; the tolerance is half that last digit, 0.05 kN. The
  // parameters are exact as published (3 significant figures), so the quoting is the only
  // rounding.
  constexpr double kTenth = 0.05;  // [kN]
  const double k_max = 20300.0, f_ult = 326.0, r_f = 0.7, height = 1.68;
  Law f(LawParameters::hyperbolic_gap(k_max, f_ult, r_f, k_max, 1.0));
  // 2.7 % of H: y = 0.04536 m, F = 0.04536 / (4.92611e-5 + 9.73988e-5) = 309.3 kN.
  CHECK(f.envelope(0.027 * height) == doctest::Approx(309.3).epsilon(kTenth / 309.3));
  // 3 % of H: y = 0.0504 m, F = 0.0504 / (4.92611e-5 + 1.08221e-4) = 320.0 kN.
  CHECK(f.envelope(0.03 * height) == doctest::Approx(320.0).epsilon(kTenth / 320.0));
  // The end of the validated range, y = 0.0764 m: F = 0.0764 / (4.92611e-5 + 1.64049e-4)
  //   = 358.2 kN, 1.10 F_ult: with R_f < 1 the hyperbola passes F_ult on its way to the
  //   asymptote F_ult / R_f.
  CHECK(f.envelope(0.0764) == doctest::Approx(358.2).epsilon(kTenth / 358.2));
  // The curve reaches F_ult at y* = F_ult / (K_max (1 - R_f)) = 326 / 6090 = 0.05353 m,
  // 3.19 % of H: just past the measured peak at 2.7-3 % of H, where the curve carries
  // 0.95-0.98 F_ult. The calibrated hyperbola and the test's peak are consistent.
  const double y_star = f_ult / (k_max * (1.0 - r_f));
  CHECK(f.envelope(y_star) == doctest::Approx(f_ult).epsilon(kHand));
  CHECK(y_star / height == doctest::Approx(0.0319).epsilon(0.00005 / 0.0319));
  CHECK(f.envelope(0.027 * height) / f_ult > 0.94);
  CHECK(f.envelope(0.03 * height) / f_ult < 1.0);
  // The law returns the envelope on first loading, with the sign of the backfill's side.
  CHECK(f.set_trial(0.03 * height) == doctest::Approx(320.0).epsilon(kTenth / 320.0));
}

TEST_CASE("connector laws: work = stored + dissipated on a random path") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> step(-4e-3, 4e-3);
  Law laws[] = {Law(LawParameters::bilinear(1000.0, 10.0, 0.1)),
                Law(LawParameters::hyperbolic_gap(20300.0, 326.0, 0.7, 25000.0, 1.0))};
  for (Law& law : laws) {
    double d = 0.0, f = 0.0, work = 0.0;
    for (int i = 0; i < 300; ++i) {
      const double target = d + step(rng);
      const int n = 400;
      const double h = (target - d) / n;
      for (int k = 0; k < n; ++k) {
        const double f_new = law.set_trial(d + h);
        law.commit();
        work += 0.5 * (f + f_new) * h;
        d += h;
        f = f_new;
      }
    }
    CHECK(work == doctest::Approx(law.stored_energy() + law.dissipated_energy()).epsilon(kWork));
  }
  Cable c({.stiffness = 1000.0, .slack = 0.002, .yield_force = 5.0});
  double e = 0.0, f = 0.0, work = 0.0;
  for (int i = 0; i < 300; ++i) {
    const double target = e + step(rng);
    const int n = 400;
    const double h = (target - e) / n;
    for (int k = 0; k < n; ++k) {
      const double f_new = c.set_trial(e + h);
      c.commit();
      work += 0.5 * (f + f_new) * h;
      e += h;
      f = f_new;
    }
  }
  CHECK(work == doctest::Approx(c.stored_energy() + c.dissipated_energy()).epsilon(kWork));
}

TEST_CASE("a law on its committed branch: the branch's line through the committed state") {
  // Bilinear (k = 1000 kN/m, F_y = 10 kN, r = 0.1), committed at d = 0.02 on the post-yield
  // branch with F = 11 kN (the path above). On that branch F = 11 + 100 (d - 0.02): at
  // d = 0.015 (a smaller deformation, which the law itself would take as elastic unloading to
  // 11 - 1000 * 0.005 = 6 kN) the branch gives 11 - 0.5 = 10.5 kN, and at d = 0.03,
  // 11 + 1 = 12 kN, as the law.
  Law b(LawParameters::bilinear(1000.0, 10.0, 0.1));
  b.set_trial(0.02);
  b.commit();
  CHECK(b.force_on_committed_branch(0.015) == doctest::Approx(10.5).epsilon(kHand));
  CHECK(b.force_on_committed_branch(0.03) == doctest::Approx(12.0).epsilon(kHand));
  CHECK(b.set_trial(0.03) == doctest::Approx(12.0).epsilon(kHand));
  // The trial is left as it is: still the last set_trial's.
  b.force_on_committed_branch(0.015);
  CHECK(b.force() == doctest::Approx(12.0).epsilon(kHand));
  CHECK(b.set_trial(0.015) == doctest::Approx(6.0).epsilon(kHand));
  // A cable committed slack stays slack on its branch (tangent 0), whatever the elongation;
  // the line of a taut one goes on below its slack (a linearisation: the law gives 0 there);
  // committed taut at e = 0.02 (F = 10 kN, k = 1000 kN/m, slack 0.01) it is 10 + 1000 (e - 0.02).
  Cable c({.stiffness = 1000.0, .slack = 0.01, .yield_force = 0.0});
  c.set_trial(0.0);
  c.commit();
  CHECK(c.force_on_committed_branch(0.05) == 0.0);
  c.set_trial(0.02);
  c.commit();
  CHECK(c.force_on_committed_branch(0.005) == doctest::Approx(-5.0).epsilon(kHand));
  CHECK(c.force_on_committed_branch(0.03) == doctest::Approx(20.0).epsilon(kHand));
}
