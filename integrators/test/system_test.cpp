#include "integrators/system.hpp"

#include <doctest/doctest.h>

#include <limits>
#include <stdexcept>
#include <string>

namespace {

using nsb::integrators::ContactData;
using nsb::integrators::Matrix;
using nsb::integrators::Vector;

// A contact-free system whose mass and initial state the test sets freely.
class Free final : public nsb::integrators::System {
 public:
  Matrix m = Matrix::Identity(2, 2);
  Vector q0 = Vector::Zero(2);
  Vector u0 = Vector::Zero(2);

  int dofs() const override { return 2; }
  std::vector<std::string> coordinate_names() const override { return {"a", "b"}; }
  std::vector<std::string> velocity_names() const override { return {"va", "vb"}; }
  const Matrix& mass() const override { return m; }
  Vector initial_position() const override { return q0; }
  Vector initial_velocity() const override { return u0; }
  void forces(double, const Vector&, const Vector&, Vector& f) override { f.setZero(); }
  void tangent(double, const Vector&, const Vector&, Matrix& K, Matrix& C) override {
    K.setZero();
    C.setZero();
  }
  int contacts() const override { return 0; }
  void contact_data(double, const Vector&, const Vector&, std::vector<ContactData>&) const override {}
  nsb::integrators::PowerTerms power(double, const Vector&, const Vector&) const override {
    return {};
  }
  nsb::integrators::EnergyState energy(double, const Vector&) const override { return {}; }
};

// The message of the std::invalid_argument that f throws, or "" if it throws none.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("checked_inverse_mass returns M^-1 of a valid system") {
  Free s;
  s.m << 4.0, 1.0, 1.0, 2.0;
  // Hand inverse of [[4, 1], [1, 2]]: det = 7, inverse = [[2, -1], [-1, 4]] / 7.
  const Matrix inv = nsb::integrators::checked_inverse_mass(s, "test");
  CHECK(inv(0, 0) == doctest::Approx(2.0 / 7.0));
  CHECK(inv(0, 1) == doctest::Approx(-1.0 / 7.0));
  CHECK(inv(1, 0) == doctest::Approx(-1.0 / 7.0));
  CHECK(inv(1, 1) == doctest::Approx(4.0 / 7.0));
}

TEST_CASE("checked_inverse_mass names the method and what is wrong") {
  Free s;
  const auto check = [&](const char* what) {
    const std::string msg =
        error_of([&] { nsb::integrators::checked_inverse_mass(s, "moreau_jean"); });
    CHECK(msg.rfind("moreau_jean: ", 0) == 0);
    CHECK(msg.find(what) != std::string::npos);
  };
  s.m << 1.0, 0.5, 0.0, 1.0;
  check("not symmetric");
  s.m << 1.0, 2.0, 2.0, 1.0;  // eigenvalues 3 and -1
  check("not positive definite");
  s.m(0, 0) = std::numeric_limits<double>::quiet_NaN();
  check("non-finite");
  s.m = Matrix::Identity(3, 3);
  check("dofs() x dofs()");
  s.m = Matrix::Identity(2, 2);
  s.q0 = Vector::Zero(3);
  check("not of size dofs()");
  s.q0 = Vector::Zero(2);
  s.u0(1) = std::numeric_limits<double>::infinity();
  check("initial state");
}
