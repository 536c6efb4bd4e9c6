// The assembly of parts (models/assembly.hpp): the bent force law along a hand-derived
// elastic path, its tangent against finite differences, Rayleigh damping on the assembled
// M and K0, the normal contact data against the full ones, and input errors naming the part.
#include "models/assembly.hpp"

#include "models/bridge_parts.hpp"
#include "models/rayleigh.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

namespace {

using nsb::models::Assembly;
namespace parts = nsb::models::parts;
namespace ni = nsb::integrators;

// Bent: yield at 0.01 m and 100 kN (k0 = 1e4 kN/m); the paths below stay elastic.
constexpr double kYieldForce = 100.0, kYieldDisplacement = 0.01;
constexpr double kK0 = kYieldForce / kYieldDisplacement;
// Forces of O(100 kN) from a few products: round-off ~ 1e-13.
constexpr double kForceTol = 1e-10;

parts::RigidBody deck() {
  return {.mass = 140.5, .inertia = 13090.0, .length = 33.53, .width = 2.44};
}

parts::Bent bent(double position) {
  const auto t = nsb::models::takeda::Parameters::bilinear(kYieldForce, kYieldDisplacement);
  return {.body = 0, .position = position, .longitudinal = t, .transverse = t,
          .ground_longitudinal = nullptr, .ground_transverse = nullptr};
}

// One deck on two bents at -+8 m, without contacts.
Assembly::Parts on_bents() {
  Assembly::Parts p;
  p.bodies = {deck()};
  p.bents = {bent(-8.0), bent(8.0)};
  return p;
}

std::string error_of(const Assembly::Parts& p) {
  try {
    Assembly a(p);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

}  // namespace

TEST_CASE("bents: elastic forces and torques by hand, stored energy 1/2 k d^2") {
  // At q = (dx, dy, theta): bent j at s_j sees dx and dy + s_j theta, so
  //   f_x = -2 k dx,  f_y = -k (2 dy + (s_1 + s_2) theta),
  //   f_theta = -k sum_j s_j (dy + s_j theta).
  // With s = -+8: f_y = -2 k dy, f_theta = -k 128 theta.
  Assembly a(on_bents());
  const Eigen::Vector3d q(0.002, -0.003, 1e-4);
  Eigen::VectorXd f(3);
  a.forces(0.0, q, Eigen::Vector3d::Zero(), f);
  CHECK(std::abs(f(0) + 2 * kK0 * 0.002) < kForceTol);
  CHECK(std::abs(f(1) - 2 * kK0 * 0.003) < kForceTol);
  CHECK(std::abs(f(2) + kK0 * 128.0 * 1e-4) < kForceTol);
  CHECK(a.bent_force_transverse(0) == doctest::Approx(kK0 * (-0.003 - 8.0 * 1e-4)));
  const double d0 = -0.003 - 8e-4, d1 = -0.003 + 8e-4;
  const double stored = 0.5 * kK0 * (2 * 0.002 * 0.002 + d0 * d0 + d1 * d1);
  CHECK(a.energy(0.0, q).stored == doctest::Approx(stored).epsilon(1e-12));
  // dissipated = work - stored: zero on the elastic branch, up to round-off of the work.
  CHECK(std::abs(a.energy(0.0, q).hysteretic) <= 1e-12 * stored);
  CHECK(!a.tangent_changed());
}

TEST_CASE("bents: the tangent is -df/dq (finite differences on the elastic branch)") {
  Assembly a(on_bents());
  const Eigen::Vector3d q(0.001, 0.002, -5e-5);
  Eigen::MatrixXd K(3, 3), C(3, 3);
  Eigen::VectorXd fp(3), fm(3);
  a.forces(0.0, q, Eigen::Vector3d::Zero(), fp);
  a.tangent(0.0, q, Eigen::Vector3d::Zero(), K, C);
  constexpr double h = 1e-7;  // linear branch: only round-off, ~1e-16 * 1e2 / 1e-7
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(i);
    a.forces(0.0, q + e, Eigen::Vector3d::Zero(), fp);
    a.forces(0.0, q - e, Eigen::Vector3d::Zero(), fm);
    const Eigen::VectorXd column = -(fp - fm) / (2 * h);
    CHECK((column - K.col(i)).norm() <= 1e-6 * K.norm());
  }
  CHECK(C.isZero());  // no damping part
}

TEST_CASE("Rayleigh damping on the assembled M and K0 gives the two modal ratios") {
  auto p = on_bents();
  p.damping = parts::RayleighParts{.ratio_i = 0.05, .ratio_j = 0.08, .mode_i = 1, .mode_j = 3};
  Assembly a(p);
  const Eigen::VectorXd zeta =
      nsb::models::modal_damping_ratios(a.mass(), a.initial_stiffness(), a.damping_matrix());
  CHECK(zeta(0) == doctest::Approx(0.05).epsilon(1e-10));
  CHECK(zeta(2) == doctest::Approx(0.08).epsilon(1e-10));
  // f_D = -C u without support motion.
  const Eigen::Vector3d u(0.1, -0.2, 0.01);
  Eigen::VectorXd f(3);
  a.forces(0.0, Eigen::Vector3d::Zero(), u, f);
  CHECK((f + a.damping_matrix() * u).norm() < 1e-12 * (a.damping_matrix() * u).norm());
  CHECK(a.power(0.0, Eigen::Vector3d::Zero(), u).damping ==
        doctest::Approx(u.dot(a.damping_matrix() * u)));
}

TEST_CASE("contact_normals gives contact_data's normal fields, moving seats and body faces") {
  // The benchmark bridge from parts under a support motion, plus the fields at a body face
  // (tests of models/deck_chain.hpp cover hinges in runs).
  nsb::models::Record r{.t = {0.0, 0.5, 1.0, 1.5}, .a = {0.0, 3.0, -2.0, 0.0}, .source = "test"};
  nsb::models::GroundMotionOptions o;
  o.baseline_correction = false;
  const auto m = std::make_shared<const nsb::models::GroundMotion>(r, o);
  nsb::models::BridgeDesign design = nsb::models::BridgeDesign::benchmark();
  design.excitation.seats[0] = {.longitudinal = m, .transverse = m, .rotation = nullptr};
  design.excitation.seats[1] = {.longitudinal = m, .transverse = nullptr, .rotation = m};
  Assembly a(nsb::models::bridge_parts(design));
  const Eigen::Vector3d q(0.003, -0.01, 2e-4), u(0.2, 0.1, -0.01);
  auto full = a.make_contact_buffer(), normal = a.make_contact_buffer();
  a.contact_data(0.8, q, u, full);
  a.contact_normals(0.8, q, u, normal);
  for (std::size_t i = 0; i < full.size(); ++i) {
    INFO("contact ", i);
    CHECK(normal[i].gap_normal == full[i].gap_normal);
    CHECK(normal[i].w_normal == full[i].w_normal);
    CHECK(normal[i].what_normal == full[i].what_normal);
    CHECK(normal[i].far == full[i].far);
    CHECK(full[i].what_normal != 0.0);  // the seats move
  }
}

TEST_CASE("bad parts are rejected naming the part and field") {
  auto p = on_bents();
  p.bents[1].body = 1;
  CHECK(error_of(p) == "bents[1].body: must name one of the bodies");
  p = on_bents();
  p.bents[0].position = 20.0;
  CHECK(error_of(p) == "bents[0].position: must lie on the body, |s| <= L/2 [m]");
  p = on_bents();
  p.bents[0].transverse.d_yield = -1.0;
  CHECK(error_of(p).find("bents[0].transverse.") == 0);
  p = on_bents();
  p.bodies[0].mass = 0.0;
  CHECK(error_of(p) == "bodies[0].mass: must be > 0 [t]");
  p = on_bents();
  p.contacts = {{.body = 0, .corner = 0, .obstacle = parts::Obstacle::kBody,
                 .obstacle_index = 0, .face = {}, .restitution = 0.0, .friction = 0.0,
                 .family = "", .name = ""}};
  CHECK(error_of(p) == "contacts[0].obstacle_index: must be another body than the corner's");
  p.contacts[0].obstacle = parts::Obstacle::kPrescribed;
  CHECK(error_of(p) ==
        "contacts[0].obstacle_index: must name one of the prescribed bodies");
  p.prescribed.resize(1);
  p.contacts[0].corner = 4;
  CHECK(error_of(p) == "contacts[0].corner: must be 0, 1, 2 or 3");
  p.contacts[0].corner = 0;
  p.contacts[0].face.normal = {1.0, 1.0};
  CHECK(error_of(p) == "contacts[0].face.normal: must be a unit vector");
  // A face through (-20, 0) facing +x: the corner at -16.77 is 3.2 m off it; facing -x it
  // penetrates.
  p.contacts[0].face = {.point = {-20.0, 0.0}, .normal = {-1.0, 0.0}};
  CHECK(error_of(p).find("contacts[0]: initial penetration") == 0);
  p = on_bents();
  p.damping = parts::RayleighParts{.ratio_i = 0.05, .ratio_j = 0.05, .mode_i = 2, .mode_j = 2};
  CHECK(error_of(p).find("damping: ") == 0);
}

TEST_CASE("bents: a push past yield follows the backbone, and the tangent drops to r k") {
  // Bilinear Takeda (models/takeda.hpp): beyond d_y the backbone is F = f_y + r k (d - d_y),
  // r = 0.05. Both bents see dx = 2 d_y: F = 100 + 0.05 * 1e4 * 0.01 = 105 kN each.
  Assembly a(on_bents());
  Eigen::VectorXd f(3);
  a.forces(0.0, Eigen::Vector3d(2 * kYieldDisplacement, 0.0, 0.0), Eigen::Vector3d::Zero(), f);
  CHECK(f(0) == doctest::Approx(-2 * 105.0).epsilon(1e-12));
  CHECK(a.tangent_changed());
  Eigen::MatrixXd K(3, 3), C(3, 3);
  a.tangent(0.0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), K, C);
  CHECK(K(0, 0) == doctest::Approx(2 * 0.05 * kK0).epsilon(1e-12));
  a.revert();  // back to the committed elastic state
  CHECK(!a.tangent_changed());
}

TEST_CASE("a prescribed body is posed at its reference plus its support motion") {
  nsb::models::Record r{.t = {0.0, 0.5, 1.0, 1.5}, .a = {0.0, 3.0, -2.0, 0.0}, .source = "test"};
  nsb::models::GroundMotionOptions o;
  o.baseline_correction = false;
  const auto m = std::make_shared<const nsb::models::GroundMotion>(r, o);
  auto p = on_bents();
  p.prescribed = {{.reference = {1.0, 2.0}, .longitudinal = m, .transverse = nullptr,
                   .rotation = m}};
  Assembly a(p);
  const auto g = m->values(0.6);
  const auto pose = a.prescribed_motion(0, 0.6);
  CHECK(pose.position == Eigen::Vector3d(1.0 + g.displacement, 2.0, g.displacement));
  CHECK(pose.velocity == Eigen::Vector3d(g.velocity, 0.0, g.velocity));
  CHECK(pose.acceleration == Eigen::Vector3d(g.acceleration, 0.0, g.acceleration));
}
