// The frictional impact problem of eq. (6): hand-solved impacts of a particle, properties of
// random planar rigid bodies with 1 to 4 contacts, all solvers against each other, the
// fallback and the reusable solver.
#include "lcp/enumeration.hpp"
#include "lcp/frictional.hpp"
#include "lcp/lemke.hpp"
#include "lcp/pgs.hpp"
#include "lcp/test/problems.hpp"

#include <doctest/doctest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <new>
#include <random>
#include <stdexcept>

// Counts heap allocations, to check that the time-stepping path allocates nothing.
namespace {
std::atomic<long> g_allocations{0};
}  // namespace
void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

using namespace nsb::lcp;

namespace {
// Hand solutions below are short rational expressions: a few roundings.
constexpr double kHand = 1e-13;
// Iterative solvers (PGS, Newton–FB) stop at this residual; their answers agree with the
// direct ones to about this much relative to the data.
constexpr double kIterative = 1e-10;
// Consistency of two computations of the same velocity (through G or through u+): a few
// roundings of products of O(1) data.
constexpr double kConsistency = 1e-12;

const Solver kAllSolvers[] = {Solver::kLemke, Solver::kPgs, Solver::kNewtonFb,
                              Solver::kEnumeration};

// A particle of mass m hitting a surface with normal (0, 1) and tangent (1, 0):
// W_N = (0, 1), W_T = (1, 0), G = W^T M^-1 W = I/m (eq. 8), gdot- = W^T u-.
FrictionalProblem particle(double m, double vx, double vy, double eps, double mu) {
  FrictionalProblem fp;
  fp.delassus = Matrix::Identity(2, 2) / m;
  fp.gdot_free = (Vector(2) << vy, vx).finished();
  fp.gdot_n_minus = Vector::Constant(1, vy);
  fp.restitution = Vector::Constant(1, eps);
  fp.friction = Vector::Constant(1, mu);
  return fp;
}

SolveOptions options_for(Solver s) {
  SolveOptions o;
  if (s == Solver::kPgs || s == Solver::kNewtonFb) o.tolerance = 1e-13;
  return o;
}
}  // namespace

TEST_CASE("hand-solved particle impacts: sliding both ways and sticking") {
  // m = 2, eps = 0.5, mu = 0.4, gdot_N- = -2. Newton's law (eq. 3): gdot_N+ = -eps gdot_N- = 1,
  // so Lambda_N = m (gdot_N+ - gdot_N-) = 2 * 3 = 6 and the friction bound is mu Lambda_N = 2.4.
  struct Case {
    double vx, lambda_t, gdot_t;
  };
  // vx = 3: stopping needs |Lambda_T| = m |vx| = 6 > 2.4, so it slides: Lambda_T = -2.4,
  //         gdot_T+ = 3 - 2.4/2 = 1.8.
  // vx = -3: the mirror image: Lambda_T = +2.4, gdot_T+ = -1.8.
  // vx = 1: stopping needs |Lambda_T| = 2 <= 2.4, so it sticks: Lambda_T = -2, gdot_T+ = 0.
  const Case cases[] = {{3.0, -2.4, 1.8}, {-3.0, 2.4, -1.8}, {1.0, -2.0, 0.0}};
  for (const Case& c : cases) {
    const FrictionalProblem fp = particle(2.0, c.vx, -2.0, 0.5, 0.4);
    for (Solver s : kAllSolvers) {
      const FrictionalResult r = solve_frictional(fp, s, options_for(s));
      INFO("vx = " << c.vx << ", solver " << to_string(s));
      REQUIRE(r.ok());
      const double tol = (s == Solver::kPgs || s == Solver::kNewtonFb) ? kIterative : kHand;
      CHECK(r.lambda_n(0) == doctest::Approx(6.0).epsilon(tol));
      CHECK(r.lambda_t(0) == doctest::Approx(c.lambda_t).epsilon(tol));
      CHECK(r.gdot_n_plus(0) == doctest::Approx(1.0).epsilon(tol));
      CHECK(std::abs(r.gdot_t_plus(0) - c.gdot_t) < 10 * tol);
      CHECK(r.residual <= 1e-12);
      CHECK(r.solver_used == s);
    }
  }
}

TEST_CASE("eq. 4 corrected: gdot_TL+ = (|gdot_T+| - gdot_T+)/2 is the third block of z") {
  // The sliding case vx = -3 above has gdot_T+ = -1.8: the corrected eq. 4 gives
  // gdot_TR+ = 0 and gdot_TL+ = 1.8. (The misprinted gdot_TL = (|gdot_T| + gdot_T)/2 would be
  // 0, and gdot_T = gdot_TR - gdot_TL would then be 0, contradicting the sliding velocity.)
  // Lambda_TR = mu Lambda_N + Lambda_T = 2.4 + 2.4 = 4.8 and Lambda_TL = 2.4 - 2.4 = 0 (eq. 5).
  const FrictionalProblem fp = particle(2.0, -3.0, -2.0, 0.5, 0.4);
  const Problem p = build_eq6(fp);
  REQUIRE(p.size() == 3);
  const Result r = lemke(p);
  REQUIRE(r.ok());
  CHECK(r.z(0) == doctest::Approx(6.0).epsilon(kHand));  // Lambda_N
  CHECK(r.z(1) == doctest::Approx(4.8).epsilon(kHand));  // Lambda_TR
  CHECK(r.z(2) == doctest::Approx(1.8).epsilon(kHand));  // gdot_TL+
  CHECK(std::abs(r.w(0)) < kHand);                       // gdot_N0 = gdot_N+ + eps gdot_N- = 0
  CHECK(std::abs(r.w(1)) < kHand);                       // gdot_TR+ = 0
  CHECK(std::abs(r.w(2)) < kHand);                       // Lambda_TL = 0
}

TEST_CASE("build_eq6 has the block structure of eq. 6") {
  std::mt19937 rng(5);
  const auto b = testing::rigid_body_impact(rng, 2, 0.3, 0.6);
  const FrictionalProblem& fp = b.problem;
  const Problem p = build_eq6(fp);
  const Eigen::Index m = 2;
  REQUIRE(p.size() == 3 * m);
  const Matrix G = fp.delassus;
  const Matrix mu = fp.friction.asDiagonal();
  const Matrix I = Matrix::Identity(m, m);
  CHECK((p.M.block(0, 0, m, m) - (G.block(0, 0, m, m) - G.block(0, m, m, m) * mu)).isZero(0.0));
  CHECK((p.M.block(0, m, m, m) - G.block(0, m, m, m)).isZero(0.0));
  CHECK(p.M.block(0, 2 * m, m, m).isZero(0.0));
  CHECK((p.M.block(m, 0, m, m) - (G.block(m, 0, m, m) - G.block(m, m, m, m) * mu)).isZero(0.0));
  CHECK((p.M.block(m, m, m, m) - G.block(m, m, m, m)).isZero(0.0));
  CHECK((p.M.block(m, 2 * m, m, m) - I).isZero(0.0));
  CHECK((p.M.block(2 * m, 0, m, m) - 2.0 * mu).isZero(0.0));
  CHECK((p.M.block(2 * m, m, m, m) + I).isZero(0.0));
  CHECK(p.M.block(2 * m, 2 * m, m, m).isZero(0.0));
  // q = ((eps + E) gdot_N-, gdot_T-, 0) for an impact (gdot_free = gdot-).
  const Vector qn = (fp.restitution.array() + 1.0) * fp.gdot_n_minus.array();
  CHECK((p.q.head(m) - qn).lpNorm<Eigen::Infinity>() < kHand);
  CHECK((p.q.segment(m, m) - fp.gdot_free.tail(m)).isZero(0.0));
  CHECK(p.q.tail(m).isZero(0.0));
}

// Which random impacts must be solvable. With eps = 0 the LCP of eq. 6 always has a solution
// and Lemke finds it: its q is W^T u- (times 1 in the normal rows), so q^T d = u-^T W d = 0
// for every self-equilibrated impulse d (W d = 0), which is the condition under which
// Lemke's method processes such copositive problems (Anitescu & Potra 1997, Theorem 2;
// Cottle, Pang & Stone 1992, Theorem 4.4.13). With eps > 0 and two or fewer contacts the
// body's 3 DOF leave no self-equilibrated impulse, so the same holds. With eps > 0 and 3 or 4
// frictional contacts a wedged body can make q^T d < 0 (Newton's law asks for a rebound the
// friction locks): then no solution exists; see the test "expected failure" below.
TEST_CASE("random planar rigid bodies, 1 to 4 contacts: Newton's and Coulomb's laws hold") {
  std::mt19937 rng(2017);
  for (int trial = 0; trial < 240; ++trial) {
    const int contacts = 1 + trial % 4;
    const double eps = contacts <= 2 && (trial / 4) % 3 != 0 ? 0.5 : 0.0;
    const double mu = (trial / 12) % 4 == 0 ? 0.0 : 0.2 + 0.3 * ((trial / 12) % 3);
    const auto b = testing::rigid_body_impact(rng, contacts, eps, mu);
    const FrictionalProblem& fp = b.problem;
    for (Solver s : kAllSolvers) {
      // Enumeration visits 2^(3m) supports: keep it to m <= 3 here (the verification check
      // compares every solver with it at m = 4 too).
      if (s == Solver::kEnumeration && contacts == 4) continue;
      INFO("trial " << trial << ", " << contacts << " contacts, mu = " << mu << ", eps = " << eps
                    << ", solver " << to_string(s));
      const FrictionalResult r = solve_frictional(fp, s, options_for(s));
      // Lemke and enumeration must solve eq. 6 here; the iterative ones may stall on the
      // singular Delassus matrices of 2+ frictional contacts (rank 3 < 2m), which is what the
      // fallback is for.
      if (s == Solver::kLemke || s == Solver::kEnumeration) REQUIRE(r.ok());
      if (!r.ok()) continue;
      const double tol = (s == Solver::kLemke || s == Solver::kEnumeration) ? 1e-12 : 1e-9;
      // Independent check through the velocities: u+ = u- + M^-1 (W_N L_N + W_T L_T), and
      // the contact velocities are W^T u+ (not taken from the solver).
      const Eigen::Vector3d u_plus =
          b.u_minus + b.mass.inverse() * (b.W_n * r.lambda_n + b.W_t * r.lambda_t);
      const Vector gn = b.W_n.transpose() * u_plus;
      const Vector gt = b.W_t.transpose() * u_plus;
      CHECK((gn - r.gdot_n_plus).lpNorm<Eigen::Infinity>() < kConsistency * 10);
      if (mu > 0) CHECK((gt - r.gdot_t_plus).lpNorm<Eigen::Infinity>() < kConsistency * 10);
      const double scale = 1.0 + fp.gdot_free.lpNorm<Eigen::Infinity>() +
                           r.lambda_n.lpNorm<Eigen::Infinity>();
      for (int i = 0; i < contacts; ++i) {
        const double gn0 = gn(i) + eps * fp.gdot_n_minus(i);  // eq. 3 / 7
        CHECK(r.lambda_n(i) >= -tol * scale);
        CHECK(gn0 >= -tol * scale);
        CHECK(std::abs(r.lambda_n(i) * gn0) <= tol * scale * scale);
        CHECK(std::abs(r.lambda_t(i)) <= mu * r.lambda_n(i) + tol * scale);  // cone
        if (mu > 0 && r.lambda_n(i) > 1e-6 * scale && std::abs(gt(i)) > 1e-6 * scale) {  // sliding: full friction, opposed
          CHECK(r.lambda_t(i) * gt(i) < 0.0);
          CHECK(std::abs(std::abs(r.lambda_t(i)) - mu * r.lambda_n(i)) <= tol * scale);
        }
      }
      // With eps = 0 the impact cannot create kinetic energy:
      // dT = gdot+^T L - 1/2 L^T G L <= 0 since L_N^T gdot_N+ = 0 and L_T^T gdot_T+ <= 0.
      if (eps == 0.0) {
        const double before = 0.5 * b.u_minus.dot(b.mass * b.u_minus);
        const double after = 0.5 * u_plus.dot(b.mass * u_plus);
        CHECK(after <= before * (1.0 + 1e-9) + 1e-12);
      }
      CHECK(r.residual <= (s == Solver::kLemke || s == Solver::kEnumeration ? 1e-11 : 1e-9));
    }
  }
}

TEST_CASE("expected failure: restitution with a wedged frictional body has no solution") {
  // Three contacts, eps = 0.5, mu = 0.5: the contacts at both ends can push against each other
  // (an impulse d >= 0 in the friction cones with W d = 0), and the rebound that Newton's law
  // asks for (the eps gdot_N- part of q) makes q^T d < 0. By Farkas' lemma the LCP is then
  // infeasible along d. Enumeration confirms there is no complementary solution; Lemke must
  // report a failure, never success: a verified secondary ray, or kRoundOff when pivots on
  // near-zero entries spoilt the tableau so that the ray does not verify.
  std::mt19937 rng(2017);
  int infeasible = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const auto b = testing::rigid_body_impact(rng, 3, 0.5, 0.5);
    const Problem p = build_eq6(b.problem);
    const Result e = enumerate(p);
    const Result l = lemke(p);
    if (e.status == Status::kNoSolution) {
      ++infeasible;
      CHECK((l.status == Status::kRayTermination || l.status == Status::kRoundOff));
      // Neither PGS nor Lemke with its regularized retries (the contact stage's chain
      // before enumeration) can succeed either.
      CHECK_FALSE(solve_frictional(b.problem, Solver::kPgs).ok());
      const FrictionalResult f = solve_frictional(b.problem, Solver::kLemke);
      CHECK_FALSE(f.ok());
      CHECK(f.solver_used == Solver::kLemke);
    }
    if (l.ok()) CHECK(l.residual <= 1e-12);
  }
  CHECK(infeasible > 6);  // the case is common, not a curiosity of one seed
}

TEST_CASE("one contact: the impulses are unique, and every solver finds the same ones") {
  std::mt19937 rng(99);
  for (int trial = 0; trial < 100; ++trial) {
    const auto b = testing::rigid_body_impact(rng, 1, 0.3 * (trial % 3), 0.1 + 0.1 * (trial % 8));
    const FrictionalResult ref = solve_frictional(b.problem, Solver::kEnumeration);
    REQUIRE(ref.ok());
    for (Solver s : kAllSolvers) {
      const FrictionalResult r = solve_frictional(b.problem, s, options_for(s));
      INFO("trial " << trial << ", solver " << to_string(s));
      REQUIRE(r.ok());
      CHECK(std::abs(r.lambda_n(0) - ref.lambda_n(0)) <= kIterative * (1 + ref.lambda_n(0)));
      CHECK(std::abs(r.lambda_t(0) - ref.lambda_t(0)) <= kIterative * (1 + ref.lambda_n(0)));
    }
  }
}

TEST_CASE("frictionless problems have no tangential unknowns") {
  std::mt19937 rng(8);
  const auto b = testing::rigid_body_impact(rng, 3, 0.5, 0.0);  // m x m Delassus
  REQUIRE(b.problem.frictionless());
  CHECK(eq6_size(b.problem) == 3);
  for (Solver s : kAllSolvers) {
    const FrictionalResult r = solve_frictional(b.problem, s, options_for(s));
    REQUIRE(r.ok());
    CHECK(r.lambda_t.isZero(0.0));
    CHECK(r.gdot_t_plus.isZero(0.0));
  }
  // A 2m x 2m Delassus matrix with every mu = 0 also drops the tangential unknowns.
  const auto c = testing::rigid_body_impact(rng, 2, 0.5, 0.3);
  FrictionalProblem fp = c.problem;
  fp.friction.setZero();
  CHECK(eq6_size(fp) == 2);
  const FrictionalResult r = solve_frictional(fp, Solver::kLemke);
  REQUIRE(r.ok());
  CHECK(r.lambda_t.isZero(0.0));
  // The tangential velocities are still reported: gdot_T+ = G_TN L_N + gdot_T,free.
  Vector gt = fp.gdot_free.tail(2);
  gt.noalias() += fp.delassus.block(2, 0, 2, 2) * r.lambda_n;
  CHECK((gt - r.gdot_t_plus).lpNorm<Eigen::Infinity>() < kConsistency);
}

TEST_CASE("the LCP of eq. 6 has zero diagonal entries: plain PGS cannot run, the natural form can") {
  const FrictionalProblem fp = particle(2.0, 3.0, -2.0, 0.5, 0.4);
  // M(2, 2) = 0: the Lambda_TL row has no gdot_TL+ term (eq. 6, third row).
  const Result plain = pgs(build_eq6(fp));
  CHECK(plain.status == Status::kZeroDiagonal);
  const FrictionalResult natural = pgs_frictional(fp, PgsOptions{});
  CHECK(natural.ok());
  // Warm start at the solution: zero sweeps.
  const FrictionalResult warm = pgs_frictional(fp, PgsOptions{}, natural.lambda_n, natural.lambda_t);
  CHECK(warm.ok());
  CHECK(warm.iterations == 0);
}

TEST_CASE("a failed solver says so and hands over to no other; Lemke solves the problem") {
  // Two coupled frictional contacts: one PGS sweep cannot solve it. Trying another solver is
  // the contact stage's fallback chain (integrators/contact_stage.hpp), not lcp's.
  std::mt19937 rng(12);
  const FrictionalProblem fp = testing::rigid_body_impact(rng, 2, 0.0, 0.4).problem;
  SolveOptions one;
  one.max_iterations = 1;
  one.tolerance = 1e-14;
  const FrictionalResult no = solve_frictional(fp, Solver::kPgs, one);
  CHECK(no.status == Status::kMaxIterations);
  CHECK(no.solver_used == Solver::kPgs);
  CHECK(no.iterations == 1);
  const FrictionalResult lemke_only = solve_frictional(fp, Solver::kLemke);
  CHECK(lemke_only.ok());
  CHECK(lemke_only.solver_used == Solver::kLemke);
}

TEST_CASE("FrictionalSolver reuses its workspace and matches solve_frictional") {
  std::mt19937 rng(44);
  FrictionalSolver solver(4);
  FrictionalResult reused;
  for (int trial = 0; trial < 80; ++trial) {
    const int contacts = 1 + (trial * 3) % 4;
    const auto b = testing::rigid_body_impact(rng, contacts, 0.0, 0.5);
    for (Solver s : {Solver::kLemke, Solver::kPgs}) {
      solver.solve(b.problem, s, {}, reused);
      const FrictionalResult fresh = solve_frictional(b.problem, s);
      INFO("trial " << trial << ", solver " << to_string(s));
      CHECK(reused.status == fresh.status);
      CHECK(reused.solver_used == fresh.solver_used);
      CHECK((reused.lambda_n - fresh.lambda_n).lpNorm<Eigen::Infinity>() == 0.0);
      CHECK((reused.lambda_t - fresh.lambda_t).lpNorm<Eigen::Infinity>() == 0.0);
      CHECK(reused.ok());
    }
  }
}

TEST_CASE("validation names the field; read_eq6 checks the size") {
  FrictionalProblem fp = particle(2.0, 3.0, -2.0, 0.5, 0.4);
  fp.restitution(0) = 1.5;
  CHECK_THROWS_WITH_AS(fp.validate(), doctest::Contains("restitution(0)"), std::invalid_argument);
  fp.restitution(0) = 0.5;
  fp.friction(0) = -0.1;
  CHECK_THROWS_WITH_AS(fp.validate(), doctest::Contains("friction(0)"), std::invalid_argument);
  fp.friction(0) = 0.4;
  fp.gdot_free(1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH_AS(solve_frictional(fp, Solver::kLemke), doctest::Contains("gdot_free(1)"),
                       std::invalid_argument);
  fp.gdot_free(1) = 3.0;
  fp.delassus = Matrix::Identity(3, 3);
  CHECK_THROWS_WITH_AS(fp.validate(), doctest::Contains("delassus"), std::invalid_argument);
  fp = particle(2.0, 3.0, -2.0, 0.5, 0.4);
  CHECK_THROWS_AS(read_eq6(fp, Vector::Zero(2)), std::invalid_argument);
  // No contacts at all: a valid, trivial problem.
  FrictionalProblem none;
  const FrictionalResult r = solve_frictional(none, Solver::kLemke);
  CHECK(r.ok());
  CHECK(r.lambda_n.size() == 0);
}

TEST_CASE("FrictionalSolver: no heap allocation per call once sized (Lemke, PGS, Newton-FB)") {
  std::mt19937 rng(71);
  std::vector<FrictionalProblem> problems;
  for (int k = 0; k < 50; ++k) problems.push_back(testing::rigid_body_impact(rng, 3, 0.0, 0.5).problem);
  FrictionalSolver solver(4);
  FrictionalResult result;
  solver.solve(problems[0], Solver::kLemke, {}, result);  // sizes the result vectors
  solver.solve(problems[0], Solver::kNewtonFb, {}, result);  // sizes its eq. (6) LCP
  for (Solver s : {Solver::kLemke, Solver::kPgs, Solver::kNewtonFb}) {
    const long before = g_allocations.load();
    int solved = 0;
    for (const auto& fp : problems) {
      solver.solve(fp, s, {}, result);
      // A failure goes on to Lemke, as the contact stage's chain takes it: that call must not
      // allocate either (Newton-FB fails on 1 of these 50 problems).
      if (!result.ok()) solver.solve(fp, Solver::kLemke, {}, result);
      solved += result.ok();
    }
    const long allocations = g_allocations.load() - before;
    INFO("solver " << to_string(s));
    CHECK(allocations == 0);
    CHECK(solved == 50);
  }
}

TEST_CASE("in-place LCP solvers: the by-value answer, no clock, no message, no allocation") {
  // The in-place forms (Lemke::solve(p, o, r), pgs(p, o, r), NewtonFb::solve) must give the
  // same z as the by-value forms, which add only the wall time and the message; once the
  // Result has size n they allocate nothing (n <= NewtonFb::kSmall for Newton-FB).
  std::mt19937 rng(72);
  std::vector<Problem> problems;
  for (int k = 0; k < 20; ++k)
    problems.push_back(testing::manufacture(rng, testing::spd(rng, 8, 100.0)).problem);
  Lemke lemke_solver(8);
  NewtonFb nfb_solver;
  Result r;
  lemke_solver.solve(problems[0], LemkeOptions{}, r);  // sizes r
  const long before = g_allocations.load();
  for (const Problem& p : problems) {
    lemke_solver.solve(p, LemkeOptions{}, r);
    CHECK(r.ok());
    pgs(p, PgsOptions{}, r);
    CHECK(r.ok());
    nfb_solver.solve(p, NewtonFbOptions{}, r);
    CHECK(r.ok());
  }
  CHECK(g_allocations.load() - before == 0);
  for (const Problem& p : problems) {
    const Result a = lemke(p);
    lemke_solver.solve(p, LemkeOptions{}, r);
    CHECK(r.z == a.z);
    CHECK(r.residual == a.residual);
    CHECK(r.wall_time == 0.0);
    CHECK(r.message.empty());
    CHECK(a.message == describe(a.status));
    const Result b = pgs(p);
    pgs(p, PgsOptions{}, r);
    CHECK(r.z == b.z);
    const Result c = newton_fb(p);
    nfb_solver.solve(p, NewtonFbOptions{}, r);
    CHECK(r.z == c.z);
    CHECK(r.iterations == c.iterations);
  }
}
