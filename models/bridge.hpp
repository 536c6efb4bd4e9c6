// The benchmark bridge of Shi & Dimitrakopoulos (2017): a rigid deck (x, y, theta) on three
// two-column RC bents with Takeda hysteresis, Rayleigh damping, and four frictional deck-corner
// contacts against two abutment seats whose motion is prescribed. Multi-support excitation:
// every bent and every seat has its own ground motion (eq. 2).
//
// Equation of motion (eq. 2, absolute coordinates q of the deck centre):
//   M udot = f_S + f_D + W_N lambda_N + W_T lambda_T,      M = diag(m_d, m_d, I_d),
//   f_S = -sum_j [F_x,j b_x + F_y,j b_y,j],   b_x = (1, 0, 0),  b_y,j = (0, 1, s_j),
//   F_x,j = Takeda_x,j(x - u_gx,j(t)),  F_y,j = Takeda_y,j(y + s_j theta - u_gy,j(t)),
//   f_D = -C (u - us_dot(t)),   C = a0 M + a1 K0  (Rayleigh on modes i, j of M and K0),
// where s_j is the bent position along the deck axis (the transverse bent force acts with the
// lever arm s_j), K0 the initial stiffness, and us = K0^-1 sum_j k0_j b_j u_g,j the
// quasi-static deck displacement of the support motion (Chopra, Dynamics of Structures,
// sec. 9.7): for uniform excitation us = (u_gx, u_gy, 0), so f_D acts on the velocity relative
// to the ground; in general a1 K0 (u - us_dot) = a1 sum_j k0_j b_j (b_j^T u - u_gdot,j) is the
// damping of each bent on its own relative velocity. The bent kinematics are linear in theta
// (small rotations; |theta| < 0.01 rad in the benchmark). The contacts use exact kinematics
// (models/contact_geometry.hpp) with moving seats: seat a is posed at its reference face point
// plus its displacement (u_x, u_y) and rotation about that point.
//
// Cost: an integrator asks for forces, contact data and power at the same time t several
// times per step, and supports usually share one record. The bridge therefore evaluates each
// distinct GroundMotion object once per distinct t and keeps the values (a cache inside the
// const methods): one Bridge must not be used from several threads at once.
//
// Units: kN, t, m, s, rad.
#pragma once

#include "integrators/system.hpp"
#include "models/contact_geometry.hpp"
#include "models/deck_geometry.hpp"
#include "models/ground_motion.hpp"
#include "models/rayleigh.hpp"
#include "models/rigid_deck.hpp"
#include "models/takeda.hpp"

#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace nsb::models {

// A bent of identical circular RC columns, fixed at both ends, and the engineering estimates
// of its springs (docs/bridge.md): per column k = 12 EI_eff / H^3 with EI_eff = cracked_ratio
// E pi d^4 / 64; yield displacement Delta_y = phi_y H^2 / 6 with phi_y = 2.25 eps_y / d
// (Priestley, Seible & Calvi 1996); yield force = bent stiffness * Delta_y. The same springs
// serve both directions.
struct BentDesign {
  double height = 0.0;               // clear column height H [m], > 0
  double column_diameter = 0.305;    // d [m], > 0
  int columns = 2;                   // columns per bent, >= 1
  double elastic_modulus = 3.0e7;    // E_c [kPa], > 0 (30 GPa)
  double cracked_ratio = 0.5;        // EI_eff / EI_gross, in (0, 1]
  double yield_strain = 0.0023;      // eps_y of the reinforcement [-], > 0
  double post_yield_ratio = 0.05;    // Takeda post-yield / yield stiffness, in [0, 1)
  double unloading_exponent = 0.4;   // Takeda alpha, in [0, 1]
  void validate(const std::string& prefix = "") const;  // throws naming the field
  double column_stiffness() const;     // [kN/m]
  double stiffness() const;            // columns * column_stiffness() [kN/m]
  double yield_displacement() const;   // [m]
  double yield_force() const;          // [kN]
  takeda::Parameters takeda() const;   // bilinear Takeda of the whole bent
};

class Bridge final : public integrators::SystemBase {
 public:
  struct Bent {
    double position = 0.0;                // s_j along the deck axis from the centre [m]
    takeda::Parameters longitudinal;      // bent spring along x (all columns together)
    takeda::Parameters transverse;        // bent spring along y
  };
  struct Parameters {
    double mass = 140.5;        // m_d [t], > 0 (paper, sec. 3)
    double inertia = 13090.0;   // I_d [t m^2], > 0 (paper, sec. 3)
    // L = 110 ft = 33.53 m (Saiidi, Vosooghi & Nelson 2013); W, gaps assumed (docs/bridge.md).
    DeckGeometry deck{33.53, 2.44, 0.0, 0.0127, 0.0127};
    double restitution = 0.0;   // eps_N in [0, 1] (paper: 0)
    double friction = 0.5;      // mu >= 0 (paper: 0.5)
    double damping_ratio_i = 0.08, damping_ratio_j = 0.08;  // Rayleigh ratios, >= 0 (paper 8 %)
    int damping_mode_i = 1, damping_mode_j = 3;            // 1-based modes, distinct, in 1..3
    std::vector<Bent> bents;    // >= 2 bents at >= 2 distinct positions (torsional stiffness)
    Eigen::Vector3d initial_position = Eigen::Vector3d::Zero();  // absolute (x, y, theta)
    Eigen::Vector3d initial_velocity = Eigen::Vector3d::Zero();
    void validate() const;      // throws std::invalid_argument naming the field
    // The benchmark's parameter set (docs/bridge.md): three bents of heights 1.83, 2.44,
    // 1.52 m at -L/4, 0, +L/4 (four equal spans), designed by BentDesign.
    static Parameters benchmark();
  };
  // Ground motion of one support; null means none in that direction.
  using Motion = std::shared_ptr<const GroundMotion>;
  struct SupportMotion {
    Motion longitudinal;  // along global x [m]
    Motion transverse;    // along global y [m]
    Motion rotation;      // seats only: rotation about the face point; the record's
                          // "acceleration" is the angular acceleration [rad/s^2]
  };
  struct Excitation {
    std::vector<SupportMotion> bents;  // empty, or one per bent
    std::array<SupportMotion, 2> seats;  // 0 = left, 1 = right
  };

  // Throws std::invalid_argument for bad parameters, a bent excitation of the wrong size, or
  // an initial penetration at t = 0.
  explicit Bridge(const Parameters& p, Excitation excitation = {});

  const Parameters& parameters() const { return p_; }
  const RayleighDamping& rayleigh_damping() const { return rayleigh_; }
  const Eigen::Matrix3d& initial_stiffness() const { return k0_; }
  const Eigen::Matrix3d& damping_matrix() const { return c_; }
  const Excitation& excitation() const { return excitation_; }
  // Pose of seat a (0 left, 1 right) at time t, with derivatives.
  PlanarMotion seat_motion(int seat, double t) const;
  // us_dot(t): velocity of the quasi-static deck displacement (see the header comment).
  Eigen::Vector3d quasi_static_velocity(double t) const;

  void forces(double t, const integrators::Vector& q, const integrators::Vector& u,
              integrators::Vector& f) override;
  void tangent(double t, const integrators::Vector& q, const integrators::Vector& u,
               integrators::Matrix& K, integrators::Matrix& C) override;
  bool tangent_changed() const override;
  void commit() override;
  void revert() override;
  int contacts() const override { return 4; }
  void contact_data(double t, const integrators::Vector& q, const integrators::Vector& u,
                    std::vector<integrators::ContactData>& out) const override;
  // g_N, W_N, what_N and far only (corner_contact_normal): a quarter of the work.
  void contact_normals(double t, const integrators::Vector& q, const integrators::Vector& u,
                       std::vector<integrators::ContactData>& out) const override;
  // damping = (u - us_dot)^T C (u - us_dot); ground = work rate of the bents' support
  // reactions on the support motion: -sum_j (F_x,j u_gxdot,j + F_y,j u_gydot,j)
  // - us_dot^T C (u - us_dot). The seats' work enters through the contact impulses (their
  // rheonomic terms what_N, what_T), which the system does not know. Spring forces are those
  // of the trial state of the last forces() call.
  integrators::PowerTerms power(double t, const integrators::Vector& q,
                                const integrators::Vector& u) const override;
  // stored: elastic energy of the springs; hysteretic: dissipated by them (trial state).
  integrators::EnergyState energy(double t, const integrators::Vector& q) const override;

 private:
  // Values of one distinct ground motion at the cached time.
  struct MotionValue {
    double d = 0.0, v = 0.0, a = 0.0;  // displacement, velocity, acceleration
  };
  // Where a support's components are in motions_; kNone: no motion in that direction.
  static constexpr int kNone = -1;
  struct SupportIndex {
    int longitudinal = kNone, transverse = kNone, rotation = kNone;
  };
  int motion_index(const Motion& m, bool needs_acceleration);
  // Evaluates every distinct motion at t unless the cache already holds t.
  void update_motions(double t) const;
  const MotionValue& value(int index) const {
    static constexpr MotionValue kZero{};
    return index == kNone ? kZero : values_[static_cast<std::size_t>(index)];
  }
  PlanarMotion seat_motion_cached(int seat) const;
  // Fills out[i] for the four corners with write(corner, q, u, seat motion, out[i]), the seats'
  // motion evaluated once at t: the loop shared by contact_data and contact_normals.
  template <class Write>
  void each_corner(double t, const integrators::Vector& q, const integrators::Vector& u,
                   std::vector<integrators::ContactData>& out, Write write) const;

  Parameters p_;
  Excitation excitation_;
  // The distinct motions of the excitation (supports sharing a GroundMotion object share an
  // entry), whether their acceleration is needed (seats), and each support's indices.
  std::vector<const GroundMotion*> motions_;
  std::vector<char> needs_acceleration_;
  std::vector<SupportIndex> bent_index_;
  std::array<SupportIndex, 2> seat_index_;
  mutable std::vector<MotionValue> values_;
  mutable Eigen::Vector3d us_dot_ = Eigen::Vector3d::Zero();  // us_dot at values_t_
  mutable double values_t_ = std::numeric_limits<double>::quiet_NaN();
  std::vector<takeda::Spring> springs_x_, springs_y_;
  std::array<CornerFace, 4> corners_;
  std::array<Eigen::Vector2d, 2> faces_;
  Eigen::Matrix3d k0_ = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d c_ = Eigen::Matrix3d::Zero();
  // us = sum_j (qs_x[j] u_gx,j + qs_y[j] u_gy,j): columns of K0^-1 k0_j b_j.
  std::vector<Eigen::Vector3d> qs_x_, qs_y_;
  RayleighDamping rayleigh_;
};

}  // namespace nsb::models
