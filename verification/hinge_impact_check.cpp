// Body-body impacts at a hinge between two free decks (models/deck_chain.hpp, the contacts of
// a bridge in segments): eq. (6) of Shi & Dimitrakopoulos 2017 for two bodies, checked three
// ways against the enumeration of its cases (models/analytic.hpp, solve_impact_by_cases, on
// the two-body Delassus matrix G = W^T M^-1 W, M = diag(m_A, m_A, I_A, m_B, m_B, I_B)):
//  (a) every LCP solver (lcp::solve_frictional: Lemke, PGS, Newton-FB, enumeration) on the
//      same problem, one corner or two, straight or skew, over eps and mu;
//  (b) both nonsmooth integrators (Moreau–Jean, event-driven) from the touching configuration:
//      the velocities after the impact, and the total linear momentum, which the internal
//      impulses conserve to round-off;
//  (c) the hinge rotation criterion of docs/criterion.md ("Impacts at a hinge"): neither deck
//      rotates iff the ratio k = P_T / P_N of the non-rotating motion equals tan(alpha).
#include "integrators/event_driven.hpp"
#include "integrators/moreau_jean.hpp"
#include "lcp/frictional.hpp"
#include "models/analytic.hpp"
#include "models/deck_chain.hpp"
#include "models/parts.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace {

namespace ni = nsb::integrators;
namespace nm = nsb::models;
namespace an = nsb::models::analytic;
namespace lcp = nsb::lcp;
constexpr double kPi = std::numbers::pi;

// Agreement of post-impact velocities with the enumeration: both exact up to the solvers'
// residual (1e-12) times the conditioning of G (the inertia terms: ~1e3 here), as in
// verification/criterion_check.cpp.
constexpr double kVelocityAgreement = 1e-8;
// Linear momentum: the impulses are equal and opposite on the two decks, so only the
// round-off of the velocity updates remains (relative to sum m |v|).
constexpr double kRoundOff = 1e-12;
// |omega+| L / |v-| above this is a rotation (criterion_check.cpp's threshold).
constexpr double kRotating = 1e-9;

// Two decks touching at the hinge (gap 0), abutments 3 m away: the hinge contacts are the
// assembly's contacts 2 and 3 (models/deck_chain.hpp order). theta_b turns deck B about its
// centre, which is then moved along x until its first corner touches: one corner strikes.
struct Pair {
  nm::DeckChain::Parameters p;
  double theta_b = 0.0;
};

nm::Assembly::Parts pair_parts(const Pair& pair, const Eigen::Vector3d& ua,
                               const Eigen::Vector3d& ub) {
  nm::DeckChain::Parameters p = pair.p;
  p.decks[0].initial_velocity = ua;
  p.decks[1].initial_velocity = ub;
  nm::Assembly::Parts parts = nm::DeckChain::parts(p);
  if (pair.theta_b != 0.0) {
    // B is moved along the outward normal n of A's right face, so that its corners keep their
    // place along A's face (the joint's transverse offset stays zero). A step ds changes the
    // gap of B's corner on A's face by ds and that of A's corner on B's face (normal
    // -R(theta_b) n) by cos(theta_b) ds: moving B by the smallest gap of the two sides
    // (the assembly's inner pairs) never penetrates and leaves at most (1 - cos theta_b) of
    // it, 2e-6 here, so four steps from 1 m close the gap to round-off.
    parts.bodies[1].initial_position.z() = pair.theta_b;
    const Eigen::Vector2d n = nm::parts::end_face(parts.bodies[0], nm::parts::End::kRight).normal;
    parts.bodies[1].initial_position.head<2>() += n;  // far from A while measuring
    for (int step = 0; step < 4; ++step) {
      nm::Assembly m(parts);
      std::vector<ni::ContactData> c;
      m.contact_data(0.0, m.initial_position(), m.initial_velocity(), c);
      parts.bodies[1].initial_position.head<2>() -= std::min(c[2].gap_normal, c[3].gap_normal) * n;
    }
  }
  return parts;
}

struct TwoBodyImpact {
  an::ImpactProblem problem;
  Eigen::MatrixXd w;          // 6 x 2m: normals then tangents
  Eigen::VectorXd minv;       // diag of M^-1
  Eigen::VectorXd u;          // u-
  std::vector<int> active;    // assembly contact indices of the striking corners
};

// The eq. (6) problem of the hinge corners touching (g_N <= 1e-12 m) at t = 0.
TwoBodyImpact impact_problem(nm::Assembly& a) {
  std::vector<ni::ContactData> c;
  a.contact_data(0.0, a.initial_position(), a.initial_velocity(), c);
  TwoBodyImpact out;
  for (int i : {2, 3}) {
    if (std::abs(c[static_cast<std::size_t>(i)].gap_normal) <= 1e-12) out.active.push_back(i);
  }
  const auto m = static_cast<Eigen::Index>(out.active.size());
  out.w.resize(6, 2 * m);
  for (Eigen::Index k = 0; k < m; ++k) {
    const auto& ck = c[static_cast<std::size_t>(out.active[static_cast<std::size_t>(k)])];
    out.w.col(k) = ck.w_normal;
    out.w.col(m + k) = ck.w_tangent;
  }
  out.minv = a.mass().diagonal().cwiseInverse();
  out.u = a.initial_velocity();
  out.problem.delassus = out.w.transpose() * out.minv.asDiagonal() * out.w;
  out.problem.gdot_minus = out.w.transpose() * out.u;
  out.problem.restitution = Eigen::VectorXd::Constant(m, c[2].restitution);
  out.problem.friction = Eigen::VectorXd::Constant(m, c[2].friction);
  return out;
}

Eigen::VectorXd after(const TwoBodyImpact& t, const Eigen::VectorXd& ln,
                      const Eigen::VectorXd& lt) {
  Eigen::VectorXd z(ln.size() + lt.size());
  z << ln, lt;
  return t.u + t.minv.asDiagonal() * (t.w * z);
}

Eigen::Vector2d momentum(const nm::DeckChain::Parameters& p, const Eigen::VectorXd& u) {
  return p.decks[0].mass * u.segment<2>(0) + p.decks[1].mass * u.segment<2>(3);
}

Pair make_pair(double skew, double e, double mu, double theta_b) {
  Pair pair;
  pair.p.width = 2.44;
  pair.p.skew_deg = skew;
  pair.p.decks = {{.mass = 70.25, .inertia = 1636.25, .length = 16.75},
                  {.mass = 95.0, .inertia = 3100.0, .length = 20.5}};
  pair.p.joints = {{.gap = 3.0}, {.gap = 0.0, .restitution = e, .friction = mu}, {.gap = 3.0}};
  pair.theta_b = theta_b;
  return pair;
}

// Velocities right after the impact at t = 0: Moreau–Jean's first step (h = 1e-6 s), the
// event-driven state at 1e-9 s. Later, a contact that stays closed after an impact with
// e = 0 carries a force (the curvature terms of the rotating pair, wbar_N), which changes u
// by ~1e-8 |u| within 1e-6 s: not the impact law.
Eigen::VectorXd integrate(nm::Assembly& a, bool moreau) {
  ni::Recorder rec(a, 0.0);
  ni::RunResult r;
  if (moreau) {
    ni::MoreauJeanOptions o;
    o.step = 1e-6;
    o.end_time = 1e-6;
    r = ni::moreau_jean(a, o, rec);
  } else {
    ni::EventDrivenOptions o;
    o.end_time = 1e-9;
    o.tolerance = 1e-12;
    r = ni::event_driven(a, o, rec);
  }
  REQUIRE(r.completed);
  const std::size_t last = rec.rows() - 1;
  Eigen::VectorXd u(6);
  int k = 0;
  for (const auto& name : a.velocity_names()) u(k++) = rec.at(last, rec.column(name));
  return u;
}

}  // namespace

TEST_CASE("hinge impacts: every LCP solver and both integrators agree with the enumeration") {
  int problems = 0, one_corner = 0;
  int solved[4] = {0, 0, 0, 0};
  double worst_solver = 0.0, worst_integrator = 0.0, worst_momentum = 0.0;
  const lcp::Solver solvers[4] = {lcp::Solver::kLemke, lcp::Solver::kPgs, lcp::Solver::kNewtonFb,
                                  lcp::Solver::kEnumeration};
  for (double skew : {0.0, 15.0, 30.0, -40.0}) {
    for (double e : {0.0, 0.5, 1.0}) {
      for (double mu : {0.0, 0.3, 0.8}) {
        for (double theta_b : {0.0, 2e-3}) {
          for (double vy : {0.0, 0.4, -1.2}) {
            const Pair pair = make_pair(skew, e, mu, theta_b);
            const Eigen::Vector3d ua(1.0, vy, 0.0), ub(-0.2, 0.0, 0.0);
            nm::Assembly a(pair_parts(pair, ua, ub));
            const TwoBodyImpact t = impact_problem(a);
            CAPTURE(skew);
            CAPTURE(e);
            CAPTURE(mu);
            CAPTURE(theta_b);
            CAPTURE(vy);
            REQUIRE(!t.active.empty());
            if (t.problem.gdot_minus.head(static_cast<Eigen::Index>(t.active.size())).maxCoeff() >=
                -1e-3) {
              continue;  // a corner not approaching: not a two-corner impact of this grid
            }
            one_corner += t.active.size() == 1;
            const auto cases = an::solve_impact_by_cases(t.problem);
            REQUIRE(cases.unique());
            const auto& sol = cases.solutions[0];
            const Eigen::VectorXd oracle = after(t, sol.lambda_n, sol.lambda_t);
            const double scale = t.u.norm();
            for (int s = 0; s < 4; ++s) {
              lcp::FrictionalProblem fp;
              fp.delassus = t.problem.delassus;
              fp.gdot_free = t.problem.gdot_minus;
              fp.gdot_n_minus = t.problem.gdot_minus.head(t.problem.restitution.size());
              fp.restitution = t.problem.restitution;
              fp.friction = t.problem.friction;
              const auto r = lcp::solve_frictional(fp, solvers[s]);
              if (!r.ok()) continue;
              ++solved[s];
              const double d = (after(t, r.lambda_n, r.lambda_t) - oracle).cwiseAbs().maxCoeff();
              worst_solver = std::max(worst_solver, d / scale);
              CHECK(d <= kVelocityAgreement * scale);
            }
            for (bool moreau : {true, false}) {
              CAPTURE(moreau);
              nm::Assembly run(pair_parts(pair, ua, ub));
              const Eigen::VectorXd u = integrate(run, moreau);
              const double d = (u - oracle).cwiseAbs().maxCoeff();
              worst_integrator = std::max(worst_integrator, d / scale);
              CHECK(d <= kVelocityAgreement * scale);
              const double pscale = pair.p.decks[0].mass * ua.norm() +
                                    pair.p.decks[1].mass * ub.norm();
              const double dp = (momentum(pair.p, u) - momentum(pair.p, t.u)).norm();
              worst_momentum = std::max(worst_momentum, dp / pscale);
              CHECK(dp <= kRoundOff * pscale);
            }
            ++problems;
          }
        }
      }
    }
  }
  MESSAGE(problems, " hinge impacts (", one_corner, " of one corner); solved: lemke ", solved[0],
          ", pgs ", solved[1], ", nfb ", solved[2], ", enum ", solved[3],
          "; worst |u+ - u+_enum| / |u-|: solvers ", worst_solver, ", integrators ",
          worst_integrator, "; worst momentum change / sum m|v|: ", worst_momentum);
  CHECK(problems > 100);
  CHECK(one_corner > 30);
  CHECK(solved[0] == problems);
  CHECK(solved[3] == problems);
}

// docs/criterion.md, "Impacts at a hinge": both decks at theta = 0, omega- = 0, both corners
// striking. Without rotation after the impact, momentum gives P_N = -m* (1 + e) gdot_N-, and
// P_T = -m* gdot_T- (stick, |k| <= mu) or P_T = -sgn(gdot_T-) mu P_N (slide), k = P_T / P_N;
// the angular momentum of the two decks then needs (L_A + L_B) (k cos(a) - sin(a)) = 0.
TEST_CASE("hinge criterion: neither deck rotates iff k = tan(alpha)") {
  int checked = 0, still = 0;
  for (double skew : {0.0, 10.0, 30.0, 45.0, -25.0}) {
    for (double e : {0.0, 0.4, 1.0}) {
      for (double mu : {0.0, 0.2, 0.6, 1.2}) {
        for (double vy : {0.0, 0.3, -0.8}) {
          const Pair pair = make_pair(skew, e, mu, 0.0);
          const Eigen::Vector3d ua(1.0, vy, 0.0), ub(0.0, 0.0, 0.0);
          nm::Assembly a(pair_parts(pair, ua, ub));
          const TwoBodyImpact t = impact_problem(a);
          REQUIRE(t.active.size() == 2);
          const double gn = t.problem.gdot_minus(0), gt = t.problem.gdot_minus(2);
          if (gn >= -1e-3) continue;
          const double stick = gt / ((1.0 + e) * gn);
          const double k = std::abs(stick) <= mu ? stick : -std::copysign(mu, gt);
          const double a_rad = skew * kPi / 180.0;
          const bool predicted = std::abs(k - std::tan(a_rad)) > 1e-9;
          const auto cases = an::solve_impact_by_cases(t.problem);
          REQUIRE(cases.unique());
          const Eigen::VectorXd u = after(t, cases.solutions[0].lambda_n,
                                          cases.solutions[0].lambda_t);
          const bool rot = std::max(std::abs(u(2)) * 16.75, std::abs(u(5)) * 20.5) >
                           kRotating * t.u.norm();
          CAPTURE(skew);
          CAPTURE(e);
          CAPTURE(mu);
          CAPTURE(vy);
          CAPTURE(k);
          CHECK(rot == predicted);
          // Moreau–Jean's impact step agrees (it solves the same eq. (6)).
          nm::Assembly run(pair_parts(pair, ua, ub));
          const Eigen::VectorXd um = integrate(run, true);
          CHECK((std::max(std::abs(um(2)) * 16.75, std::abs(um(5)) * 20.5) >
                 kRotating * t.u.norm()) == predicted);
          ++checked;
          still += !rot;
        }
      }
    }
  }
  MESSAGE(checked, " two-corner hinge impacts, ", still, " without rotation (k = tan alpha)");
  CHECK(still > 5);
  CHECK(checked - still > 50);
}
