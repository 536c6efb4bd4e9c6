// The compliance method on a free deck striking the right abutment at one corner (corner 3),
// against the nonsmooth impact law of eq. (6) solved exactly by cases
// (models/analytic.hpp: deck_impact) with eps = the law's effective restitution.
#include "integrators/compliance.hpp"
#include "models/analytic.hpp"
#include "models/bridge_parts.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>

namespace {

using nsb::integrators::compliance;
using nsb::integrators::ComplianceOptions;
using nsb::integrators::DampingLaw;
using nsb::integrators::EventKind;
using nsb::integrators::Recorder;

// The benchmark deck (paper §3; L, W assumed in docs/bridge.md), skewed so that the
// single-corner impact couples all three velocities.
constexpr double kMass = 140.5, kInertia = 13090.0, kLength = 33.35, kWidth = 2.44;
constexpr double kSkewDeg = 20.0;
constexpr double kBaseStiffness = 2.747e7;  // [kN/m^1.5]
// Compliance against eq. (6) with mu = 0: the requirement is 1 %; what remains is the
// rotation of W_N during the finite contact, of order omega t_c ~ 1e-3.
constexpr double kFrictionlessTolerance = 0.01;

nsb::models::analytic::DeckBody analytic_geometry() {
  nsb::models::analytic::DeckBody g;
  g.mass = kMass;
  g.inertia = kInertia;
  g.deck = {.length = kLength, .width = kWidth, .skew_deg = kSkewDeg};
  return g;
}

// A pre-impact velocity with corner 3 closing at 0.25 m/s and corner 4 opening at 0.05 m/s.
Eigen::Vector3d pre_impact_velocity() {
  const auto g = analytic_geometry();
  const Eigen::Vector3d w3 = nsb::models::analytic::deck_contact_columns(g.deck, 3).w_normal;
  const Eigen::Vector3d w4 = nsb::models::analytic::deck_contact_columns(g.deck, 4).w_normal;
  // Solve w3 . u = -0.25, w4 . u = +0.05 with vy = 0.02 for (vx, omega).
  const double vy = 0.02;
  Eigen::Matrix2d A;
  A << w3[0], w3[2], w4[0], w4[2];
  const Eigen::Vector2d b(-0.25 - w3[1] * vy, 0.05 - w4[1] * vy);
  const Eigen::Vector2d s = A.partialPivLu().solve(b);
  return {s[0], vy, s[1]};
}

struct Outcome {
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  double duration = 0.0;
};

// Runs the deck from touching (gap 0 at corners 3 and 4) until corner 3 opens, and returns
// the velocity right after: the deck is free once every contact is open.
Outcome compliance_impact(DampingLaw law, double e, double mu, double k) {
  nsb::models::BridgeDesign p = nsb::models::BridgeDesign::free_deck();
  p.mass = kMass;
  p.inertia = kInertia;
  p.deck = {.length = kLength, .width = kWidth, .skew_deg = kSkewDeg, .gap_right = 0.0,
            .gap_left = 5.0};
  p.restitution = e;
  p.friction = mu;
  p.initial_velocity = pre_impact_velocity();
  nsb::models::Assembly deck(nsb::models::bridge_parts(p));
  ComplianceOptions o;
  o.law = law;
  o.stiffness = k;
  o.tolerance = 1e-10;
  o.end_time = 0.5;
  Recorder rec(deck, 0.0);
  const auto st = compliance(deck, o, rec);
  REQUIRE(st.completed);
  double t_open = -1.0;
  for (const auto& ev : rec.events()) {
    if (ev.contact == 3 && ev.kind == EventKind::kOpen) {
      t_open = ev.t;
      break;
    }
  }
  REQUIRE(t_open > 0.0);
  // No other closure after the start.
  for (const auto& ev : rec.events()) {
    if (ev.kind == EventKind::kClose) CHECK(ev.t == 0.0);
  }
  Outcome r;
  const auto t = rec.series("t");
  const auto vx = rec.series("vx"), vy = rec.series("vy"), om = rec.series("omega");
  const std::size_t last = t.size() - 1;
  r.velocity = {vx[last], vy[last], om[last]};
  r.duration = t_open;
  return r;
}

}  // namespace

TEST_CASE("compliance: frictionless free-deck corner impact equals eq. (6) with e_effective") {
  const auto g = analytic_geometry();
  const Eigen::Vector3d u_minus = pre_impact_velocity();
  std::printf("# free deck, corner 3, skew %.0f deg, u- = (%.5f, %.5f, %.6f)\n", kSkewDeg,
              u_minus[0], u_minus[1], u_minus[2]);
  struct Case {
    DampingLaw law;
    double e;
  };
  for (const Case c : {Case{DampingLaw::kHertzDamp, 0.0}, Case{DampingLaw::kHertzDamp, 0.8},
                       Case{DampingLaw::kHuntCrossleyExact, 0.2},
                       Case{DampingLaw::kHuntCrossleyExact, 0.5},
                       Case{DampingLaw::kFlores, 0.5}}) {
    const double e_eff = nsb::integrators::hunt_crossley_restitution(
        nsb::integrators::damping_factor(c.law, c.e));
    const auto ref = nsb::models::analytic::deck_impact(g, {3}, u_minus, e_eff, 0.0);
    REQUIRE(ref.solutions == 1);
    const Outcome out = compliance_impact(c.law, c.e, 0.0, kBaseStiffness);
    const double err = (out.velocity - ref.velocity_after).norm() / ref.velocity_after.norm();
    std::printf("%-20s e_set %.2f e_eff %.4f  u+ compliance (%.6f, %.6f, %.7f)  eq.6 (%.6f, "
                "%.6f, %.7f)  rel. diff %.2e  t_c %.4f s\n",
                std::string(nsb::integrators::to_string(c.law)).c_str(), c.e, e_eff,
                out.velocity[0], out.velocity[1], out.velocity[2], ref.velocity_after[0],
                ref.velocity_after[1], ref.velocity_after[2], err, out.duration);
    CAPTURE(c.e);
    CHECK(err < kFrictionlessTolerance);
    for (int i = 0; i < 3; ++i) {
      CHECK(out.velocity[i] == doctest::Approx(ref.velocity_after[i])
                                   .epsilon(kFrictionlessTolerance)
                                   .scale(1e-2 * ref.velocity_after.norm()));
    }
  }
}

TEST_CASE("compliance: frictional free-deck corner impact against eq. (6)") {
  // With mu = 0.5 the two models differ in kind: the regularised friction of eq. (10) acts
  // through compression and restitution with the instantaneous slip direction, whereas
  // eq. (6) couples a single impulse to Newton's law on the normal velocity only. The
  // difference is reported (docs/compliance.md), and bounded here only by what both models
  // must share: the same normal impulse direction and a dissipative outcome.
  const auto g = analytic_geometry();
  const Eigen::Vector3d u_minus = pre_impact_velocity();
  const Eigen::Vector3d w3 = nsb::models::analytic::deck_contact_columns(g.deck, 3).w_normal;
  const Eigen::Vector3d wt3 = nsb::models::analytic::deck_contact_columns(g.deck, 3).w_tangent;
  const Eigen::Vector3d m_diag(kMass, kMass, kInertia);
  const auto kinetic = [&](const Eigen::Vector3d& u) {
    return 0.5 * u.dot(m_diag.cwiseProduct(u));
  };
  for (double e : {0.2, 0.5}) {
    const double e_eff = nsb::integrators::hunt_crossley_restitution(
        nsb::integrators::damping_factor(DampingLaw::kHuntCrossleyExact, e));
    const auto ref = nsb::models::analytic::deck_impact(g, {3}, u_minus, e_eff, 0.5);
    const Outcome out = compliance_impact(DampingLaw::kHuntCrossleyExact, e, 0.5, kBaseStiffness);
    const double err = (out.velocity - ref.velocity_after).norm() / ref.velocity_after.norm();
    std::printf("mu = 0.5, e_set %.2f: u+ compliance (%.6f, %.6f, %.7f) eq.6 (%.6f, %.6f, "
                "%.7f) rel. diff %.3f; gdot_N+ %.5f vs %.5f; gdot_T+ %.5f vs %.5f (gdot_T- "
                "%.5f)\n",
                e, out.velocity[0], out.velocity[1], out.velocity[2], ref.velocity_after[0],
                ref.velocity_after[1], ref.velocity_after[2], err, w3.dot(out.velocity),
                w3.dot(ref.velocity_after), wt3.dot(out.velocity), wt3.dot(ref.velocity_after),
                wt3.dot(u_minus));
    CHECK(kinetic(out.velocity) < kinetic(u_minus));
    CHECK(w3.dot(out.velocity) > 0.0);  // separating
    // Friction reduces the slip magnitude in both models.
    CHECK(std::abs(wt3.dot(out.velocity)) <= std::abs(wt3.dot(u_minus)));
  }
}
