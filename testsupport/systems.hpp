// Small mechanical systems for the tests of every module: each is the simplest system that
// exercises one feature of the integrators (a free mass, a mass on a spring, a ball on a
// moving floor, a block with Coulomb friction, a block pressed against a wall in prescribed
// motion, two masses that collide, a rigid bar with two corners, an elastic-plastic spring).
// Their contact data are exact and are checked against finite differences in
// testsupport/test/systems_test.cpp; the closed forms the tests compare with are derived
// beside each test.
//
// Every system derives from integrators::SystemBase and counts commit() calls, so that a test
// can check that an integrator commits once per accepted step. Gravity and constant loads are
// conservative: their potential is in EnergyState::stored, and PowerTerms::external holds
// only the work rate of time-dependent loads.
//
// Units: kN, t, m, s, rad.
#pragma once

#include "integrators/system.hpp"

#include <string>
#include <vector>

namespace nsb::testsupport {

using integrators::ContactData;
using integrators::EnergyState;
using integrators::Matrix;
using integrators::PowerTerms;
using integrators::Vector;

// SystemBase with a public commit counter.
class TestSystem : public integrators::SystemBase {
 public:
  void commit() override { ++commits; }
  long commits = 0;  // commit() calls since construction

 protected:
  using SystemBase::SystemBase;
};

// n free bodies without forces or contacts; the test sets M and the initial state freely
// (checked_inverse_mass is what checks them). Coordinates q1..qn, velocities u1..un unless
// named.
class FreeMass final : public TestSystem {
 public:
  explicit FreeMass(int dofs);
  FreeMass(std::vector<std::string> coordinate_names, std::vector<std::string> velocity_names);
  using SystemBase::set_initial_state;
  using SystemBase::set_mass;
};

// m x'' + c x' + k x = F0 sin(w t) (1 DOF: x), optionally against a wall at x_w = V t on its
// left: g_N = x - V t, W_N = 1, what_N = -V, wbar_N = 0. Stored energy k x^2 / 2.
class SpringMass final : public TestSystem {
 public:
  struct Parameters {
    double mass = 1.0;               // m [t], > 0
    double stiffness = 0.0;          // k [kN/m], >= 0
    double damping = 0.0;            // c [kN s/m], >= 0
    double force_amplitude = 0.0;    // F0 [kN]
    double force_frequency = 0.0;    // w [rad/s]
    double initial_position = 0.0;   // x0 [m]
    double initial_velocity = 0.0;   // v0 [m/s]
    bool wall = false;               // a unilateral contact with the wall
    double wall_velocity = 0.0;      // V [m/s]
    double restitution = 0.0;        // Newton's e of the wall contact, in [0, 1]
  };
  explicit SpringMass(const Parameters& p);
  const Parameters& parameters() const { return p_; }
  double load(double t) const;  // F0 sin(w t) [kN]

  void forces(double t, const Vector& q, const Vector& u, Vector& f) override;
  void tangent(double t, const Vector& q, const Vector& u, Matrix& K, Matrix& C) override;
  int contacts() const override { return p_.wall ? 1 : 0; }
  void contact_data(double t, const Vector& q, const Vector& u,
                    std::vector<ContactData>& out) const override;
  PowerTerms power(double t, const Vector& q, const Vector& u) const override;
  EnergyState energy(double t, const Vector& q) const override;

 private:
  Parameters p_;
};

// A point mass (1 DOF: height y) under gravity and an upward load F(t) = ramp t, above a floor
// at y_f(t) = V t + A sin(w t): g_N = y - y_f(t), W_N = 1, what_N = -y_f'(t),
// wbar_N = -y_f''(t). Frictionless. Stored energy m g y.
class Ball final : public TestSystem {
 public:
  struct Parameters {
    double mass = 1.0;               // m [t], > 0
    double gravity = 9.81;           // g [m/s^2], >= 0
    double initial_height = 1.0;     // y0 [m]
    double initial_velocity = 0.0;   // v0 [m/s], upward positive
    double restitution = 0.5;        // Newton's e, in [0, 1]
    double ramp = 0.0;               // upward load growing at this rate [kN/s]
    double floor_velocity = 0.0;     // V [m/s]
    double floor_amplitude = 0.0;    // A [m]
    double floor_frequency = 0.0;    // w [rad/s]
  };
  explicit Ball(const Parameters& p);
  const Parameters& parameters() const { return p_; }
  double floor_height(double t) const;  // y_f(t) [m]

  void forces(double t, const Vector& q, const Vector& u, Vector& f) override;
  int contacts() const override { return 1; }
  void contact_data(double t, const Vector& q, const Vector& u,
                    std::vector<ContactData>& out) const override;
  PowerTerms power(double t, const Vector& q, const Vector& u) const override;
  EnergyState energy(double t, const Vector& q) const override;

 private:
  Parameters p_;
};

// A block on the ground y = 0 (2 DOF: x, y) with Coulomb friction, pushed along x by
// F(t) = F0 + F1 sin(w t) and held by a spring k x: g_N = y, W_N = (0, 1), W_T = (1, 0).
// Stored energy k x^2 / 2 + m g y.
class Block final : public TestSystem {
 public:
  struct Parameters {
    double mass = 2.0;               // m [t], > 0
    double gravity = 9.81;           // g [m/s^2], >= 0
    double friction = 0.5;           // mu, >= 0
    double stiffness = 0.0;          // k [kN/m], >= 0, along x
    double force = 0.0;              // F0 [kN]
    double force_amplitude = 0.0;    // F1 [kN]
    double force_frequency = 0.0;    // w [rad/s]
    double initial_position = 0.0;   // x0 [m]
    double initial_velocity = 0.0;   // vx0 [m/s]
    double initial_height = 0.0;     // y0 [m] (< 0: a compliant floor's static penetration)
    double restitution = 0.0;        // Newton's e, in [0, 1]
  };
  explicit Block(const Parameters& p);
  const Parameters& parameters() const { return p_; }
  double driving_force(double t) const;  // F0 + F1 sin(w t) [kN]

  void forces(double t, const Vector& q, const Vector& u, Vector& f) override;
  void tangent(double t, const Vector& q, const Vector& u, Matrix& K, Matrix& C) override;
  int contacts() const override { return 1; }
  void contact_data(double t, const Vector& q, const Vector& u,
                    std::vector<ContactData>& out) const override;
  PowerTerms power(double t, const Vector& q, const Vector& u) const override;
  EnergyState energy(double t, const Vector& q) const override;

 private:
  Parameters p_;
};

// A block (2 DOF: x, y) pressed by a constant force P towards a wall on its left whose motion
// is prescribed with constant acceleration, x_w(t) = x0 + v0 t + a t^2 / 2; gravity along -y
// slides it down the wall against Coulomb friction. g_N = x - x_w(t), W_N = (1, 0),
// W_T = (0, 1), and the exact rheonomic terms what_N = -x_w'(t) = -(v0 + a t),
// wbar_N = -x_w''(t) = -a; the wall does not move along y (what_T = wbar_T = 0). The block
// starts at rest relative to the wall, touching it (g_N = initial_gap). Stored energy
// P x + m g y (the potential of the two constant forces).
class WallBlock final : public TestSystem {
 public:
  struct Parameters {
    double mass = 1.0;              // m [t], > 0
    double pressing_force = 10.0;   // P [kN], >= 0, towards the wall (-x)
    double gravity = 0.0;           // g [m/s^2], >= 0, along -y
    double friction = 0.0;          // mu, >= 0
    double restitution = 0.0;       // Newton's e, in [0, 1]
    double wall_position = 0.0;     // x0 [m]
    double wall_velocity = 0.0;     // v0 [m/s]
    double wall_acceleration = 1.0; // a [m/s^2]
    double initial_gap = 0.0;       // g_N(0) [m], >= 0
  };
  explicit WallBlock(const Parameters& p);
  const Parameters& parameters() const { return p_; }
  double wall_position(double t) const;      // x_w(t) [m]
  double wall_velocity(double t) const;      // x_w'(t) [m/s]

  void forces(double t, const Vector& q, const Vector& u, Vector& f) override;
  int contacts() const override { return 1; }
  void contact_data(double t, const Vector& q, const Vector& u,
                    std::vector<ContactData>& out) const override;
  EnergyState energy(double t, const Vector& q) const override;

 private:
  Parameters p_;
};

// Two point masses on a line (2 DOF: x1, x2), x1 < x2, each on a spring to the ground, one
// contact g_N = x2 - x1 - d, W_N = (-1, 1). Stored energy (k1 x1^2 + k2 x2^2) / 2.
class TwoMasses final : public TestSystem {
 public:
  struct Parameters {
    double mass1 = 1.0, mass2 = 1.0;              // [t], > 0
    double stiffness1 = 0.0, stiffness2 = 0.0;    // springs to the ground [kN/m], >= 0
    double distance = 0.0;                        // d [m]: the contact closes at x2 - x1 = d
    double position1 = 0.0, position2 = 1e-3;     // initial positions [m]
    double velocity1 = 0.0, velocity2 = 0.0;      // initial velocities [m/s]
    double restitution = 0.5;                     // Newton's e, in [0, 1]
  };
  explicit TwoMasses(const Parameters& p);
  const Parameters& parameters() const { return p_; }

  void forces(double t, const Vector& q, const Vector& u, Vector& f) override;
  void tangent(double t, const Vector& q, const Vector& u, Matrix& K, Matrix& C) override;
  int contacts() const override { return 1; }
  void contact_data(double t, const Vector& q, const Vector& u,
                    std::vector<ContactData>& out) const override;
  EnergyState energy(double t, const Vector& q) const override;

 private:
  Parameters p_;
};

// A rigid bar (3 DOF: centre x, y and rotation theta) of length 2 l over the floor y = 0,
// under gravity; its two ends (corners) r_i = s_i l (cos theta, sin theta), s = -1, +1, touch
// the floor with Coulomb friction. For corner i:
//   g_N = y + s_i l sin(theta),  W_N = (0, 1, s_i l cos(theta)),  wbar_N = -s_i l sin(theta) w^2,
//   g_T = x + s_i l cos(theta),  W_T = (1, 0, -s_i l sin(theta)), wbar_T = -s_i l cos(theta) w^2,
// with w = theta'. W depends on q, so the contact terms wbar are not zero. Stored energy m g y.
class TwoCornerBody final : public TestSystem {
 public:
  struct Parameters {
    double mass = 1.0;               // m [t], > 0
    double inertia = 1.0 / 3.0;      // I about the centre [t m^2], > 0 (m l^2 / 3 for l = 1)
    double half_length = 1.0;        // l [m], > 0
    double gravity = 9.81;           // g [m/s^2], >= 0
    double friction = 0.0;           // mu, >= 0
    double restitution = 0.0;        // Newton's e, in [0, 1]
    Vector initial_position = Vector::Zero(3);  // (x, y, theta)
    Vector initial_velocity = Vector::Zero(3);  // (vx, vy, omega)
  };
  explicit TwoCornerBody(const Parameters& p);
  const Parameters& parameters() const { return p_; }

  void forces(double t, const Vector& q, const Vector& u, Vector& f) override;
  int contacts() const override { return 2; }
  void contact_data(double t, const Vector& q, const Vector& u,
                    std::vector<ContactData>& out) const override;
  EnergyState energy(double t, const Vector& q) const override;

 private:
  Parameters p_;
};

// A unit mass on an elastic-perfectly-plastic spring (stiffness k, yield force f_y) with
// trial and committed plastic displacement, driven by F0 sin(w t) (1 DOF: x). Its tangent
// switches between k and 0 as it yields and unloads, so an implicit integrator has to
// refactorize; tangent_changed() says when. No contacts. Stored energy F_s^2 / (2 k).
class PlasticOscillator final : public TestSystem {
 public:
  struct Parameters {
    double stiffness = 1.0;         // k [kN/m], > 0
    double yield_force = 1.0;       // f_y [kN], > 0
    double force_amplitude = 0.0;   // F0 [kN]
    double force_frequency = 0.0;   // w [rad/s]
  };
  explicit PlasticOscillator(const Parameters& p);

  void forces(double t, const Vector& q, const Vector& u, Vector& f) override;
  void tangent(double t, const Vector& q, const Vector& u, Matrix& K, Matrix& C) override;
  bool tangent_changed() const override { return trial_yielding_ != yielding_; }
  void commit() override;
  void revert() override;
  PowerTerms power(double t, const Vector& q, const Vector& u) const override;
  EnergyState energy(double t, const Vector& q) const override;

 private:
  Parameters p_;
  double plastic_ = 0.0, trial_plastic_ = 0.0, trial_force_ = 0.0;
  bool yielding_ = false, trial_yielding_ = false;
};

}  // namespace nsb::testsupport
