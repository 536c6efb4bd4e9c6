// Performance profiles (Dolan & Moré 2002) on hand examples.
#include "benchmarks/performance_profile.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace nsb::benchmarks {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

TEST_CASE("three solvers on four problems: the ratios and rho by hand") {
  // Costs (rows: solvers A, B, C; columns: problems 1..4; inf = failed):
  //   A:  1    2    4    inf
  //   B:  2    2    1    3
  //   C:  inf  6    2    inf
  // Best per problem: 1, 2, 1, 3. Ratios r_p,s = t_p,s / best_p:
  //   A:  1    1    4    inf     rho_A: 2/4 on [1, 4), 3/4 from 4 on (one failure)
  //   B:  2    1    1    1       rho_B: 3/4 on [1, 2), 1 from 2 on
  //   C:  inf  3    2    inf     rho_C: 0 on [1, 2), 1/4 on [2, 3), 2/4 from 3 on
  const PerformanceProfile profile({{1.0, 2.0, 4.0, kInf}, {2.0, 2.0, 1.0, 3.0},
                                    {kInf, 6.0, 2.0, kInf}});
  REQUIRE(profile.solvers() == 3);
  REQUIRE(profile.problems() == 4);
  CHECK(profile.ratio(0, 2) == 4.0);
  CHECK(profile.ratio(1, 0) == 2.0);
  CHECK(profile.ratio(2, 1) == 3.0);
  CHECK(profile.ratio(2, 3) == kInf);
  CHECK(profile.rho(0, 1.0) == 0.5);
  CHECK(profile.rho(0, 3.99) == 0.5);
  CHECK(profile.rho(0, 4.0) == 0.75);
  CHECK(profile.rho(0, 1e300) == 0.75);
  CHECK(profile.rho(0, kInf) == 0.75);  // a failure is within no factor
  CHECK(profile.rho(1, 1.0) == 0.75);
  CHECK(profile.rho(1, 1.5) == 0.75);
  CHECK(profile.rho(1, 2.0) == 1.0);
  CHECK(profile.rho(2, 1.0) == 0.0);
  CHECK(profile.rho(2, 2.0) == 0.25);
  CHECK(profile.rho(2, 2.5) == 0.25);
  CHECK(profile.rho(2, 3.0) == 0.5);
  CHECK(profile.rho(2, 1e300) == 0.5);
  CHECK(profile.failures(0) == 1);
  CHECK(profile.failures(1) == 0);
  CHECK(profile.failures(2) == 2);
  CHECK(profile.max_ratio() == 4.0);
}

TEST_CASE("a problem every solver fails counts against all; ties are best for each") {
  // Problem 1: both fail. Problem 2: a tie at 5, ratio 1 for both.
  const PerformanceProfile profile({{kInf, 5.0}, {kInf, 5.0}});
  CHECK(profile.ratio(0, 0) == kInf);
  CHECK(profile.rho(0, 1.0) == 0.5);
  CHECK(profile.rho(1, 1.0) == 0.5);
  CHECK(profile.rho(1, 1e300) == 0.5);
  CHECK(profile.rho(1, kInf) == 0.5);
  CHECK(profile.failures(1) == 1);
  CHECK(profile.max_ratio() == 1.0);
  // No problems at all: rho is 0.
  const PerformanceProfile empty({{}, {}});
  CHECK(empty.problems() == 0);
  CHECK(empty.rho(0, 2.0) == 0.0);
}

TEST_CASE("a cost that is not > 0, and rows of different lengths, are refused") {
  CHECK_THROWS_WITH_AS(PerformanceProfile({{1.0, 0.0}}), doctest::Contains("cost[0][1]"),
                       std::invalid_argument);
  CHECK_THROWS_AS(PerformanceProfile({{1.0, std::nan("")}}), std::invalid_argument);
  CHECK_THROWS_WITH_AS(PerformanceProfile({{1.0, 2.0}, {1.0}}), doctest::Contains("solver 1"),
                       std::invalid_argument);
}

}  // namespace nsb::benchmarks
