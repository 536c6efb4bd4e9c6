#include "integrators/system.hpp"
#include "testsupport/systems.hpp"

#include <doctest/doctest.h>

#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using nsb::integrators::ContactData;
using nsb::integrators::Matrix;
using nsb::integrators::Vector;

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
  nsb::testsupport::FreeMass s(2);
  Matrix m(2, 2);
  m << 4.0, 1.0, 1.0, 2.0;
  s.set_mass(m);
  // Hand inverse of [[4, 1], [1, 2]]: det = 7, inverse = [[2, -1], [-1, 4]] / 7.
  const Matrix inv = nsb::integrators::checked_inverse_mass(s, "test");
  CHECK(inv(0, 0) == doctest::Approx(2.0 / 7.0));
  CHECK(inv(0, 1) == doctest::Approx(-1.0 / 7.0));
  CHECK(inv(1, 0) == doctest::Approx(-1.0 / 7.0));
  CHECK(inv(1, 1) == doctest::Approx(4.0 / 7.0));
}

TEST_CASE("checked_inverse_mass names the method and what is wrong") {
  nsb::testsupport::FreeMass s(2);
  Matrix m(2, 2);
  Vector q0 = Vector::Zero(2), u0 = Vector::Zero(2);
  const auto check = [&](const char* what) {
    s.set_mass(m);
    s.set_initial_state(q0, u0);
    const std::string msg =
        error_of([&] { nsb::integrators::checked_inverse_mass(s, "moreau_jean"); });
    CHECK(msg.rfind("moreau_jean: ", 0) == 0);
    CHECK(msg.find(what) != std::string::npos);
  };
  m << 1.0, 0.5, 0.0, 1.0;
  check("not symmetric");
  m << 1.0, 2.0, 2.0, 1.0;  // eigenvalues 3 and -1
  check("not positive definite");
  m(0, 0) = std::numeric_limits<double>::quiet_NaN();
  check("non-finite");
  m = Matrix::Identity(3, 3);
  check("dofs() x dofs()");
  m = Matrix::Identity(2, 2);
  q0 = Vector::Zero(3);
  check("not of size dofs()");
  q0 = Vector::Zero(2);
  u0(1) = std::numeric_limits<double>::infinity();
  check("initial state");
}

// A system that does not override contact_normals() gets contact_data(): every field the
// same, so an integrator may ask for the normal part of any system.
TEST_CASE("contact_normals defaults to contact_data") {
  nsb::testsupport::TwoCornerBody::Parameters p;
  p.friction = 0.3;
  p.restitution = 0.5;
  p.initial_position << 0.0, 0.5, 0.2;
  const nsb::testsupport::TwoCornerBody s(p);
  auto full = s.make_contact_buffer(), normal = s.make_contact_buffer();
  for (double t : {0.0, 0.7}) {
    Vector q(3), u(3);
    q << 0.1, 0.4 + t, -0.3;
    u << 1.0, -2.0, 0.5;
    s.contact_data(t, q, u, full);
    s.contact_normals(t, q, u, normal);
    REQUIRE(normal.size() == full.size());
    for (std::size_t i = 0; i < full.size(); ++i) {
      CHECK(normal[i].gap_normal == full[i].gap_normal);
      CHECK(normal[i].w_normal == full[i].w_normal);
      CHECK(normal[i].w_tangent == full[i].w_tangent);
      CHECK(normal[i].what_normal == full[i].what_normal);
      CHECK(normal[i].wbar_normal == full[i].wbar_normal);
      CHECK(normal[i].restitution == full[i].restitution);
      CHECK(normal[i].friction == full[i].friction);
      CHECK(normal[i].far == full[i].far);
    }
  }
}

TEST_CASE("natural_periods: 2 pi / omega of K phi = omega^2 M phi, longest first") {
  // Two masses on their own springs, uncoupled: omega^2 = k / m for each.
  // m = 2 t, k = 8 kN/m: omega^2 = 4, T = pi s; m = 1 t, k = 100 kN/m: omega^2 = 100, T = pi / 5 s.
  nsb::testsupport::TwoMasses::Parameters p;
  p.mass1 = 1.0;
  p.stiffness1 = 100.0;
  p.mass2 = 2.0;
  p.stiffness2 = 8.0;
  nsb::testsupport::TwoMasses s(p);
  const std::vector<double> t = nsb::integrators::natural_periods(s);
  REQUIRE(t.size() == 2);
  const double pi = 3.14159265358979323846;
  CHECK(t[0] == doctest::Approx(pi).epsilon(1e-14));
  CHECK(t[1] == doctest::Approx(pi / 5).epsilon(1e-14));
  // No stiffness: every mode is a mechanism, of infinite period.
  nsb::testsupport::FreeMass free(2);
  for (const double period : nsb::integrators::natural_periods(free)) {
    CHECK(period == std::numeric_limits<double>::infinity());
  }
}
