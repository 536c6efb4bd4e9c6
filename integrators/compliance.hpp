// The compliance ("gap element") approach of Shi & Dimitrakopoulos (2017), §4: every
// contact is a Hertz spring with nonlinear damping along the normal (eq. 9) and Coulomb
// friction regularised over a small slip velocity along the tangent (eq. 10). The contact
// forces enter the smooth equations of motion
//   M udot = f(t, q, u) + sum_i ( W_N,i lambda_N,i + W_T,i lambda_T,i ),   qdot = u,
// which are integrated by the L-stable Rosenbrock 4(3) method of Boost.Odeint's rosenbrock4
// (Hairer & Wanner's RODAS coefficients and Odeint's step-size controller, run on Eigen
// vectors because Odeint's uBLAS-based stepper does not compile under C++20 with Boost 1.74)
// with an analytic Jacobian (the system's tangent K, C plus the derivatives of the contact
// forces). See docs/compliance.md for the derivations and the measured behaviour.
//
// Sign convention (the printed eq. 9, -k (g_N)^1.5, is undefined for g_N < 0): with the
// penetration delta = -g_N > 0 and its rate deltadot = -gdot_N (> 0 while compressing),
//   lambda_N = max(0, k delta^1.5 (1 + chi deltadot / v_minus))   for g_N < 0, else 0,
// i.e. the Hunt–Crossley form with hysteresis damping xi = chi k / v_minus, where v_minus is
// the normal approach velocity at the closure of this contact and chi = chi(e) is set by the
// damping law from the contact's coefficient of restitution e (ContactData::restitution).
// lambda_N >= 0 pushes along W_N, the direction that opens the gap.
//
// Eq. (10), with sat(x) = max(-1, min(1, x)):
//   lambda_T = -mu lambda_N sat(gdot_T / eps_v),
// which is the printed law for |gdot_T| >= eps_v and its linear regularisation below.
//
// Units: kN, t, m, s, rad.
#pragma once

#include "integrators/recorder.hpp"
#include "integrators/run_hooks.hpp"
#include "integrators/system.hpp"

#include <array>
#include <atomic>
#include <span>

#include <string>
#include <string_view>
#include <vector>

namespace nsb::integrators {

// How the damping factor chi of lambda_N = k delta^1.5 (1 + chi deltadot / v_minus) follows
// from the coefficient of restitution e.
enum class DampingLaw {
  // chi = 3 (1 - e^2) / 4: Lankarani & Nikravesh (1990, J. Mech. Des. 112:369), the
  // "Hertzdamp" model of Muthukumar & DesRoches (2006, EESD 35:811), the paper's refs. 18-19.
  // Derived for e close to 1; at e = 0 it gives e_effective = 0.66 (docs/compliance.md).
  kHertzDamp,
  // chi = 8 (1 - e) / (5 e): Flores, Machado, Silva & Martins (2011, Multibody Syst. Dyn.
  // 25:357). Accurate at low e but unbounded at e = 0; e is floored at kMinLawRestitution.
  kFlores,
  // chi = the exact root of 1 - chi e = (1 + chi) exp(-chi (1 + e)), the closed-form
  // restitution of the Hunt–Crossley model (Carvalho & Martins 2019, Mech. Mach. Theory
  // 139:174; derived in docs/compliance.md). Exact for every e in (0, 1]; e is floored at
  // kMinLawRestitution, so e_set = 0 gives e_effective = kMinLawRestitution.
  kHuntCrossleyExact,
};

// Restitution below which kFlores and kHuntCrossleyExact use this value: chi ~ 1/e is
// unbounded at e = 0, and 1e-3 m/s out of 1 m/s is below anything the nonsmooth model
// distinguishes from a plastic impact.
inline constexpr double kMinLawRestitution = 1e-3;

// The one list of the laws' names (scene key solver.damping_law, summary.json).
inline constexpr std::array<config::Name<DampingLaw>, 3> kDampingLawNames{
    {{"hertzdamp", DampingLaw::kHertzDamp},
     {"flores", DampingLaw::kFlores},
     {"hunt_crossley_exact", DampingLaw::kHuntCrossleyExact}}};

std::string_view to_string(DampingLaw law);
// Throws std::invalid_argument naming the allowed names.
DampingLaw parse_damping_law(std::string_view name);
const std::vector<std::string>& damping_law_names();

// chi(e) of the law; e in [0, 1] (throws std::invalid_argument otherwise).
double damping_factor(DampingLaw law, double restitution);

// The exact coefficient of restitution of a single Hunt–Crossley impact with factor chi >= 0
// (no other forces): the root e in [0, 1] of 1 - chi e = (1 + chi) exp(-chi (1 + e)).
// Independent of k, of the approach velocity and of the (reduced) mass.
double hunt_crossley_restitution(double chi);

// Eq. (9): the normal force and its partial derivatives.
struct NormalForce {
  double force = 0.0;          // lambda_N [kN], >= 0
  double d_penetration = 0.0;  // d lambda_N / d delta [kN/m]
  double d_rate = 0.0;         // d lambda_N / d deltadot [kN s/m]
};
// k [kN/m^1.5] > 0, chi >= 0, v_minus [m/s] > 0; delta <= 0 gives zero force.
NormalForce hertz_damp_force(double k, double chi, double v_minus, double delta,
                             double delta_rate);

// Eq. (10): the regularised Coulomb force and its partial derivatives.
struct TangentForce {
  double force = 0.0;      // lambda_T [kN], along +W_T
  double d_normal = 0.0;   // d lambda_T / d lambda_N [-]
  double d_slip = 0.0;     // d lambda_T / d gdot_T [kN s/m]
};
TangentForce regularized_coulomb(double mu, double lambda_n, double slip_rate, double eps_v);

struct ComplianceOptions {
  static constexpr std::string_view kMethod = "compliance";  // solver.method in scene files
  double end_time = 1.0;               // final time [s], > the system's initial time
  double tolerance = 1e-8;             // Odeint absolute and relative tolerance, in (0, 0.1)
  double stiffness = 2.747e7;          // Hertz k [kN/m^1.5], > 0 (868.7 kN/mm^1.5,
                                       //   Muthukumar & DesRoches 2006)
  double stiffness_factor = 1.0;       // multiplies stiffness (the paper's 1e-4 ... 1e2), > 0
  double reference_mass = 140.5;       // colliding mass [t] at which a contact's default k is
                                       //   `stiffness` (the benchmark deck's m_d), >= 0; a
                                       //   contact that reports its colliding mass m_c gets
                                       //   stiffness * m_c / reference_mass; 0: no scaling
  double stick_slip_velocity = 1e-3;   // eps_v of eq. (10) [m/s], > 0
  DampingLaw law = DampingLaw::kHertzDamp;
  double max_step = 1e-3;              // largest step [s], > 0: keeps the recorded history
                                       //   (one row per accepted step) resolved
  double min_impact_velocity = 1e-3;   // floor on v_minus [m/s], > 0: a contact that closes
                                       //   at rest would otherwise get unbounded damping
  double initial_step = 1e-5;          // first trial step [s], > 0
  long max_steps = 50'000'000;         // accepted + rejected steps before giving up, > 0
  // The contact stiffness the run uses where a contact gives none: stiffness *
  // stiffness_factor [kN/m^1.5].
  double effective_stiffness() const { return stiffness * stiffness_factor; }
  // The schema of these fields (keys of a scene's [solver] table, units, ranges).
  static std::span<const config::Field<ComplianceOptions>> fields();
  void validate() const;               // throws std::invalid_argument naming the key
};

// The Hertz k of contact c [kN/m^1.5]: its own (ContactData::stiffness, a per-family scene key)
// times stiffness_factor; where it gives none and reports its colliding mass m_c, the default
// scaled to that mass, stiffness * (m_c / reference_mass) * stiffness_factor: Goldsmith's
// duration of a Hertz impact, t_c = 3.2181 (m^2 / (k^2 v))^(1/5), is the same for every mass
// when k grows as m (docs/compliance.md, "A default stiffness that scales with the bridge");
// otherwise options.effective_stiffness(). At m_c == reference_mass the ratio is exactly 1, so
// a contact of the reference mass gets effective_stiffness() to the last bit.
inline double contact_stiffness(const ComplianceOptions& options, const ContactData& c) {
  if (c.stiffness > 0.0) return c.stiffness * options.stiffness_factor;
  if (c.colliding_mass > 0.0 && options.reference_mass > 0.0) {
    return options.stiffness * (c.colliding_mass / options.reference_mass) *
           options.stiffness_factor;
  }
  return options.effective_stiffness();
}

// Integrates `system` from its initial state to options.end_time. Records a sample after
// every accepted step (the recorder thins them to its sample_dt), with lambdaN, lambdaT the
// contact forces [kN], and a kClose / kOpen event whenever a gap element closes / opens.
// Steps stop exactly at gap closures (located by bisection on the step's cubic Hermite
// interpolant), so contact onset is never stepped over. The system's internal state is
// committed after every accepted step. Returns the run's statistics with method
// "compliance": steps, rejected_steps, factorizations (one LU per attempted step).
// Throws std::invalid_argument for bad options; a step size that underflows or a
// non-finite state ends the run with completed = false and a message.
// progress is called every few thousand steps with the time reached; it may be empty. stop
// (RunHooks::stop) is read after each call; once true, the run ends as kInterrupted.
RunResult compliance(System& system, const ComplianceOptions& options, Recorder& recorder,
                     const Progress& progress = {}, const std::atomic<bool>* stop = nullptr);
// The run API's entry for this method (integrators/run.hpp). Compliance solves no contact
// problem, so hooks.contact_observer sees nothing; a restart in hooks is a bad call.
inline RunResult run_method(System& system, const ComplianceOptions& options, Recorder& recorder,
                            const Progress& progress, const RunHooks& hooks) {
  require_no_restart(hooks, ComplianceOptions::kMethod);
  return compliance(system, options, recorder, progress, hooks.stop);
}

}  // namespace nsb::integrators
