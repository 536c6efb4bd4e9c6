#include "models/parts.hpp"
#include "models/field_checks.hpp"

#include "models/deck_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace nsb::models::parts {

namespace {

bool finite_positive(double v) { return std::isfinite(v) && v > 0; }

DeckGeometry plan(const RigidBody& b) {
  return {.length = b.length, .width = b.width, .skew_deg = b.skew_deg, .gap_right = 0.0,
          .gap_left = 0.0, .skew_left_deg = b.skew_left_deg, .skew_right_deg = b.skew_right_deg,
          .radius = b.radius};
}

}  // namespace

void RigidBody::validate(const std::string& prefix) const {
  require(finite_positive(mass), prefix + "mass", "must be > 0 [t]");
  require(finite_positive(inertia), prefix + "inertia", "must be > 0 [t m^2]");
  plan(*this).validate(prefix);
  require(rest.allFinite(), prefix + "rest", "must be finite [m, m, rad]");
  require(initial_position.allFinite(), prefix + "initial_position",
          "must be finite [m, m, rad]");
  require(initial_velocity.allFinite(), prefix + "initial_velocity",
          "must be finite [m/s, m/s, rad/s]");
}

Eigen::Vector2d RigidBody::corner(int index) const { return plan(*this).corner(index); }

Face end_face(const RigidBody& body, End end) {
  // DeckGeometry's face normals point from an abutment towards the deck, i.e. into the deck
  // end: the outward normal of the deck's end face is their opposite.
  const DeckGeometry g = plan(body);
  const int contact = end == End::kLeft ? 0 : 2;
  return {g.end_point(end == End::kLeft ? 0 : 1), -g.face_normal(contact)};
}

Face bounded_end_face(const RigidBody& body, End end) {
  Face f = end_face(body, end);
  // The end's two corners lie on its face on either side of the end point, each (W/2) /
  // cos alpha from it for a straight end of angle alpha (its own, docs/bridge.md "Faces with
  // their own angles") and W/2 for a curved deck's radial end: the half-length is their
  // distance from the end point.
  const DeckGeometry g = plan(body);
  const int first = end == End::kLeft ? 0 : 2;
  const Eigen::Vector2d point = g.end_point(end == End::kLeft ? 0 : 1);
  f.half_length = std::max((g.corner(first) - point).norm(), (g.corner(first + 1) - point).norm());
  return f;
}

BodyContactKinematics corner_on_body(const CornerFace& c, const Eigen::Vector3d& q_a,
                                     const Eigen::Vector3d& u_a, const Eigen::Vector3d& q_b,
                                     const Eigen::Vector3d& u_b) {
  PlanarMotion b;
  b.position = q_b;
  b.velocity = u_b;  // acceleration zero: its part is W_B^T udot_B (see the header)
  BodyContactKinematics k;
  k.a = corner_contact(c, q_a, u_a, b);
  const double dx = k.a.point.x() - q_b.x(), dy = k.a.point.y() - q_b.y();
  const Eigen::Vector2d& n = k.a.normal;
  const Eigen::Vector2d& t = k.a.tangent;
  k.w_normal_b << -n.x(), -n.y(), -(dx * n.y() - dy * n.x());
  k.w_tangent_b << -t.x(), -t.y(), -(dx * t.y() - dy * t.x());
  return k;
}

BodyContactNormal corner_on_body_normal(const CornerFace& c, const Eigen::Vector3d& q_a,
                                        const Eigen::Vector3d& u_a, const Eigen::Vector3d& q_b,
                                        const Eigen::Vector3d& u_b) {
  PlanarMotion b;
  b.position = q_b;
  b.velocity = u_b;
  BodyContactNormal k;
  k.a = corner_contact_normal(c, q_a, u_a, b);
  const double dx = k.a.point.x() - q_b.x(), dy = k.a.point.y() - q_b.y();
  const double nx = k.a.w_normal.x(), ny = k.a.w_normal.y();  // n
  k.w_normal_b << -nx, -ny, -(dx * ny - dy * nx);
  return k;
}

void write_body_contact(const BodyContactKinematics& k, int offset_a, int offset_b,
                        double restitution, double friction, integrators::ContactData& out) {
  write_contact(k.a, offset_a, restitution, friction, out);
  out.w_normal.segment<3>(offset_b) = k.w_normal_b;
  out.w_tangent.segment<3>(offset_b) = k.w_tangent_b;
  out.what_normal = 0.0;  // scleronomic: both sides are free bodies
  out.what_tangent = 0.0;
}

void write_body_contact_normal(const BodyContactKinematics& k, int offset_a, int offset_b,
                               integrators::ContactData& out) {
  out.gap_normal = k.a.gap_normal;
  out.w_normal.setZero();
  out.w_normal.segment<3>(offset_a) = k.a.w_normal;
  out.w_normal.segment<3>(offset_b) = k.w_normal_b;
  out.what_normal = 0.0;
  out.far = is_far(k.a.gap_normal, k.a.gap_rate_normal);
}

void write_body_contact_normal(const BodyContactNormal& k, int offset_a, int offset_b,
                               integrators::ContactData& out) {
  out.gap_normal = k.a.gap_normal;
  out.w_normal.setZero();
  out.w_normal.segment<3>(offset_a) = k.a.w_normal;
  out.w_normal.segment<3>(offset_b) = k.w_normal_b;
  out.what_normal = 0.0;
  out.far = is_far(k.a.gap_normal, k.a.gap_rate_normal);
}

int MotionTable::add(const Motion& m, bool needs_acceleration) {
  if (!m) return kNone;
  const auto it = std::find(motions_.begin(), motions_.end(), m);
  const auto i = static_cast<std::size_t>(it - motions_.begin());
  if (it == motions_.end()) {
    motions_.push_back(m);
    needs_acceleration_.push_back(0);
    values_.emplace_back();
  }
  if (needs_acceleration) needs_acceleration_[i] = 1;
  t_ = std::numeric_limits<double>::quiet_NaN();
  return static_cast<int>(i);
}

}  // namespace nsb::models::parts
