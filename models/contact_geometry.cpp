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
  // (x, y) = R v, as two scalars: building a Vector2d from separately computed halves and
  // reading it back whole stalls the store forwarding, a large share of this function.
  void apply(const Eigen::Vector2d& v, double& x, double& y) const {
    x = c * v.x() - s * v.y();
    y = s * v.x() + c * v.y();
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
  double rx, ry;
  body_rotation.apply(c.body_point, rx, ry);
  const double px = q.x() + rx, py = q.y() + ry;
  const double pdx = vx + omega * -ry, pdy = vy + omega * rx;

  // Obstacle face point: position, velocity and acceleration (rigid-body kinematics).
  double rax, ray;
  obstacle_rotation.apply(c.face_point, rax, ray);
  const double ax = obstacle.position.x() + rax, ay = obstacle.position.y() + ray;
  const double adx = obstacle.velocity.x() + phid * -ray;
  const double ady = obstacle.velocity.y() + phid * rax;
  const double phid2 = phid * phid;
  const double addx = obstacle.acceleration.x() + phidd * -ray - phid2 * rax;
  const double addy = obstacle.acceleration.y() + phidd * rax - phid2 * ray;

  double nx, ny;
  obstacle_rotation.apply(c.face_normal, nx, ny);
  const double tx = -ny, ty = nx;  // t = J n
  const double dx = px - ax, dy = py - ay;

  k.point.x() = px;
  k.point.y() = py;
  k.normal.x() = nx;
  k.normal.y() = ny;
  k.tangent.x() = tx;
  k.tangent.y() = ty;
  k.gap_normal = nx * dx + ny * dy;
  k.gap_tangent = tx * dx + ty * dy;
  const double wn2 = rx * ny - ry * nx;  // r x n
  const double wt2 = rx * ty - ry * tx;  // r x t
  k.w_normal.x() = nx;
  k.w_normal.y() = ny;
  k.w_normal.z() = wn2;
  k.w_tangent.x() = tx;
  k.w_tangent.y() = ty;
  k.w_tangent.z() = wt2;
  k.what_normal = phid * k.gap_tangent - (nx * adx + ny * ady);
  k.what_tangent = -phid * k.gap_normal - (tx * adx + ty * ady);
  k.gap_rate_normal = (nx * vx + ny * vy + wn2 * omega) + k.what_normal;
  k.gap_rate_tangent = (tx * vx + ty * vy + wt2 * omega) + k.what_tangent;

  // Terms of the second derivatives that do not depend on udot (see the header).
  const double relx = pdx - adx, rely = pdy - ady;
  const double omega2 = omega * omega;
  k.wbar_normal = phid * (tx * relx + ty * rely) - omega2 * (nx * rx + ny * ry) -
                  (nx * addx + ny * addy) + phidd * k.gap_tangent + phid * k.gap_rate_tangent;
  k.wbar_tangent = -phid * (nx * relx + ny * rely) - omega2 * (tx * rx + ty * ry) -
                   (tx * addx + ty * addy) - phidd * k.gap_normal - phid * k.gap_rate_normal;
  return k;
}

ContactNormal corner_contact_normal(const CornerFace& c, const Eigen::Vector3d& q,
                                    const Eigen::Vector3d& u, const PlanarMotion& obstacle) {
  // The statements of corner_contact() that g_N, W_N, what_N and gdot_N depend on, unchanged:
  // the same numbers without the tangential and second-order terms.
  ContactNormal k;
  const double vx = u.x(), vy = u.y(), omega = u.z();
  const double phi = obstacle.position.z();
  const double phid = obstacle.velocity.z();
  const Rotation body_rotation(q.z()), obstacle_rotation(phi);

  double rx, ry;
  body_rotation.apply(c.body_point, rx, ry);
  const double px = q.x() + rx, py = q.y() + ry;

  double rax, ray;
  obstacle_rotation.apply(c.face_point, rax, ray);
  const double ax = obstacle.position.x() + rax, ay = obstacle.position.y() + ray;
  const double adx = obstacle.velocity.x() + phid * -ray;
  const double ady = obstacle.velocity.y() + phid * rax;

  double nx, ny;
  obstacle_rotation.apply(c.face_normal, nx, ny);
  const double tx = -ny, ty = nx;  // t = J n
  const double dx = px - ax, dy = py - ay;

  k.point.x() = px;
  k.point.y() = py;
  k.gap_normal = nx * dx + ny * dy;
  k.gap_tangent = tx * dx + ty * dy;
  const double wn2 = rx * ny - ry * nx;  // r x n
  k.w_normal.x() = nx;
  k.w_normal.y() = ny;
  k.w_normal.z() = wn2;
  k.what_normal = phid * k.gap_tangent - (nx * adx + ny * ady);
  k.gap_rate_normal = (nx * vx + ny * vy + wn2 * omega) + k.what_normal;
  return k;
}

}  // namespace nsb::models
