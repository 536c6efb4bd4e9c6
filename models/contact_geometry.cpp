#include "models/contact_geometry.hpp"

#include <cmath>

namespace nsb::models {

namespace {

// Cosine and sine of a rotation angle. The corners of one body share its angle and a seat
// that does not rotate has Phi = 0 exactly, so the last angle's values are kept (per thread)
// and 0 needs no evaluation: the results are the same numbers, computed less often.
struct Rotation {
  double c = 1.0, s = 0.0;
  explicit Rotation(double angle) {
    if (angle == 0.0) return;
    thread_local double last_angle = 0.0, last_c = 1.0, last_s = 0.0;
    if (angle != last_angle) {
      last_angle = angle;
      last_c = std::cos(angle);
      last_s = std::sin(angle);
    }
    c = last_c;
    s = last_s;
  }
  Eigen::Vector2d operator()(const Eigen::Vector2d& v) const {
    return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
  }
};

}  // namespace

ContactKinematics corner_contact(const CornerFace& c, const Eigen::Vector3d& q,
                                 const Eigen::Vector3d& u, const PlanarMotion& obstacle) {
  // Written out in scalars (the same operations, in the same order, as the vector formulas
  // of the header): this runs for every corner at every step, and small Eigen temporaries
  // cost more here than the arithmetic.
  ContactKinematics k;
  const double vx = u.x(), vy = u.y(), omega = u.z();
  const double phi = obstacle.position.z();
  const double phid = obstacle.velocity.z();
  const double phidd = obstacle.acceleration.z();
  const Rotation body_rotation(q.z()), obstacle_rotation(phi);

  // Body corner: position p = (x, y) + r and velocity pdot = v + omega J r.
  const Eigen::Vector2d r = body_rotation(c.body_point);
  const double px = q.x() + r.x(), py = q.y() + r.y();
  const double pdx = vx + omega * -r.y(), pdy = vy + omega * r.x();

  // Obstacle face point: position, velocity and acceleration (rigid-body kinematics).
  const Eigen::Vector2d ra = obstacle_rotation(c.face_point);
  const double ax = obstacle.position.x() + ra.x(), ay = obstacle.position.y() + ra.y();
  const double adx = obstacle.velocity.x() + phid * -ra.y();
  const double ady = obstacle.velocity.y() + phid * ra.x();
  const double phid2 = phid * phid;
  const double addx = obstacle.acceleration.x() + phidd * -ra.y() - phid2 * ra.x();
  const double addy = obstacle.acceleration.y() + phidd * ra.x() - phid2 * ra.y();

  const Eigen::Vector2d n = obstacle_rotation(c.face_normal);
  const double nx = n.x(), ny = n.y();
  const double tx = -ny, ty = nx;  // t = J n
  const double dx = px - ax, dy = py - ay;

  k.point = Eigen::Vector2d(px, py);
  k.normal = n;
  k.tangent = Eigen::Vector2d(tx, ty);
  k.gap_normal = nx * dx + ny * dy;
  k.gap_tangent = tx * dx + ty * dy;
  const double wn2 = r.x() * ny - r.y() * nx;  // r x n
  const double wt2 = r.x() * ty - r.y() * tx;  // r x t
  k.w_normal = Eigen::Vector3d(nx, ny, wn2);
  k.w_tangent = Eigen::Vector3d(tx, ty, wt2);
  k.what_normal = phid * k.gap_tangent - (nx * adx + ny * ady);
  k.what_tangent = -phid * k.gap_normal - (tx * adx + ty * ady);
  k.gap_rate_normal = (nx * vx + ny * vy + wn2 * omega) + k.what_normal;
  k.gap_rate_tangent = (tx * vx + ty * vy + wt2 * omega) + k.what_tangent;

  // Terms of the second derivatives that do not depend on udot (see the header).
  const double relx = pdx - adx, rely = pdy - ady;
  const double omega2 = omega * omega;
  k.wbar_normal = phid * (tx * relx + ty * rely) - omega2 * (nx * r.x() + ny * r.y()) -
                  (nx * addx + ny * addy) + phidd * k.gap_tangent + phid * k.gap_rate_tangent;
  k.wbar_tangent = -phid * (nx * relx + ny * rely) - omega2 * (tx * r.x() + ty * r.y()) -
                   (tx * addx + ty * addy) - phidd * k.gap_normal - phid * k.gap_rate_normal;
  return k;
}

}  // namespace nsb::models
