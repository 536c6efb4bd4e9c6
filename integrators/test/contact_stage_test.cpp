// Unit tests of the contact stage: the kinematics of eqs. (3), (7), (8) against hand-computed
// matrices, the fallback chain, and the statuses, with expected values derived in comments.
#include "integrators/contact_stage.hpp"

#include "lcp/enumeration.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace nsb::integrators {
namespace {

// Two contacts on a 2-DOF system: contact 0 with W_N = (1, 0), W_T = (0, 1); contact 1 with
// W_N = (1, 1), W_T = (1, -1); what_N = (0.5, -0.25), what_T = (0.1, 0.2).
std::vector<ContactData> two_contacts(double mu = 0.3) {
  std::vector<ContactData> c(2);
  for (auto& ci : c) {
    ci.w_normal = Vector::Zero(2);
    ci.w_tangent = Vector::Zero(2);
    ci.friction = mu;
  }
  c[0].w_normal << 1.0, 0.0;
  c[0].w_tangent << 0.0, 1.0;
  c[1].w_normal << 1.0, 1.0;
  c[1].w_tangent << 1.0, -1.0;
  c[0].what_normal = 0.5;
  c[1].what_normal = -0.25;
  c[0].what_tangent = 0.1;
  c[1].what_tangent = 0.2;
  c[0].wbar_normal = 7.0;
  c[1].wbar_normal = -3.0;
  return c;
}

TEST_CASE("Delassus matrix and free velocities (eqs. 3, 7, 8) match the hand computation") {
  // A^-1 = diag(1/2, 1/4). W = [W_N0 W_N1 W_T0 W_T1] = [[1,1,0,1],[0,1,1,-1]].
  // G = W^T A^-1 W: G_ij = w_i(0) w_j(0) / 2 + w_i(1) w_j(1) / 4.
  Matrix a_inv = Matrix::Zero(2, 2);
  a_inv(0, 0) = 0.5;
  a_inv(1, 1) = 0.25;
  const auto c = two_contacts();
  const std::vector<int> index = {0, 1};
  ContactStage stage(2, 2, {});
  Vector u(2);
  u << 2.0, -1.0;
  const lcp::FrictionalProblem& p =
      stage.build(c, index, true, a_inv, u, ContactLevel::kVelocity);
  Matrix expected(4, 4);
  expected << 0.5, 0.5, 0.0, 0.5,       //
      0.5, 0.75, 0.25, 0.25,            //
      0.0, 0.25, 0.25, -0.25,           //
      0.5, 0.25, -0.25, 0.75;
  CHECK((p.delassus - expected).cwiseAbs().maxCoeff() == 0.0);
  // gdot_N = W_N^T u + what_N: (2 + 0.5, 2 - 1 - 0.25); gdot_T = (-1 + 0.1, 2 + 1 + 0.2).
  CHECK(p.gdot_free[0] == 2.5);
  CHECK(p.gdot_free[1] == 0.75);
  CHECK(p.gdot_free[2] == doctest::Approx(-0.9));
  CHECK(p.gdot_free[3] == doctest::Approx(3.2));
  CHECK(p.friction[0] == 0.3);
  // Acceleration level: wbar replaces what, and no friction unless the caller sets it.
  const lcp::FrictionalProblem& pa =
      stage.build(c, index, false, a_inv, u, ContactLevel::kAcceleration);
  CHECK(pa.delassus.rows() == 2);
  CHECK(pa.gdot_free[0] == 9.0);
  CHECK(pa.gdot_free[1] == -2.0);
  CHECK(pa.friction[0] == 0.0);
}

TEST_CASE("a sliding contact's friction enters its normal column at acceleration level") {
  // B_N0 = W_N0 - mu s W_T0 with mu s = 0.3: (1, -0.3). G_00 = W_N0^T A^-1 B_N0 = 1 * 1 = 1
  // with A^-1 = I; G_10 = W_N1^T B_N0 = 1 - 0.3 = 0.7.
  const auto c = two_contacts();
  const std::vector<int> index = {0, 1};
  ContactStage stage(2, 2, {});
  const double coupling[] = {-0.3, 0.0};
  const lcp::FrictionalProblem& p =
      stage.build(c, index, false, Matrix::Identity(2, 2), Vector::Zero(2),
                  ContactLevel::kAcceleration, coupling);
  CHECK(p.delassus(0, 0) == doctest::Approx(1.0));
  CHECK(p.delassus(1, 0) == doctest::Approx(0.7));
  CHECK(p.delassus(0, 1) == doctest::Approx(1.0));
}

TEST_CASE("one frictionless contact is solved in closed form and applied") {
  // G = 1/2, b = gdot_free + eps gdot_N- = -1 + 0.5 (-2) = -2: Lambda = 4, du = A^-1 W 4 = 2.
  auto c = two_contacts(0.0);
  c[0].restitution = 0.5;
  const std::vector<int> index = {0};
  ContactStage stage(2, 2, {});
  Matrix a_inv = Matrix::Zero(2, 2);
  a_inv(0, 0) = 0.5;
  a_inv(1, 1) = 0.25;
  Vector u(2);
  u << -1.5, 0.0;  // gdot_free = -1.5 + 0.5 = -1
  lcp::FrictionalProblem& p = stage.build(c, index, false, a_inv, u, ContactLevel::kVelocity);
  p.gdot_n_minus[0] = -2.0;
  CHECK(stage.solve() == ContactStatus::kSolved);
  CHECK(stage.lambda_n(0) == doctest::Approx(4.0));
  Vector v = u;
  stage.apply(v);
  CHECK(v[0] == doctest::Approx(0.5));  // gdot+ = 0.5 + 0.5 = 1 = -eps gdot-
}

TEST_CASE("the fallback chain solves what the configured solver cannot") {
  // Contact 0 has W_N = 0 (a degenerate column): G = [[0, 0], [0, 0.5]] has a zero diagonal,
  // on which PGS stops with kZeroDiagonal. The problem is still solvable: contact 0 is
  // separating (gdot_free,0 = what_N0 = 0.5 > 0, Lambda_0 = 0) and contact 1 closes with
  // Lambda_1 = -gdot_free,1 / G_11 = 1.25 / 0.5 = 2.5 (A^-1 = I, W_N1 = (0.5, 0.5),
  // G_11 = 0.5, gdot_free,1 = what_N1 = -1.25). Lemke, second in the chain, solves it.
  std::vector<ContactData> c = two_contacts(0.0);
  c[0].w_normal.setZero();
  c[1].w_normal << 0.5, 0.5;
  c[1].what_normal = -1.25;
  const std::vector<int> index = {0, 1};
  ContactStageOptions o;
  o.solver = lcp::Solver::kPgs;
  SUBCASE("with the chain") {
    ContactStage stage(2, 2, o);
    stage.build(c, index, false, Matrix::Identity(2, 2), Vector::Zero(2), ContactLevel::kVelocity);
    CHECK(stage.solve() == ContactStatus::kSolvedByFallback);
    CHECK(stage.result().solver_used == lcp::Solver::kLemke);
    CHECK(stage.lambda_n(0) == doctest::Approx(0.0));
    CHECK(stage.lambda_n(1) == doctest::Approx(2.5));
    CHECK(stage.counts().fallbacks == 1);
    CHECK(stage.counts().unsolved == 0);
  }
  SUBCASE("without the chain the problem stays unsolved, and says so") {
    o.fallback = false;
    ContactStage stage(2, 2, o);
    stage.build(c, index, false, Matrix::Identity(2, 2), Vector::Zero(2), ContactLevel::kVelocity);
    CHECK(stage.solve() == ContactStatus::kUnsolved);
    CHECK(stage.counts().unsolved == 1);
    CHECK(stage.impulses().cwiseAbs().maxCoeff() == 0.0);
  }
}

TEST_CASE("the chain's order: a configured solver that fails hands over to Lemke, second") {
  // Five decoupled particles (10 DOF, A^-1 = I): contact i has W_N = e_2i, W_T = e_2i+1, so
  // G = I (10 x 10) and eq. (6) has 15 unknowns, more than enumeration's max_size (12):
  // enumeration, configured first, returns kTooLarge. The chain (configured, Lemke, PGS,
  // enumeration) then runs Lemke. By hand, with what_N = -1, what_T = 0.1, mu = 0.3, eps = 0:
  // Lambda_N = 1 closes each contact (gdot_N+ = -1 + 1 = 0); stopping the slip needs
  // |Lambda_T| = 0.1 <= mu Lambda_N = 0.3, so each sticks with Lambda_T = -0.1.
  constexpr int kContacts = 5;
  std::vector<ContactData> c(kContacts);
  std::vector<int> index;
  for (int i = 0; i < kContacts; ++i) {
    ContactData& ci = c[static_cast<std::size_t>(i)];
    ci.w_normal = Vector::Zero(2 * kContacts);
    ci.w_tangent = Vector::Zero(2 * kContacts);
    ci.w_normal[2 * i] = 1.0;
    ci.w_tangent[2 * i + 1] = 1.0;
    ci.what_normal = -1.0;
    ci.what_tangent = 0.1;
    ci.friction = 0.3;
    index.push_back(i);
  }
  REQUIRE(3 * kContacts > lcp::EnumerationOptions{}.max_size);
  ContactStageOptions o;
  o.solver = lcp::Solver::kEnumeration;
  ContactStage stage(2 * kContacts, kContacts, o);
  stage.build(c, index, true, Matrix::Identity(2 * kContacts, 2 * kContacts),
              Vector::Zero(2 * kContacts), ContactLevel::kVelocity);
  CHECK(stage.solve() == ContactStatus::kSolvedByFallback);
  CHECK(stage.result().solver_used == lcp::Solver::kLemke);
  CHECK(stage.counts().fallbacks == 1);
  CHECK(stage.counts().unsolved == 0);
  for (int i = 0; i < kContacts; ++i) {
    CHECK(stage.lambda_n(i) == doctest::Approx(1.0));
    CHECK(stage.lambda_t(i) == doctest::Approx(-0.1));
  }
}

TEST_CASE("non-finite data is reported, never thrown") {
  auto c = two_contacts();
  c[1].what_normal = std::numeric_limits<double>::quiet_NaN();
  const std::vector<int> index = {0, 1};
  ContactStage stage(2, 2, {});
  stage.build(c, index, true, Matrix::Identity(2, 2), Vector::Zero(2), ContactLevel::kVelocity);
  ContactStatus s = ContactStatus::kSolved;
  CHECK_NOTHROW(s = stage.solve());
  CHECK(s == ContactStatus::kNonFiniteInput);
  CHECK(stage.counts().non_finite == 1);
  CHECK(stage.impulses().cwiseAbs().maxCoeff() == 0.0);
}

TEST_CASE("round-off tolerances scale with the problem") {
  Vector q(2);
  q << 0.0, -3.0;
  // kRoundOff (1 + |q|_inf) = 1024 eps * 4.
  CHECK(ContactTolerances::gap(q) == doctest::Approx(4.0 * 1024.0 * 2.220446049250313e-16));
}

}  // namespace
}  // namespace nsb::integrators

namespace nsb::integrators {
namespace {

// Keeps what the stage shows it, copied (the references die with the next solve).
class Recording final : public ContactObserver {
 public:
  struct Seen {
    ProblemOrigin origin;
    ContactStatus status;
    bool closed_form;
    lcp::Solver solver;
    Eigen::Index contacts;
    double gdot_n_minus0;
  };
  void solved(const SolvedProblem& s) override {
    seen.push_back({s.origin, s.status, s.closed_form, s.result.solver_used,
                    s.problem.contacts(), s.problem.gdot_n_minus[0]});
  }
  std::vector<Seen> seen;
};

}  // namespace

TEST_CASE("an observer is shown every problem once, after the chain, with its origin") {
  Recording observer;
  ContactStageOptions o;
  o.solver = lcp::Solver::kPgs;
  o.observer = &observer;
  ContactStage stage(2, 2, o);
  // 1. One frictionless contact (the closed form of the test above), edited before solve():
  //    the observer sees the problem as solved, gdot_N- = -2.
  auto c = two_contacts(0.0);
  lcp::FrictionalProblem& p =
      stage.build(c, {0}, false, Matrix::Identity(2, 2), Vector::Zero(2), ContactLevel::kVelocity);
  p.gdot_n_minus[0] = -2.0;
  CHECK(stage.solve({ProblemKind::kImpact, 0.25, 7}) == ContactStatus::kSolved);
  // 2. The zero-diagonal problem that PGS refuses and Lemke solves (test above).
  c[0].w_normal.setZero();
  c[1].w_normal << 0.5, 0.5;
  c[1].what_normal = -1.25;
  stage.build(c, {0, 1}, false, Matrix::Identity(2, 2), Vector::Zero(2), ContactLevel::kVelocity);
  CHECK(stage.solve({ProblemKind::kStep, 0.5, 8}) == ContactStatus::kSolvedByFallback);
  // 3. Non-finite data: shown too, with nothing solved.
  c[1].what_normal = std::numeric_limits<double>::quiet_NaN();
  stage.build(c, {0, 1}, false, Matrix::Identity(2, 2), Vector::Zero(2), ContactLevel::kVelocity);
  CHECK(stage.solve() == ContactStatus::kNonFiniteInput);

  REQUIRE(observer.seen.size() == 3);
  CHECK(static_cast<std::int64_t>(observer.seen.size()) == stage.counts().solves);
  const auto& a = observer.seen[0];
  CHECK(a.origin.kind == ProblemKind::kImpact);
  CHECK(a.origin.t == 0.25);
  CHECK(a.origin.step == 7);
  CHECK(a.closed_form);
  CHECK(a.contacts == 1);
  CHECK(a.gdot_n_minus0 == -2.0);
  const auto& b = observer.seen[1];
  CHECK(b.origin.kind == ProblemKind::kStep);
  CHECK(b.status == ContactStatus::kSolvedByFallback);
  CHECK_FALSE(b.closed_form);
  CHECK(b.solver == lcp::Solver::kLemke);
  CHECK(b.contacts == 2);
  CHECK(observer.seen[2].status == ContactStatus::kNonFiniteInput);
}

}  // namespace nsb::integrators
