// Closed-form reference solutions for the simple benchmark systems (models/simple_systems.hpp)
// and for the frictional impact of a rigid planar deck against its abutments: the oracles of
// the tests and verification checks. The rotation criterion eta of eq. (1) of Shi &
// Dimitrakopoulos (2017), derived from the same impact law, is models/criterion.hpp. The
// derivations are summarised beside each function and written out in docs/analytic.md.
//
// Units: kN, t, m, s, rad (angles given in degrees where the name says so).
// Bad arguments (negative mass, e outside [0, 1], a case the closed form does not cover)
// throw std::invalid_argument naming the argument.
#pragma once

#include "models/criterion.hpp"
#include "models/deck_geometry.hpp"
#include "models/simple_systems.hpp"

#include <Eigen/Dense>

#include <array>
#include <vector>

namespace nsb::models::analytic {

// ---------------------------------------------------------------------------------------
// Bouncing ball (BouncingBall): free flight y(t) = y0 + v0 t - g t^2 / 2 between impacts,
// Newton's law v+ = -e v- at y = 0.
//   first impact:  t1 = (v0 + sqrt(v0^2 + 2 g h)) / g,  speed V1 = sqrt(v0^2 + 2 g h);
//   impact k:      speed V_k = e^(k-1) V1,  t_{k+1} = t_k + 2 e V_k / g;
//   accumulation:  t_inf = t1 + 2 e V1 / (g (1 - e)); from rest, sqrt(2h/g)(1 + e)/(1 - e);
//   energy after k impacts: E_k = m (e^k V1)^2 / 2 (kinetic at y = 0, potential m g y).
struct BallImpact {
  double time = 0.0;          // t_k [s]
  double speed_before = 0.0;  // |v-| [m/s]
  double speed_after = 0.0;   // v+ = e |v-| [m/s], upward
};
double ball_first_impact_time(const BouncingBall::Parameters& p);
double ball_first_impact_speed(const BouncingBall::Parameters& p);
// The first `count` impacts (count >= 0). With e = 0 there is one impact, then rest.
std::vector<BallImpact> ball_impacts(const BouncingBall::Parameters& p, int count);
// Time at which the infinitely many impacts accumulate and the ball comes to rest
// (+infinity for e = 1; the first impact time for e = 0). Requires g > 0.
double ball_accumulation_time(const BouncingBall::Parameters& p);
// Mechanical energy m v^2 / 2 + m g y after k >= 0 impacts (k = 0: the initial energy).
double ball_energy_after(const BouncingBall::Parameters& p, int k);
struct State1 {
  double position = 0.0;  // [m]
  double velocity = 0.0;  // [m/s]
};
// Exact state at time t >= 0 (at rest on the ground after the accumulation time).
State1 ball_state(const BouncingBall::Parameters& p, double t);

// ---------------------------------------------------------------------------------------
// Undamped, unforced oscillator against a rigid stop at x = d (ImpactOscillator with
// damping_ratio = 0 and no forcing). With w = sqrt(k/m), energy amplitude
// A = sqrt(x^2 + (v/w)^2) between impacts:
//   impact speed        V = w sqrt(A^2 - d^2)           (A > |d|, else no impact)
//   rebound             v+ = -e V, next amplitude A' = sqrt(d^2 + (e V / w)^2)
//   time to next impact T = 2 (pi - phi) / w,  phi = atan2(e V / w, d) in [0, pi]
// (the free orbit leaves the stop at phase phi and returns at phase 2 pi - phi).
double oscillator_impact_speed(double omega, double amplitude, double gap);
double oscillator_next_amplitude(double omega, double impact_speed, double gap,
                                 double restitution);
double oscillator_time_between_impacts(double omega, double impact_speed, double gap,
                                       double restitution);
struct OscillatorImpact {
  double time = 0.0;             // [s]
  double speed_before = 0.0;     // V [m/s], towards the stop
  double speed_after = 0.0;      // e V [m/s], away from the stop
  double amplitude_after = 0.0;  // A' [m]
};
// The first `count` impacts from the initial state (fewer if the orbit never reaches the
// stop, or if e = 0 with gap <= 0 where the mass stays on the stop). Requires stiffness > 0,
// damping_ratio = 0 and force_amplitude = 0 (throws otherwise).
std::vector<OscillatorImpact> oscillator_impacts(const ImpactOscillator::Parameters& p,
                                                 int count);
// Exact state at time t >= 0 (uses as many impacts as needed; for gap < 0 the impacts
// accumulate and the mass rests on the stop afterwards).
State1 oscillator_state(const ImpactOscillator::Parameters& p, double t);

// ---------------------------------------------------------------------------------------
// Block with Coulomb friction (SlidingBlock). Normal force N = m g cos(beta); the
// tangential load F_a(t) = F + F0 sin(2 pi f t) - m g sin(beta).
//   sliding (v != 0):  m a = F_a - mu N sgn(v);
//   sticking (v = 0):  stays stuck while |F_a| <= mu N, slips when |F_a| > mu N.
// With no driving force: stopping time v0/(mu g) and distance v0^2/(2 mu g).
double block_stopping_time(double v0, double mu, double g);
double block_stopping_distance(double v0, double mu, double g);
// True when a block at rest stays at rest under the tangential load F_a (|F_a| <= mu N).
bool block_sticks(double tangential_load, double mu, double normal_force);
// Exact state (x, vx) at time t >= 0 for a constant driving force (force_amplitude = 0):
// slide with constant deceleration, stop, then stick or slide again (throws if
// force_amplitude != 0).
State1 block_state(const SlidingBlock::Parameters& p, double t);

// Block starting at rest under a harmonic force F0 sin(2 pi f t) (constant force F allowed,
// beta allowed): the first slip phase in closed form, its end by bisection on the closed-form
// velocity v(t) = [F_a-integral - mu N sgn (t - t_b)] / m.
struct HarmonicSlip {
  bool slips = false;        // false when |F_a(t)| <= mu N for all t (stick forever)
  double start_time = 0.0;   // t_b: first time |F_a| = mu N with |F_a| increasing [s]
  double end_time = 0.0;     // first t > t_b with v(t) = 0 [s]
  double direction = 0.0;    // +1 or -1: the sign of the slip velocity
  double displacement = 0.0; // x(end_time) - x(start_time) [m]
};
HarmonicSlip block_harmonic_first_slip(const SlidingBlock::Parameters& p);

// Friction oscillator m x'' + k x = -mu m g sgn(x'), released from rest at x0 (no
// driving force). Each half cycle lasts pi / w and is harmonic about the shifted centre
// sgn(x_n) delta, delta = mu g / w^2, so successive turning points are
// x_{n+1} = sgn(x_n) (2 delta - |x_n|): the amplitude decays by 2 delta per half cycle,
// 4 mu g / w^2 per cycle. The motion stops at the first turning point with |x_n| <= delta.
struct FrictionOscillator {
  double omega = 1.0;          // w = sqrt(k/m) [rad/s], > 0
  double friction = 0.1;       // mu, >= 0
  double gravity = 9.81;       // g [m/s^2], >= 0
  double initial_position = 1.0;  // x0 [m], released from rest
  void validate() const;
};
// Turning points x_0 = x0, x_1, ..., x_n (the last one is the stick position).
std::vector<double> friction_oscillator_turning_points(const FrictionOscillator& p);
State1 friction_oscillator_state(const FrictionOscillator& p, double t);

// ---------------------------------------------------------------------------------------
// Frictional impact of a free rigid planar deck (3 DOF: x, y, theta; M = diag(m, m, I))
// against its rigid abutments, with the deck geometry of models/deck_geometry.hpp:
// parallelogram of length L along the axis and width W, skew alpha; corners
// (+-L/2 +- (W/2) tan(alpha), +-W/2), numbered 1 (left, +W/2), 2 (left, -W/2),
// 3 (right, +W/2), 4 (right, -W/2). At the right abutment n = (-cos a, sin a), at the left
// n = (cos a, -sin a); t = n rotated by +90 degrees. For a corner at r from the centre
// (deck at theta = 0): W_N = (n_x, n_y, r x n), W_T = (t_x, t_y, r x t).
struct DeckBody {
  double mass = 1.0;     // m [t], > 0
  double inertia = 1.0;  // I [t m^2], > 0
  DeckGeometry deck{.length = 1.0, .width = 1.0};  // L, W, alpha; the gaps play no part
  void validate() const;  // throws std::invalid_argument naming the field
};
// Corner position r (deck frame, theta = 0) and contact columns W_N, W_T. corner in 1..4.
Eigen::Vector2d deck_corner(const DeckGeometry& g, int corner);
struct ContactColumns {
  Eigen::Vector3d w_normal;
  Eigen::Vector3d w_tangent;
};
ContactColumns deck_contact_columns(const DeckGeometry& g, int corner);

// The impact problem of eq. (6) in its original (non-LCP) form, for m <= 4 contacts:
//   gdot+ = G Lambda + gdot-,  G = W^T M^-1 W (2m x 2m, normals first),
//   per contact i one of: inactive   Lambda_N = Lambda_T = 0, gdot_N0 = gdot_N+ + e gdot_N- >= 0;
//                         stick      gdot_N0 = 0, gdot_T+ = 0, |Lambda_T| <= mu Lambda_N;
//                         slide(s)   gdot_N0 = 0, Lambda_T = -s mu Lambda_N, s gdot_T+ >= 0,
//   with Lambda_N >= 0. Solved exactly by enumerating the 4^m cases, each a linear system.
// The case of one contact in that enumeration (not a smooth-phase mode: the integrators'
// ContactState also knows a closed frictionless contact).
enum class ImpactCase { kInactive, kStick, kSlidePositive, kSlideNegative };
struct ImpactProblem {
  Eigen::MatrixXd delassus;     // G, 2m x 2m
  Eigen::VectorXd gdot_minus;   // [gdot_N-; gdot_T-], size 2m
  Eigen::VectorXd restitution;  // e_i, size m
  Eigen::VectorXd friction;     // mu_i, size m
  void validate() const;
};
struct ImpactSolution {
  Eigen::VectorXd lambda_n, lambda_t;        // impulses [kN s]
  Eigen::VectorXd gdot_n_plus, gdot_t_plus;  // post-impact contact velocities [m/s]
  std::vector<ImpactCase> cases;  // the case of each contact
};
struct ImpactCases {
  // Every solution with distinct post-impact velocities (usually exactly one). The impulses
  // of one solution need not be unique: two corners of one end share W_T, so only their
  // total tangential impulse is determined; one representative is kept.
  std::vector<ImpactSolution> solutions;
  int singular_cases = 0;  // cases with a singular linear system (min-norm solution tried)
  bool unique() const { return solutions.size() == 1; }
};
ImpactCases solve_impact_by_cases(const ImpactProblem& p);

// Impact of the deck at the given corners (one or two, e.g. {3} or {3, 4}) with pre-impact
// velocity u- = (vx, vy, omega), all corners with restitution e and friction mu.
struct DeckImpact {
  Eigen::Vector3d velocity_after = Eigen::Vector3d::Zero();  // u+ of the first solution
  ImpactSolution contact;                                     // impulses and states
  ImpactProblem problem;                                      // the problem solved
  int solutions = 0;  // solutions with distinct post-impact velocities
};
DeckImpact deck_impact(const DeckBody& g, const std::vector<int>& corners,
                       const Eigen::Vector3d& velocity_before, double restitution,
                       double friction);


}  // namespace nsb::models::analytic
