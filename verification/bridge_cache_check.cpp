// The assembly evaluates each distinct ground motion once per distinct time and keeps the
// values (parts::MotionTable, models/assembly.hpp). This checks that the kept values never leak into another time: on the
// benchmark bridge of excitation 7 (records shared by several supports), a bridge queried at
// times out of order, repeated, before the record and after its end gives
//  - seat poses and the quasi-static velocity equal to those computed directly from the
//    GroundMotion objects and the definition us = K0^-1 sum_j k0_j b_j u_g,j (Chopra,
//    Dynamics of Structures, sec. 9.7), and
//  - forces, contact data and powers identical to those of a fresh bridge (same design and
//    motions) that is asked at that time only.
#include "models/assembly.hpp"
#include "models/bridge_parts.hpp"
#include "scene/scene.hpp"

#include <doctest/doctest.h>

#include <Eigen/Cholesky>

#include <cmath>
#include <string>
#include <vector>

namespace {

using nsb::integrators::ContactData;
using nsb::integrators::Vector;
using nsb::models::Assembly;
using nsb::models::BridgeDesign;
using nsb::models::bridge_parts;

// us from K0^-1 by another factorization than the bridge's: round-off of a 3x3 solve with
// entries up to 1e6 kN/m, relative.
constexpr double kSolveTol = 1e-10;

// Times [s] out of order, repeated, before the record (negative), and after its end (30 s;
// the compressed record lasts 22 s).
const std::vector<double> kTimes = {3.0, 3.0, 7.25, 3.0, -1.0, 0.0, 30.0, 7.25, 5.5, 3.0};

Eigen::Vector3d direct_quasi_static_velocity(const BridgeDesign& d, const Assembly& b,
                                             double t) {
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  const auto& bents = d.bents;
  for (std::size_t j = 0; j < bents.size(); ++j) {
    const auto& m = d.excitation.bents[j];
    const double vx = m.longitudinal ? m.longitudinal->velocity(t) : 0.0;
    const double vy = m.transverse ? m.transverse->velocity(t) : 0.0;
    rhs += bents[j].longitudinal.k0 * vx * Eigen::Vector3d::UnitX() +
           bents[j].transverse.k0 * vy * Eigen::Vector3d(0.0, 1.0, bents[j].position);
  }
  const Eigen::Matrix3d k0 = b.initial_stiffness();
  return k0.llt().solve(rhs);
}

void check_same_contacts(const std::vector<ContactData>& a, const std::vector<ContactData>& b) {
  REQUIRE(a.size() == b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    CHECK(a[i].gap_normal == b[i].gap_normal);
    CHECK(a[i].w_normal == b[i].w_normal);
    CHECK(a[i].w_tangent == b[i].w_tangent);
    CHECK(a[i].what_normal == b[i].what_normal);
    CHECK(a[i].what_tangent == b[i].what_tangent);
    CHECK(a[i].wbar_normal == b[i].wbar_normal);
    CHECK(a[i].wbar_tangent == b[i].wbar_tangent);
    CHECK(a[i].far == b[i].far);
  }
}

}  // namespace

TEST_CASE("bridge: support motions kept per time never leak into another time") {
  const auto scene =
      nsb::scene::load_scene(std::string(NSB_SCENES_DIR) + "/bridge-exc7.toml");
  REQUIRE(scene.design.has_value());
  const BridgeDesign& design = *scene.design;
  // The benchmark's supports share records: the case the per-time values are kept for.
  REQUIRE(design.excitation.bents.size() == 3);
  REQUIRE(design.excitation.bents[0].longitudinal == design.excitation.seats[0].longitudinal);
  Assembly built(bridge_parts(design));
  Assembly* bridge = &built;

  // A deck displaced and moving, so that every term of the forces and contacts is non-zero.
  const Vector q = Eigen::Vector3d(0.004, -0.003, 2e-4);
  const Vector u = Eigen::Vector3d(0.05, -0.02, 1e-3);
  Vector f(3), f_fresh(3);
  std::vector<ContactData> c = bridge->make_contact_buffer(), c_fresh = c;

  for (double t : kTimes) {
    CAPTURE(t);
    // Seat poses against the GroundMotion objects themselves.
    for (int a = 0; a < 2; ++a) {
      const auto& s = design.excitation.seats[static_cast<std::size_t>(a)];
      const auto pose = bridge->prescribed_motion(a, t);
      const auto face = design.deck.face_points()[static_cast<std::size_t>(a)];
      CHECK(pose.position.x() == face.x() + s.longitudinal->displacement(t));
      CHECK(pose.position.y() == face.y());  // no transverse seat motion in this scene
      CHECK(pose.velocity.x() == s.longitudinal->velocity(t));
      CHECK(pose.acceleration.x() == s.longitudinal->acceleration(t));
    }
    const Eigen::Vector3d us = bridge->quasi_static_velocity(0, t);
    const Eigen::Vector3d us_ref = direct_quasi_static_velocity(design, *bridge, t);
    CHECK((us - us_ref).norm() <= kSolveTol * (1.0 + us_ref.norm()));

    // The same queries on a bridge that has only ever seen this time.
    Assembly fresh(bridge_parts(design));
    bridge->forces(t, q, u, f);
    fresh.forces(t, q, u, f_fresh);
    CHECK(f == f_fresh);
    bridge->contact_data(t, q, u, c);
    fresh.contact_data(t, q, u, c_fresh);
    check_same_contacts(c, c_fresh);
    const auto p = bridge->power(t, q, u);
    const auto p_fresh = fresh.power(t, q, u);
    CHECK(p.damping == p_fresh.damping);
    CHECK(p.ground == p_fresh.ground);
    bridge->revert();  // keep the springs at their initial committed state for the next time
  }
}
