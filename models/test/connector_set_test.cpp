// Connectors in an assembly (models/connector_set.hpp): a restrainer cable between a deck
// end and a prescribed seat and across two bodies, and a bearing to the ground, by hand;
// tension only; input errors naming the part.
#include "models/assembly.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace {

using nsb::models::Assembly;
namespace parts = nsb::models::parts;
namespace connectors = nsb::models::connectors;
namespace ni = nsb::integrators;

// Forces of O(10 kN) from a few products: round-off ~ 1e-13.
constexpr double kForceTol = 1e-10;

parts::RigidBody deck(double x) {
  parts::RigidBody b{.mass = 10.0, .inertia = 100.0, .length = 10.0, .width = 2.0};
  b.rest = Eigen::Vector3d(x, 0.0, 0.0);
  return b;
}

ni::Vector vec3(double x, double y, double theta) {
  ni::Vector v(3);
  v << x, y, theta;
  return v;
}

}  // namespace

TEST_CASE("restrainer to a prescribed seat: tension along the cable, torque r x F") {
  // Deck of L = 10 m centred at 0; seat frame origin at (-6, 0); cable from the deck's anchor
  // (-4.5, 0) (body frame) to the seat's anchor (-0.5, 0) (seat frame): at rest it runs from
  // (-4.5, 0) to (-6.5, 0), L0 = 2 m. k = 100 kN/m, slack 0.01 m, no yield.
  Assembly::Parts p;
  p.bodies = {deck(0.0)};
  p.prescribed.resize(1);
  p.prescribed[0].reference = Eigen::Vector2d(-6.0, 0.0);
  p.restrainers = {{.body = 0, .anchor = Eigen::Vector2d(-4.5, 0.0),
                    .other = parts::Obstacle::kPrescribed, .other_index = 0,
                    .other_anchor = Eigen::Vector2d(-0.5, 0.0),
                    .cable = {.stiffness = 100.0, .slack = 0.01, .yield_force = 0.0}}};
  Assembly a(p);
  ni::Vector f(3);
  // q = (0.11, 0, 0): length 2.11, elongation 0.11, stretch 0.10, F = 10 kN pulling the deck
  // back to -x: f = (-10, 0, 0) (the anchor is on the axis: no torque).
  a.forces(0.0, vec3(0.11, 0.0, 0.0), ni::Vector::Zero(3), f);
  CHECK(f(0) == doctest::Approx(-10.0).epsilon(kForceTol));
  CHECK(std::abs(f(1)) < kForceTol);
  CHECK(std::abs(f(2)) < kForceTol);
  // Stored F^2 / 2k = 100 / 200 = 0.5 kJ.
  CHECK(a.energy(0.0, ni::Vector::Zero(3)).stored == doctest::Approx(0.5).epsilon(kForceTol));
  // q = (-0.5, 0, 0): the anchors closer than at rest, no force (tension only).
  a.forces(0.0, vec3(-0.5, 0.0, 0.0), ni::Vector::Zero(3), f);
  CHECK(f.norm() == 0.0);
  // q = (0, 0.3, 0): length sqrt(2^2 + 0.3^2) = 2.022375, stretch 0.012375, F = 1.237484 kN
  // along e = (2, 0.3) / 2.022375 = (0.988936, 0.148340); f = -F e = (-1.223793,
  // -0.183567, .); torque -F (r x e) with r = (-4.5, 0): 1.237484 * 4.5 * 0.148340
  // = +0.826060 kN m.
  a.forces(0.0, vec3(0.0, 0.3, 0.0), ni::Vector::Zero(3), f);
  const double len = std::sqrt(4.0 + 0.09), tension = 100.0 * (len - 2.0 - 0.01);
  CHECK(f(0) == doctest::Approx(-tension * 2.0 / len).epsilon(kForceTol));
  CHECK(f(1) == doctest::Approx(-tension * 0.3 / len).epsilon(kForceTol));
  CHECK(f(2) == doctest::Approx(tension * 4.5 * 0.3 / len).epsilon(kForceTol));
  CHECK(f(0) == doctest::Approx(-1.223793).epsilon(1e-6));
  CHECK(f(2) == doctest::Approx(0.826060).epsilon(1e-6));
}

TEST_CASE("restrainer across two bodies: equal and opposite; bearing to the ground") {
  // Bodies at rest centres -5.5 and +5.5 (L = 10, hinge gap 1 m); anchors at the facing
  // ends, L0 = 1 m; k = 200 kN/m, no slack. Body 1 moved by +0.05: F = 10 kN, body 0 pulled
  // to +x, body 1 to -x.
  Assembly::Parts p;
  p.bodies = {deck(-5.5), deck(5.5)};
  p.restrainers = {{.body = 0, .anchor = Eigen::Vector2d(5.0, 0.0),
                    .other = parts::Obstacle::kBody, .other_index = 1,
                    .other_anchor = Eigen::Vector2d(-5.0, 0.0),
                    .cable = {.stiffness = 200.0, .slack = 0.0, .yield_force = 0.0}}};
  // Bearing on body 0 at s = 2 m: linear 1000 kN/m in x and y, fixed ground.
  p.links = {{.body = 0, .position = 2.0,
              .longitudinal = connectors::LawParameters::linear(1000.0),
              .transverse = connectors::LawParameters::linear(1000.0),
              .ground_longitudinal = nullptr, .ground_transverse = nullptr}};
  Assembly a(p);
  ni::Vector q = ni::Vector::Zero(6), f(6);
  q(3) = 0.05;
  a.forces(0.0, q, ni::Vector::Zero(6), f);
  CHECK(f(0) == doctest::Approx(10.0).epsilon(kForceTol));
  CHECK(f(3) == doctest::Approx(-10.0).epsilon(kForceTol));
  // Bearing: body 0 at (0, 0.01, 0.001): y at the bearing 0.01 + 2 * 0.001 = 0.012 m,
  // F_y = 12 kN: f_y = -12, f_theta = -2 * 12 = -24, plus the cable's: its anchors are now
  // p_a = (-5.5 + 5 cos 0.001, 0.01 + 5 sin 0.001) and p_b = (0.5, 0), tension
  // 200 (|p_a - p_b| - 1) along e = (p_a - p_b) / |p_a - p_b|, on body 0 -T (e, r_a x e).
  q.setZero();
  q(1) = 0.01;
  q(2) = 0.001;
  a.forces(0.0, q, ni::Vector::Zero(6), f);
  const Eigen::Vector2d r_a(5.0 * std::cos(0.001), 5.0 * std::sin(0.001));
  const Eigen::Vector2d d = Eigen::Vector2d(-5.5, 0.01) + r_a - Eigen::Vector2d(0.5, 0.0);
  const double t = 200.0 * (d.norm() - 1.0);
  const Eigen::Vector2d e = d / d.norm();
  CHECK(f(1) == doctest::Approx(-12.0 - t * e.y()).epsilon(kForceTol));
  CHECK(f(2) == doctest::Approx(-24.0 - t * (r_a.x() * e.y() - r_a.y() * e.x()))
                    .epsilon(kForceTol));
  // Stored: 1/2 * 1000 * 0.012^2 = 0.072 kJ in the bearing, T^2 / 400 in the cable.
  CHECK(a.energy(0.0, q).stored == doctest::Approx(0.072 + t * t / 400.0).epsilon(kForceTol));
}

TEST_CASE("connectors: bad parameters name the part and field") {
  Assembly::Parts p;
  p.bodies = {deck(0.0)};
  p.links = {{.body = 0, .position = 9.0,
              .longitudinal = connectors::LawParameters::linear(1000.0),
              .transverse = connectors::LawParameters::linear(1000.0),
              .ground_longitudinal = nullptr, .ground_transverse = nullptr}};
  CHECK_THROWS_WITH_AS(Assembly{p}, doctest::Contains("links[0].position"),
                       std::invalid_argument);
  p.links[0].position = 0.0;
  p.links[0].transverse = connectors::LawParameters::bilinear(1000.0, 0.0, 0.1);
  CHECK_THROWS_WITH_AS(Assembly{p}, doctest::Contains("links[0].transverse.yield_force"),
                       std::invalid_argument);
  p.links.clear();
  p.restrainers.resize(1);  // anchored on prescribed body 0, which does not exist
  CHECK_THROWS_WITH_AS(Assembly{p}, doctest::Contains("restrainers[0].other_index"),
                       std::invalid_argument);
}
