// Moreau–Jean on a free rigid deck (models/bridge_parts.hpp) striking its right abutment: the
// post-impact velocities of the impact step against the analytic impact solution
// (models/analytic.hpp, case enumeration of eqs. 3-7) and against the eq. (6) LCP solved
// directly with the LCP module. With no smooth forces the iteration matrix is M and the step's
// contact problem is exactly the impact problem, so the agreement is to round-off.
#include "integrators/moreau_jean.hpp"
#include "lcp/frictional.hpp"
#include "models/analytic.hpp"
#include "models/bridge_parts.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

namespace nsb {
namespace {

using integrators::Recorder;
using integrators::Vector;

// Agreement of two exact solutions of the same problem: Lemke's pivots and the case
// enumeration's linear solves differ only by round-off on O(1) data.
constexpr double kExact = 1e-9;

models::BridgeDesign deck(double skew_deg, double mu, const Eigen::Vector3d& q0,
                                   const Eigen::Vector3d& u0) {
  models::BridgeDesign p = models::BridgeDesign::free_deck();
  p.mass = 140.5;
  p.inertia = 13090.0;
  p.deck = {.length = 33.35, .width = 2.44, .skew_deg = skew_deg, .gap_right = 0.01,
            .gap_left = 1.0};  // far: only the right abutment is struck
  p.restitution = 0.3;
  p.friction = mu;
  p.initial_position = q0;
  p.initial_velocity = u0;
  return p;
}

struct ImpactStep {
  Eigen::Vector3d before, after;
  std::vector<int> corners;  // 1-based corners in the impact step's index set
  std::vector<int> struck;   // those with a normal impulse
  std::vector<integrators::ContactData> contacts;  // at the start of the impact step
  Eigen::Vector3d q_before;
};

// Runs until the first step with a contact impulse and returns the velocities around it.
ImpactStep first_impact(const models::BridgeDesign& p, double h) {
  models::Assembly s(models::bridge_parts(p));
  Recorder rec(s, 0.0);
  integrators::MoreauJeanOptions o;
  o.step = h;
  o.end_time = 0.2;
  integrators::moreau_jean(s, o, rec);
  ImpactStep out;
  for (std::size_t r = 1; r < rec.rows(); ++r) {
    for (int c = 1; c <= 4; ++c) {
      if (rec.at(r, rec.column("lambdaN" + std::to_string(c))) > 0.0) out.corners.push_back(c);
    }
    if (out.corners.empty()) continue;
    for (int i = 0; i < 3; ++i) {
      out.before[i] = rec.at(r - 1, 4 + static_cast<std::size_t>(i));
      out.after[i] = rec.at(r, 4 + static_cast<std::size_t>(i));
      out.q_before[i] = rec.at(r - 1, 1 + static_cast<std::size_t>(i));
    }
    out.contacts = s.make_contact_buffer();
    s.contact_data(rec.at(r - 1, 0), Vector(out.q_before), Vector(out.before), out.contacts);
    // The step's index set (g_N + (h/2) gdot_N <= 0): the contacts of its contact problem,
    // whether or not Lemke gives each of them an impulse.
    out.struck = out.corners;
    out.corners.clear();
    for (int c = 1; c <= 4; ++c) {
      const auto& d = out.contacts[static_cast<std::size_t>(c - 1)];
      if (d.gap_normal + 0.5 * h * d.gap_rate(Vector(out.before)) <= 0.0) out.corners.push_back(c);
    }
    return out;
  }
  FAIL("no impact within the run");
  return out;
}

// The impact problem (G = W^T M^-1 W over the struck corners, gdot- = W^T u-) built from the
// contact data at the impact step's start.
models::analytic::ImpactProblem impact_problem(const ImpactStep& s,
                                               const models::BridgeDesign& p) {
  const int m = static_cast<int>(s.corners.size());
  Eigen::MatrixXd W(3, 2 * m);
  for (int j = 0; j < m; ++j) {
    const auto& c = s.contacts[static_cast<std::size_t>(s.corners[static_cast<std::size_t>(j)] - 1)];
    W.col(j) = c.w_normal;
    W.col(m + j) = c.w_tangent;
  }
  const Eigen::Vector3d minv(1.0 / p.mass, 1.0 / p.mass, 1.0 / p.inertia);
  models::analytic::ImpactProblem ip;
  ip.delassus = W.transpose() * minv.asDiagonal() * W;
  ip.gdot_minus = W.transpose() * s.before;
  ip.restitution = Eigen::VectorXd::Constant(m, p.restitution);
  ip.friction = Eigen::VectorXd::Constant(m, p.friction);
  return ip;
}

Eigen::Vector3d velocity_after(const ImpactStep& s, const models::BridgeDesign& p,
                               const Eigen::VectorXd& ln, const Eigen::VectorXd& lt) {
  const int m = static_cast<int>(s.corners.size());
  Eigen::Vector3d u = s.before;
  for (int j = 0; j < m; ++j) {
    const auto& c = s.contacts[static_cast<std::size_t>(s.corners[static_cast<std::size_t>(j)] - 1)];
    const Eigen::Vector3d impulse = Eigen::Vector3d(c.w_normal) * ln[j] + Eigen::Vector3d(c.w_tangent) * lt[j];
    u += Eigen::Vector3d(impulse[0] / p.mass, impulse[1] / p.mass, impulse[2] / p.inertia);
  }
  return u;
}

void check_against_references(const models::BridgeDesign& p, const ImpactStep& s) {
  const auto ip = impact_problem(s, p);
  // Analytic: case enumeration.
  const auto cases = models::analytic::solve_impact_by_cases(ip);
  REQUIRE(cases.unique());
  const auto& sol = cases.solutions.front();
  const Eigen::Vector3d u_cases = velocity_after(s, p, sol.lambda_n, sol.lambda_t);
  INFO("Moreau–Jean ", s.after.transpose(), "; cases ", u_cases.transpose());
  CHECK((s.after - u_cases).cwiseAbs().maxCoeff() <= kExact * (1.0 + s.before.norm()));
  // Eq. (6) LCP solved directly (Lemke).
  lcp::FrictionalProblem fp;
  fp.delassus = ip.delassus;
  fp.gdot_free = ip.gdot_minus;
  const int m = static_cast<int>(s.corners.size());
  fp.gdot_n_minus = ip.gdot_minus.head(m);
  fp.restitution = ip.restitution;
  fp.friction = ip.friction;
  const auto r = lcp::solve_frictional(fp, lcp::Solver::kLemke);
  REQUIRE(r.ok());
  const Eigen::Vector3d u_lcp = velocity_after(s, p, r.lambda_n, r.lambda_t);
  CHECK((s.after - u_lcp).cwiseAbs().maxCoeff() <= kExact * (1.0 + s.before.norm()));
}

}  // namespace

TEST_CASE("double frictional impact of a free deck: both corners of the right end") {
  // The deck moves without rotation towards the right abutment; corners 3 and 4 strike it in
  // the same step. At theta = 0 the geometry is exactly that of analytic::deck_impact.
  for (double skew : {0.0, 30.0}) {
    for (double vy : {0.05, 0.6}) {  // sticking and sliding corners
      CAPTURE(skew);
      CAPTURE(vy);
      const auto p = deck(skew, 0.5, Eigen::Vector3d::Zero(), Eigen::Vector3d(0.5, vy, 0.0));
      const ImpactStep s = first_impact(p, 1e-4);
      CHECK(s.corners == std::vector<int>{3, 4});
      check_against_references(p, s);
      models::analytic::DeckBody g{p.mass, p.inertia, p.deck};
      const auto exact = models::analytic::deck_impact(g, {3, 4}, s.before, p.restitution,
                                                       p.friction);
      CHECK((s.after - exact.velocity_after).cwiseAbs().maxCoeff() <= kExact);
    }
  }
}

TEST_CASE("single frictional impact of a free deck: one corner") {
  // A small initial rotation puts corner 4 ahead of corner 3 by W sin(theta0) = 2.4 mm, 5 steps
  // of travel at 0.5 m/s and h = 1e-4: it strikes alone. The references use the contact
  // columns at the impact step (the rotated deck).
  for (double mu : {0.0, 0.2, 0.5}) {
    CAPTURE(mu);
    const auto p = deck(0.0, mu, Eigen::Vector3d(0.0, 0.0, 1e-3), Eigen::Vector3d(0.5, 0.2, 0.0));
    const ImpactStep s = first_impact(p, 1e-4);
    CHECK(s.corners == std::vector<int>{4});
    check_against_references(p, s);
    // The impact sets the deck rotating (the impulse acts off the centre).
    CHECK(std::abs(s.after[2]) > 1e-4);
  }
}

}  // namespace nsb
