// Enumeration: the oracle itself checked on hand-solved problems and its limits.
#include "lcp/enumeration.hpp"
#include "lcp/test/problems.hpp"

#include <doctest/doctest.h>

#include <random>

using namespace nsb::lcp;

TEST_CASE("hand-solved problems") {
  Problem p;
  p.M = (Matrix(2, 2) << 2, 1, 1, 2).finished();
  p.q = (Vector(2) << -5, -6).finished();
  const Result r = enumerate(p);
  REQUIRE(r.ok());
  CHECK(r.z(0) == doctest::Approx(4.0 / 3.0).epsilon(1e-14));
  CHECK(r.z(1) == doctest::Approx(7.0 / 3.0).epsilon(1e-14));

  // Singular block: M = [1 1; 1 1], q = (-1, -1). Every z >= 0 with z_1 + z_2 = 1 solves it
  // (w = 0); the first support by size, {1}, gives z = (1, 0).
  p.M = Matrix::Ones(2, 2);
  p.q = -Vector::Ones(2);
  const Result s = enumerate(p);
  REQUIRE(s.ok());
  CHECK(s.z.sum() == doctest::Approx(1.0).epsilon(1e-14));
  CHECK(s.w.lpNorm<Eigen::Infinity>() < 1e-14);
}

TEST_CASE("no solution and too large") {
  Problem p;
  p.M = -Matrix::Identity(3, 3);
  p.q = -Vector::Ones(3);
  const Result r = enumerate(p);
  CHECK(r.status == Status::kNoSolution);
  CHECK(r.iterations == 8);  // all 2^3 supports were tried
  Problem big;
  big.M = Matrix::Identity(13, 13);
  big.q = Vector::Ones(13);
  CHECK(enumerate(big).status == Status::kTooLarge);
  EnumerationOptions o;
  o.max_size = 13;
  CHECK(enumerate(big, o).ok());
  o.max_size = 21;
  CHECK_THROWS_WITH_AS(enumerate(big, o), doctest::Contains("max_size"), std::invalid_argument);
}

TEST_CASE("manufactured P-matrix problems: the unique solution is found") {
  std::mt19937 rng(77);
  for (int trial = 0; trial < 60; ++trial) {
    const auto m = testing::manufacture(rng, testing::p_matrix(rng, 1 + trial % 10), 0.2);
    const Result r = enumerate(m.problem);
    REQUIRE(r.ok());
    CHECK(testing::relative_distance(r.z, m.z) < 1e-10);
  }
}

TEST_CASE("edges: n = 0 and q >= 0 need only the empty support") {
  Problem empty;
  CHECK(enumerate(empty).ok());
  Problem p;
  p.M = -Matrix::Identity(2, 2);
  p.q = Vector::Ones(2);
  const Result r = enumerate(p);
  CHECK(r.ok());
  CHECK(r.iterations == 1);
}
