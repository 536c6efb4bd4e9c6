// The state and steps of one event-driven run (the method: event_driven.hpp). The steps live
// in one file each:
//   event_phase.cpp       smooth-phase dynamics: closed-contact forces, the ODE right-hand
//                         side, the event indicators;
//   event_location.cpp    the root finder, and locate(): the earliest event of a step;
//   event_resolution.cpp  what happens at an event: Zeno guard, impact problem, contact
//                         problem, projection onto the constraints, mode changes;
//   event_driven.cpp      the driver: start, steps of the dense-output stepper, samples, end.
#pragma once

#include "integrators/contact_stage.hpp"
#include "integrators/event_driven.hpp"
#include "integrators/event_location.hpp"
#include "integrators/run_bookkeeping.hpp"
#include "io/csv.hpp"

// Only the Odeint parts used here: <boost/numeric/odeint.hpp> pulls in uBLAS, which does not
// compile as C++20.
#include <boost/numeric/odeint/stepper/controlled_runge_kutta.hpp>
#include <boost/numeric/odeint/stepper/dense_output_runge_kutta.hpp>
#include <boost/numeric/odeint/stepper/generation.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>

#include <cstdint>
#include <deque>
#include <limits>
#include <string>
#include <vector>

namespace nsb::integrators::detail {

namespace odeint = boost::numeric::odeint;
using State = std::vector<double>;
using Dopri = odeint::runge_kutta_dopri5<State>;
using Dense = odeint::result_of::make_dense_output<Dopri>::type;

// Integrated energy terms appended to (q, u) in the Odeint state, so that the energy balance
// is integrated to the same tolerance as the motion.
enum EnergyIndex { kDamping = 0, kGround, kExternal, kNormal, kFriction, kEnergyTerms };

// One event-driven run: the state between events and the steps that advance it.
class EventDriven {
 public:
  EventDriven(System& system, const EventDrivenOptions& options, Recorder& recorder,
              const Progress& progress, const RunHooks& hooks);
  RunResult run();

 private:
  // What one step of the dense-output stepper led to.
  enum class StepEnd { kGoOn, kEndTime, kStop };

  // ---- driver (event_driven.cpp) ----
  bool start();
  StepEnd step();
  bool attempt_step(double& ta, double& tb);
  int earliest_event(double ta, double tb, double& t_event);
  void sample_until(double t_stop);
  StepEnd after_event(int k_event);
  StepEnd after_smooth_step();
  void restart_phase(double dt);
  RunResult finish(bool completed);
  void phase_impulse(double ta, double tb);
  StepVerdict accept_step();
  void drop_removed_contacts();
  // How record_sample hands the state to the recorder: a row between steps (kBetweenSteps,
  // Recorder::sample), an accepted step's state (kStep, Recorder::step), or the initial or
  // final state (kForced, Recorder::sample_now).
  enum class SampleKind { kBetweenSteps, kStep, kForced };
  void record_sample(double t, const State& x, SampleKind kind);
  // The state at the end of an accepted step (t_, x_): into the peaks, and a row when every
  // step is recorded (sample_dt = 0).
  void record_step();
  double balance_error(double t, const State& x);

  // ---- phase dynamics (event_phase.cpp) ----
  template <class SquareMatrix>
  void solve_closed(int k, SquareMatrix& a,
                    Eigen::CompleteOrthogonalDecomposition<SquareMatrix>& cod);
  int closed_unknowns() const;
  void phase_forces(double t, const Vector& q, const Vector& u);
  void rhs(const State& x, State& dxdt, double t);
  void indicators(double t, const State& x);
  double indicator_at(double t, int k);
  double gap_rate_at(double t, int i);

  // ---- event location (event_location.cpp) ----
  double locate(int k, double ta, double tb, double ha, double hb);

  // ---- event resolution (event_resolution.cpp) ----
  bool stage_failed(double t, int contact, ContactStatus status, const char* problem);
  void project_positions(double t, Vector& q, const Vector& u);
  void project_velocities(double t, const Vector& q, Vector& u);
  void book_impulses(const Matrix& W, const Vector& impulse, const Vector& what,
                     const std::vector<bool>& tangential, const Vector& u_minus,
                     const Vector& u_plus);
  void book_stage_impulses(const std::vector<int>& index, const Vector& u_minus,
                           const Vector& u_plus);
  bool zeno_guard(double t, int trigger_contact, bool initial, bool& forced);
  void find_touching(double t, const Vector& q, const Vector& u, bool initial, bool& any_impact);
  bool impact_problem(double t, Vector& u, bool forced, int trigger_contact);
  void closure_candidates(const Vector& u);
  bool contact_problem(double t, Vector& q, Vector& u);
  void record_mode_changes(double t, const std::vector<ContactState>& old);
  bool handle_event(double t, State& x, int trigger_contact, bool initial);

  // ---- state ----
  void unpack(const State& x, Vector& q, Vector& u) const {
    for (int i = 0; i < n_; ++i) {
      q[i] = x[static_cast<std::size_t>(i)];
      u[i] = x[static_cast<std::size_t>(n_ + i)];
    }
  }
  void pack(const Vector& q, const Vector& u, State& x) const {
    for (int i = 0; i < n_; ++i) {
      x[static_cast<std::size_t>(i)] = q[i];
      x[static_cast<std::size_t>(n_ + i)] = u[i];
    }
  }
  double energy_term(const State& x, int k) const {
    return x[static_cast<std::size_t>(2 * n_ + k)];
  }
  static std::size_t idx(int i) { return static_cast<std::size_t>(i); }
  void warn(double t, int contact, const std::string& what) {
    rec_.event(t, contact, EventKind::kWarning, what);
    book_.result().warnings.push_back("t = " + io::three_digits(t) + " s, contact " +
                                      std::to_string(contact) + ": " + what);
  }

  System& sys_;
  const EventDrivenOptions& opt_;
  Recorder& rec_;
  RunBookkeeping book_;
  ContactStage stage_;
  EventRootFinder roots_;
  std::vector<int> touching_, candidates_;  // index sets of the impact and contact problems
  std::vector<double> slip_coupling_;       // -mu s of the contact problem's sliding contacts
  std::vector<ContactState> old_modes_;
  Vector u_plus_, a_free_, q_event_, u_event_;
  int n_ = 0, m_ = 0;
  double closing_velocity_ = 0.0, stick_velocity_ = 0.0, gap_tolerance_ = 0.0;
  double gap_shift_ = 0.0;  // penetration [m] that fires an impact without a closing speed
  double force_shift_ = 0.0, velocity_shift_ = 0.0;
  Matrix minv_;
  std::vector<ContactData> cbuf_;
  // The mode of each contact in the current smooth phase (contact_stage.hpp's ContactState,
  // shared with Moreau–Jean): a closed contact slides with the sign of its slip velocity
  // (kSlipPositive / kSlipNegative), or is kClosed when frictionless.
  std::vector<ContactState> modes_;
  Vector f_, q_, u_, udot_, lambda_n_, lambda_t_, h_;
  // Indicators at the start of the current step (h_prev_) and at its end (h_end_).
  Vector h_prev_, h_end_;
  // Workspace of phase_forces: columns of the closed contacts, R^T M^-1, the reduced system.
  static constexpr int kSmallClosed = 8;  // unknowns (closed + sticking) of the fixed-size path
  using SmallSquare = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kSmallClosed,
                                    kSmallClosed>;
  Matrix phase_b_, phase_r_, phase_rt_minv_, phase_large_;
  Vector phase_wbar_, phase_a_free_, phase_lambda_, phase_b_lambda_;
  SmallSquare phase_small_;
  Eigen::CompleteOrthogonalDecomposition<SmallSquare> phase_small_cod_;
  Eigen::CompleteOrthogonalDecomposition<Matrix> phase_large_cod_;
  State x_;   // the state (q, u, energy terms) at t_
  State xs_;  // the dense output at a sample or a trial time of the root finder
  double t_ = 0.0;
  Dense dense_ = odeint::make_dense_output(1e-8, 1e-8, Dopri());
  std::int64_t rhs_evaluations_ = 0;
  double impact_normal_work_ = 0.0, impact_friction_work_ = 0.0, impact_ground_work_ = 0.0;
  double initial_energy_ = 0.0;
  EnergyBalance energy_;  // the balance at the last sample
  double next_sample_ = -std::numeric_limits<double>::infinity();
  // The normal impulse of each contact over the step being accepted (System::accept_step):
  // the impacts' impulses plus the closed phase's lambda_N by the trapezoidal rule, from
  // lambda_start_ (lambda_N at the step's start) [kN s]; t_start_ is where the step began.
  Vector step_impulse_, impact_impulse_, lambda_start_;
  double t_start_ = 0.0;
  AcceptedStep accepted_;
  std::deque<double> recent_events_;
  double forced_closure_until_ = -std::numeric_limits<double>::infinity();
};

}  // namespace nsb::integrators::detail
