#include "models/contact_geometry.hpp"

#include <cmath>

namespace nsb::models {

namespace {
Eigen::Vector2d rotate(double angle, const Eigen::Vector2d& v) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}
}  // namespace

ContactKinematics corner_contact(const CornerFace& c, const Eigen::Vector3d& q,
                                 const Eigen::Vector3d& u, const PlanarMotion& obstacle) {
  ContactKinematics k;
  const Eigen::Vector2d v = u.head<2>();
  const double omega = u.z();
  const double phi = obstacle.position.z();
  const double phid = obstacle.velocity.z();
  const double phidd = obstacle.acceleration.z();

  // Body corner: position and velocity.
  const Eigen::Vector2d r = rotate(q.z(), c.body_point);
  const Eigen::Vector2d p = q.head<2>() + r;
  const Eigen::Vector2d pdot = v + omega * perp(r);

  // Obstacle face point: position, velocity and acceleration (rigid-body kinematics).
  const Eigen::Vector2d ra = rotate(phi, c.face_point);
  const Eigen::Vector2d a = obstacle.position.head<2>() + ra;
  const Eigen::Vector2d adot = obstacle.velocity.head<2>() + phid * perp(ra);
  const Eigen::Vector2d addot =
      obstacle.acceleration.head<2>() + phidd * perp(ra) - phid * phid * ra;

  const Eigen::Vector2d n = rotate(phi, c.face_normal);
  const Eigen::Vector2d t = perp(n);
  const Eigen::Vector2d d = p - a;

  k.point = p;
  k.normal = n;
  k.tangent = t;
  k.gap_normal = n.dot(d);
  k.gap_tangent = t.dot(d);
  k.w_normal << n.x(), n.y(), cross2(r, n);
  k.w_tangent << t.x(), t.y(), cross2(r, t);
  k.what_normal = phid * k.gap_tangent - n.dot(adot);
  k.what_tangent = -phid * k.gap_normal - t.dot(adot);
  k.gap_rate_normal = k.w_normal.dot(u) + k.what_normal;
  k.gap_rate_tangent = k.w_tangent.dot(u) + k.what_tangent;

  // Terms of the second derivatives that do not depend on udot (see the header).
  const Eigen::Vector2d rel = pdot - adot;
  k.wbar_normal = phid * t.dot(rel) - omega * omega * n.dot(r) - n.dot(addot) +
                  phidd * k.gap_tangent + phid * k.gap_rate_tangent;
  k.wbar_tangent = -phid * n.dot(rel) - omega * omega * t.dot(r) - t.dot(addot) -
                   phidd * k.gap_normal - phid * k.gap_rate_normal;
  return k;
}

}  // namespace nsb::models
