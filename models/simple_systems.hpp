// Simple nonsmooth benchmark systems with closed-form references (models/analytic.hpp):
// a bouncing ball, an oscillator against a rigid stop, and a block sliding with Coulomb
// friction. Each implements the integrators::System interface, so that every integrator can
// be checked against an exact solution.
//
// Units: kN, t, m, s, rad. All contacts here are scleronomic (fixed obstacles): the
// rheonomic terms what_N, what_T, wbar_N, wbar_T are zero, and W_N, W_T are constant.
#pragma once

#include "config/schema.hpp"
#include "integrators/system.hpp"

#include <span>
#include <string>
#include <vector>

namespace nsb::models {

// A point mass falling onto the fixed ground y = 0 under gravity.
// 1 DOF: q = (y), the height, which is also the gap g_N = y; W_N = (1). No friction
// (W_T = 0, mu = 0). Stored energy: m g y.
class BouncingBall final : public integrators::SystemBase {  // 1 DOF: y (height = gap)
 public:
  struct Parameters {
    double mass = 1.0;         // m [t], > 0
    double height = 1.0;       // initial height y0 = initial gap [m], >= 0
    double velocity = 0.0;     // initial velocity, upward positive [m/s], finite
    double restitution = 0.9;  // Newton's coefficient e, in [0, 1]
    double gravity = 9.81;     // g [m/s^2], >= 0
    void validate() const;     // throws std::invalid_argument naming the field
  };
  explicit BouncingBall(const Parameters&);

  const Parameters& parameters() const { return p_; }

  void forces(double t, const integrators::Vector& q, const integrators::Vector& u,
              integrators::Vector& f) override;
  int contacts() const override { return 1; }
  void contact_data(double t, const integrators::Vector& q, const integrators::Vector& u,
                    std::vector<integrators::ContactData>& out) const override;
  integrators::EnergyState energy(double t, const integrators::Vector& q) const override;

 private:
  Parameters p_;
};

// A linear oscillator m x'' + c x' + k x = F0 sin(2 pi f t) against a rigid stop at x = gap.
// 1 DOF: q = (x). Gap g_N = gap - x, so W_N = (-1) (x increasing closes the gap). No
// friction. c = 2 zeta sqrt(k m). Stored energy: k x^2 / 2. No gravity.
class ImpactOscillator final : public integrators::SystemBase {  // 1 DOF: x; stop at x = gap
 public:
  struct Parameters {
    double mass = 1.0;               // m [t], > 0
    double stiffness = 1.0;          // k [kN/m], >= 0
    double damping_ratio = 0.0;      // zeta [-], >= 0 (c = 2 zeta sqrt(k m))
    double gap = 0.1;                // position of the stop [m]; x0 <= gap required
    double restitution = 0.5;        // Newton's coefficient e, in [0, 1]
    double initial_position = 0.0;   // x0 [m], <= gap (no initial penetration)
    double initial_velocity = 0.0;   // v0 [m/s]
    double force_amplitude = 0.0;    // F0 [kN], finite
    double force_frequency = 0.0;    // f [Hz], >= 0 (f = 0 with F0 != 0 gives no force)
    void validate() const;           // throws std::invalid_argument naming the field
  };
  explicit ImpactOscillator(const Parameters&);

  const Parameters& parameters() const { return p_; }
  double damping_coefficient() const { return c_; }  // c [kN s/m]

  void forces(double t, const integrators::Vector& q, const integrators::Vector& u,
              integrators::Vector& f) override;
  void tangent(double t, const integrators::Vector& q, const integrators::Vector& u,
               integrators::Matrix& K, integrators::Matrix& C) override;
  int contacts() const override { return 1; }
  void contact_data(double t, const integrators::Vector& q, const integrators::Vector& u,
                    std::vector<integrators::ContactData>& out) const override;
  integrators::PowerTerms power(double t, const integrators::Vector& q,
                                const integrators::Vector& u) const override;
  integrators::EnergyState energy(double t, const integrators::Vector& q) const override;

 private:
  double external_force(double t) const;
  Parameters p_;
  double c_ = 0.0;
};

// A block on the ground y = 0 with Coulomb friction, driven along x by a constant force
// F plus a harmonic force F0 sin(2 pi f t). 2 DOF: q = (x, y), starting at (0, 0) with
// velocity (v0, 0). Contact: g_N = y, W_N = (0, 1), W_T = (1, 0), restitution 0.
// incline_deg = beta tilts gravity: the ground is a slope of angle beta in the (x, y) frame
// attached to it, so gravity is (-m g sin(beta), -m g cos(beta)) (positive beta pulls the
// block towards -x, downhill). Stored energy: gravity potential m g (x sin(beta) + y cos(beta)).
class SlidingBlock final : public integrators::SystemBase {  // 2 DOF: x, y; ground contact g_N = y
 public:
  struct Parameters {
    double mass = 1.0;               // m [t], > 0
    double friction = 0.5;           // mu [-], >= 0
    double gravity = 9.81;           // g [m/s^2], >= 0
    double initial_velocity = 0.0;   // v0 along x [m/s]
    double force = 0.0;              // constant driving force F along x [kN]
    double force_amplitude = 0.0;    // F0 [kN] of F0 sin(2 pi f t) along x
    double force_frequency = 0.0;    // f [Hz], >= 0
    double incline_deg = 0.0;        // slope angle beta [deg], in (-90, 90)
    void validate() const;           // throws std::invalid_argument naming the field
  };
  explicit SlidingBlock(const Parameters&);

  const Parameters& parameters() const { return p_; }

  void forces(double t, const integrators::Vector& q, const integrators::Vector& u,
              integrators::Vector& f) override;
  int contacts() const override { return 1; }
  void contact_data(double t, const integrators::Vector& q, const integrators::Vector& u,
                    std::vector<integrators::ContactData>& out) const override;
  integrators::PowerTerms power(double t, const integrators::Vector& q,
                                const integrators::Vector& u) const override;
  integrators::EnergyState energy(double t, const integrators::Vector& q) const override;

  double driving_force(double t) const;  // F + F0 sin(2 pi f t) [kN]

 private:
  Parameters p_;
  double gx_ = 0.0, gy_ = 0.0;  // gravity force components [kN]
};

// The [model] keys of each system besides kind (docs/scenes.md): key, unit, range and meaning
// of each parameter; validate() checks them and the scene reader reads them.
std::span<const config::Field<BouncingBall::Parameters>> bouncing_ball_fields();
std::span<const config::Field<ImpactOscillator::Parameters>> impact_oscillator_fields();
std::span<const config::Field<SlidingBlock::Parameters>> sliding_block_fields();

}  // namespace nsb::models
