// Planar contact kinematics: a corner point of a rigid body in the plane against a straight
// face of a rigid obstacle whose motion is prescribed (a moving abutment seat).
//
// Body: generalized coordinates q = (x, y, theta), velocities u = (vx, vy, omega). A body
// point with body-frame coordinates r_b sits at p = (x, y) + R(theta) r_b.
// Obstacle: prescribed pose (X(t), Y(t), Phi(t)) with its first and second time derivatives.
// The face passes through the obstacle-frame point a_o and has the obstacle-frame unit
// normal n_o, pointing from the obstacle towards the body. In the world:
//   a = (X, Y) + R(Phi) a_o,    n = R(Phi) n_o,    t = R(+90 deg) n.
// Gaps (the frame rotates with the obstacle):
//   g_N = n . (p - a)   (signed distance: > 0 open, < 0 penetrated),
//   g_T = t . (p - a)   (tangential position of the corner along the face).
// Their time derivatives are the relative velocities of the corner with respect to the
// obstacle point that coincides with it (Glocker, Set-Valued Force Laws, 2001, ch. 7):
//   gdot_N = W_N^T u + what_N,      gddot_N = W_N^T udot + wbar_N,
//   gdot_T = W_T^T u + what_T,      gddot_T = W_T^T udot + wbar_T,
// with, for r = R(theta) r_b and r x v = r_x v_y - r_y v_x,
//   W_N = (n_x, n_y, r x n),        W_T = (t_x, t_y, r x t),
//   what_N = Phidot g_T - n . adot,  what_T = -Phidot g_N - t . adot,
//   wbar_N = Phidot t.(pdot - adot) - omega^2 n.r - n.addot + Phiddot g_T + Phidot gdot_T,
//   wbar_T = -Phidot n.(pdot - adot) - omega^2 t.r - t.addot - Phiddot g_N - Phidot gdot_N,
// where pdot = v + omega J r, adot = (Xdot, Ydot) + Phidot J R(Phi) a_o,
// addot = (Xddot, Yddot) + Phiddot J R(Phi) a_o - Phidot^2 R(Phi) a_o and J = R(+90 deg).
// (Derivation: differentiate g_N and g_T using ndot = Phidot t and tdot = -Phidot n.)
//
// Units: m, s, rad. Everything is fixed-size: no allocation.
#pragma once

#include <Eigen/Dense>

namespace nsb::models {

// Prescribed planar motion of a rigid obstacle: pose (X, Y, Phi) and its derivatives.
struct PlanarMotion {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();      // (X [m], Y [m], Phi [rad])
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();      // time derivative [m/s, rad/s]
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();  // second derivative [m/s^2, rad/s^2]
};

// A body corner against an obstacle face.
struct CornerFace {
  Eigen::Vector2d body_point = Eigen::Vector2d::Zero();   // r_b, body frame [m]
  Eigen::Vector2d face_point = Eigen::Vector2d::Zero();   // a_o, obstacle frame [m]
  Eigen::Vector2d face_normal = Eigen::Vector2d::UnitX(); // n_o, obstacle frame, unit length,
                                                          // from the obstacle to the body
};

// The kinematic quantities of one contact at (t, q, u). See the header comment for formulas.
struct ContactKinematics {
  double gap_normal = 0.0;       // g_N [m]
  double gap_tangent = 0.0;      // g_T [m]
  Eigen::Vector3d w_normal = Eigen::Vector3d::Zero();   // W_N [-, -, m]
  Eigen::Vector3d w_tangent = Eigen::Vector3d::Zero();  // W_T [-, -, m]
  double what_normal = 0.0;      // [m/s]
  double what_tangent = 0.0;     // [m/s]
  double wbar_normal = 0.0;      // [m/s^2]
  double wbar_tangent = 0.0;     // [m/s^2]
  double gap_rate_normal = 0.0;  // gdot_N = W_N^T u + what_N [m/s]
  double gap_rate_tangent = 0.0; // gdot_T = W_T^T u + what_T [m/s]
  Eigen::Vector2d point = Eigen::Vector2d::Zero();    // corner position p [m]
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();  // n, world frame
  Eigen::Vector2d tangent = Eigen::Vector2d::UnitY(); // t = n rotated +90 deg, world frame
};

// Contact kinematics of the corner `c` of the body at (q, u) against the obstacle moving
// with `obstacle` (evaluated at the same time t).
ContactKinematics corner_contact(const CornerFace& c, const Eigen::Vector3d& q,
                                 const Eigen::Vector3d& u, const PlanarMotion& obstacle);

// The normal part of ContactKinematics, the same numbers: what a time-stepping scheme needs
// to choose its index set.
struct ContactNormal {
  double gap_normal = 0.0;       // g_N [m]
  double gap_tangent = 0.0;      // g_T [m]: where the corner lies along the face
  Eigen::Vector3d w_normal = Eigen::Vector3d::Zero();  // W_N [-, -, m]
  double what_normal = 0.0;      // [m/s]
  double gap_rate_normal = 0.0;  // gdot_N = W_N^T u + what_N [m/s]
  Eigen::Vector2d point = Eigen::Vector2d::Zero();  // corner position p [m]
};
ContactNormal corner_contact_normal(const CornerFace& c, const Eigen::Vector3d& q,
                                    const Eigen::Vector3d& u, const PlanarMotion& obstacle);

// 2D cross product a x b = a_x b_y - a_y b_x.
inline double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}
// Rotation by +90 degrees: J (x, y) = (-y, x).
inline Eigen::Vector2d perp(const Eigen::Vector2d& a) { return {-a.y(), a.x()}; }

}  // namespace nsb::models
