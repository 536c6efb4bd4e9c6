// Tests of the shared LCP types: validation, the residual and Siconos's error measure.
#include "lcp/lcp.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

using namespace nsb::lcp;

namespace {
// Hand-computed values below are exact in binary up to one rounding of a square root.
constexpr double kExact = 1e-15;
}  // namespace

TEST_CASE("residual: hand-computed natural map") {
  // M = I, q = (-1, 2), z = (0.5, 1): w = z + q = (-0.5, 3);
  // min(z, w) = (-0.5, 1), ||.||_inf = 1, 1 + ||q||_inf = 3, so r = 1/3.
  const Matrix M = Matrix::Identity(2, 2);
  const Vector q = (Vector(2) << -1.0, 2.0).finished();
  const Vector z = (Vector(2) << 0.5, 1.0).finished();
  CHECK(residual(M, q, z) == doctest::Approx(1.0 / 3.0).epsilon(kExact));
  // Siconos: z - max(0, z - w) = (0.5 - 1, 1 - 0) = (-0.5, 1): norm sqrt(1.25), ||q|| = sqrt(5).
  CHECK(siconos_error(M, q, z) == doctest::Approx(std::sqrt(1.25 / 5.0)).epsilon(kExact));
  // The solution z = (1, 0): w = (0, 2), both measures vanish.
  const Vector s = (Vector(2) << 1.0, 0.0).finished();
  CHECK(residual(M, q, s) == 0.0);
  CHECK(siconos_error(M, q, s) == 0.0);
}

TEST_CASE("residual: NaN iterate is infinitely bad, q = 0 divides by one") {
  const Matrix M = Matrix::Identity(2, 2);
  Vector z = Vector::Zero(2);
  z(1) = std::numeric_limits<double>::quiet_NaN();
  CHECK(std::isinf(residual(M, Vector::Zero(2), z)));
  CHECK(std::isinf(siconos_error(M, Vector::Zero(2), z)));
  // q = 0, z = (1, 0): w = (1, 0), min = (1, 0), r = 1; Siconos: z - max(0, z - w) = (1, 0).
  const Vector z2 = (Vector(2) << 1.0, 0.0).finished();
  CHECK(residual(M, Vector::Zero(2), z2) == 1.0);
  CHECK(siconos_error(M, Vector::Zero(2), z2) == 1.0);
}

TEST_CASE("Problem::validate names the offending entry") {
  Problem p;
  p.M = Matrix::Identity(2, 2);
  p.q = Vector::Zero(3);
  CHECK_THROWS_WITH_AS(p.validate(), doctest::Contains("2 x 2"), std::invalid_argument);
  p.q = Vector::Zero(2);
  p.M(1, 0) = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH_AS(p.validate(), doctest::Contains("M(1, 0)"), std::invalid_argument);
  p.M(1, 0) = 0.0;
  p.q(1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH_AS(p.validate(), doctest::Contains("q(1)"), std::invalid_argument);
  Problem empty;
  CHECK_NOTHROW(empty.validate());
}

TEST_CASE("evaluate fills w and both measures; a wrong-size z is infinitely bad") {
  Problem p;
  p.M = (Matrix(2, 2) << 2.0, 1.0, 1.0, 2.0).finished();
  p.q = (Vector(2) << -5.0, -6.0).finished();
  Result r;
  r.z = (Vector(2) << 4.0 / 3.0, 7.0 / 3.0).finished();
  evaluate(p, r);
  CHECK(r.w.lpNorm<Eigen::Infinity>() < 1e-14);
  CHECK(r.residual < 1e-15);
  r.z = Vector::Zero(1);
  evaluate(p, r);
  CHECK(std::isinf(r.residual));
}

TEST_CASE("every status has a distinct name") {
  CHECK(to_string(Status::kSolved) == "solved");
  CHECK(to_string(Status::kRayTermination) == "ray_termination");
  CHECK(to_string(Status::kZeroDiagonal) == "zero_diagonal");
  CHECK(to_string(Status::kMaxIterations) != to_string(Status::kNotRun));
}
