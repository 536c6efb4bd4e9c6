// Every LCP solver on every problem of Siconos's LCP test collection (data/siconos-lcp), with
// the expected outcome of each pair and, where a solver cannot succeed, the mathematical
// reason. A solved problem is checked on the LCP conditions directly, not on the solver's
// own residual.
#include "lcp/enumeration.hpp"
#include "lcp/lemke.hpp"
#include "lcp/siconos_format.hpp"
#include "lcp/solve.hpp"
#include "lcp/test/problems.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <map>
#include <set>
#include <string>

using namespace nsb::lcp;

namespace {
const std::filesystem::path kDir = std::filesystem::path(NSB_DATA_DIR) / "siconos-lcp";

// Checked on z and w = M z + q directly, relative to 1 + ||q||_inf. The default tolerance of
// the solvers is 1e-12 on the same scale; 1e-10 leaves room for the summation order.
constexpr double kConditions = 1e-10;

// Solvers where the outcome is not kSolved. Everything else must be solved.
struct Expected {
  Status status;
  const char* reason;
};
const std::map<std::pair<std::string, Solver>, Expected>& failures() {
  static const std::map<std::pair<std::string, Solver>, Expected> table = {
      // CPS_3: a bimatrix game, M = [0 A; B^T 0] with A, B > 0 and q = -e. M >= 0 is
      // copositive but not copositive-plus (z = e_1 gives z^T M z = 0 with (M + M^T) z != 0),
      // so Lemke's method with covering vector e is not guaranteed to process it, and it ends
      // on a secondary ray after its first pivot. A solution exists: enumeration finds one.
      // (Siconos's own tests expect Lemke to fail here.)
      {{"lcp_CPS_3.dat", Solver::kLemke},
       {Status::kRayTermination, "copositive, not copositive-plus (bimatrix game)"}},
      // Pang_isolated_sol_perturbed: row 1 of M is (0, -1, -1) and q_1 = -1e-4, so
      // w_1 = -z_2 - z_3 - 1e-4 < 0 for every z >= 0: the problem is infeasible.
      {{"lcp_Pang_isolated_sol_perturbed.dat", Solver::kLemke},
       {Status::kRayTermination, "infeasible: w_1 = -z_2 - z_3 - 1e-4 < 0"}},
      {{"lcp_Pang_isolated_sol_perturbed.dat", Solver::kNewtonFb},
       {Status::kMaxIterations, "infeasible: 1/2 ||Phi||^2 has no zero to converge to"}},
      {{"lcp_Pang_isolated_sol_perturbed.dat", Solver::kEnumeration},
       {Status::kNoSolution, "infeasible"}},
      // tobenna: M is not a P0-matrix (the principal minor on indices 1 and 17 is -3289), so
      // stationary points of the FB merit function need not solve the LCP (Facchinei & Pang
      // 2003, Thm 9.1.14 needs P0) and Newton–FB stalls. Lemke solves it.
      {{"lcp_tobenna.dat", Solver::kNewtonFb},
       {Status::kMaxIterations, "not P0: FB stationary points need not be solutions"}},
      {{"lcp_tobenna.dat", Solver::kEnumeration}, {Status::kTooLarge, "n = 40 > 12"}},
      {{"lcp_mmc.dat", Solver::kEnumeration}, {Status::kTooLarge, "n = 26 > 12"}},
  };
  return table;
}

// PGS needs M_ii > 0 for its coordinate step: these problems have a zero diagonal entry
// (Siconos's tests expect PGS to fail on CPS_2, CPS_3, CPS_4, CPS_4bis and enum_fails).
const std::set<std::string> kZeroDiagonal = {
    "lcp_CPS_2.dat",  "lcp_CPS_3.dat",
    "lcp_CPS_4.dat",  "lcp_CPS_4bis.dat",
    "lcp_enum_fails.dat", "lcp_Pang_isolated_sol.dat",
    "lcp_Pang_isolated_sol_perturbed.dat", "lcp_inf_sol_perturbed.dat",
    "lcp_tobenna.dat"};

const Solver kAll[] = {Solver::kLemke, Solver::kPgs, Solver::kNewtonFb, Solver::kEnumeration};
}  // namespace

TEST_CASE("every solver on every problem of the collection") {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kDir)) {
    const std::string name = entry.path().filename().string();
    if (name.find("_block") != std::string::npos) continue;  // same problems, sparse storage
    ++files;
    const Problem p = read_siconos_lcp(entry.path());
    for (Solver s : kAll) {
      const Result r = solve(p, s);
      INFO(name << ", solver " << to_string(s) << ": " << to_string(r.status) << " after "
                << r.iterations << " iterations, residual " << r.residual << " (" << r.message
                << ")");
      Status expected = Status::kSolved;
      if (s == Solver::kPgs && kZeroDiagonal.count(name)) {
        bool zero = false;
        for (Eigen::Index i = 0; i < p.size(); ++i) zero = zero || !(p.M(i, i) > 0.0);
        CHECK(zero);  // the reason holds
        expected = Status::kZeroDiagonal;
      }
      const auto f = failures().find({name, s});
      if (f != failures().end()) expected = f->second.status;
      CHECK(to_string(r.status) == to_string(expected));
      if (r.ok()) {
        CHECK(testing::lcp_violations(p, r.z, kConditions).empty());
        CHECK(r.siconos_error < 1e-10);
      }
    }
  }
  CHECK(files == 17);
}

TEST_CASE("where a solution exists and a solver fails, another solver proves it exists") {
  // CPS_3 (Lemke's ray) and tobenna (Newton–FB's stall) are solvable.
  const Problem cps3 = read_siconos_lcp(kDir / "lcp_CPS_3.dat");
  const Result e = enumerate(cps3);
  REQUIRE(e.ok());
  CHECK(testing::lcp_violations(cps3, e.z, kConditions).empty());
  const Problem tob = read_siconos_lcp(kDir / "lcp_tobenna.dat");
  const Result l = lemke(tob);
  REQUIRE(l.ok());
  CHECK(testing::lcp_violations(tob, l.z, kConditions).empty());
  // tobenna's negative principal minor (not P0), as stated above.
  CHECK(tob.M(0, 0) * tob.M(16, 16) - tob.M(0, 16) * tob.M(16, 0) == -3289.0);
}

TEST_CASE("unique solutions agree across solvers") {
  // deudeu, ortiz, trivial and Murty's two problems have P-matrices (positive definite or
  // triangular with a positive diagonal): one solution, which every solver must return.
  for (const char* name : {"lcp_deudeu.dat", "lcp_ortiz.dat", "lcp_trivial.dat",
                           "lcp_exp_murty.dat", "lcp_exp_murty2.dat"}) {
    const Problem p = read_siconos_lcp(kDir / name);
    const Result ref = enumerate(p);
    REQUIRE(ref.ok());
    for (Solver s : kAll) {
      const Result r = solve(p, s);
      INFO(name << ", solver " << to_string(s));
      REQUIRE(r.ok());
      CHECK(testing::relative_distance(r.z, ref.z) < 1e-9);
    }
  }
}

TEST_CASE("Murty's example: Lemke needs 2^n pivots") {
  // lcp_exp_murty2.dat, n = 6: Murty (1988), ch. 6. 64 = 2^6 pivots counting the first one
  // (z0 entering), i.e. 2^n - 1 complementary pivots after it, as Siconos's notes state.
  const Problem p = read_siconos_lcp(kDir / "lcp_exp_murty2.dat");
  const Result r = lemke(p);
  REQUIRE(r.ok());
  MESSAGE("Lemke on lcp_exp_murty2.dat: " << r.iterations << " pivots");
  CHECK(r.iterations == 64);
  // With q = -e (lcp_exp_murty.dat) the same matrix needs only 2 pivots.
  CHECK(lemke(read_siconos_lcp(kDir / "lcp_exp_murty.dat")).iterations == 2);
}

TEST_CASE("the sparse-block files are rejected with a message naming the dense alternative") {
  for (const char* name : {"lcp_deudeu_block.dat", "lcp_ortiz_block.dat", "lcp_trivial_block.dat"})
    CHECK_THROWS_WITH_AS(read_siconos_lcp(kDir / name), doctest::Contains("sparse block"),
                         FormatError);
}
