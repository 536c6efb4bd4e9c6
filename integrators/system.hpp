// The one interface through which every integrator (Moreau–Jean, event-driven, compliance)
// sees a nonsmooth mechanical system. Integrators never know what a bridge is.
//
// Equations of motion (eq. 2 of Shi & Dimitrakopoulos 2017):
//   M du = f(t, q, u) dt + W_N dP_N + W_T dP_T,     dq = u dt,
// with unilateral contacts g_N,i(t, q) >= 0 and planar Coulomb friction. Contacts may be
// rheonomic (moving obstacles):
//   gdot_N = W_N^T u + what_N(t, q),        gddot_N = W_N^T udot + wbar_N(t, q, u),
// and likewise for the tangential direction.
//
// Units: kN, t, m, s, rad throughout.
#pragma once

#include <Eigen/Dense>

#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace nsb::integrators {

using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;

// The optional groups of history columns a run may ask for (`[output] groups`,
// docs/outputs.md). Without any, history.csv and events.csv are the default files and the
// recorder does no work for them.
enum class OutputGroup {
  kBents,     // per bent: deformation and force, both directions (the system's)
  kRelative,  // each body's centre and deck corners relative to the ground (the system's)
  kGround,    // the supports' ground displacement, velocity and acceleration (the system's)
  kEnergy,    // the energy balance's components over time (the recorder's)
  kForces,    // contact forces without the impulsive part, and the generalized forces
  kImpulses,  // events.csv: each impact's normal and tangential impulse
};

// What a system says about one potential contact at (t, q, u).
struct ContactData {
  double gap_normal = 0.0;     // g_N [m]; > 0 open, < 0 penetrated
  Vector w_normal;             // W_N column, size ndof (generalized normal direction)
  Vector w_tangent;            // W_T column, size ndof
  double what_normal = 0.0;    // rheonomic part of gdot_N [m/s]
  double what_tangent = 0.0;   // rheonomic part of gdot_T [m/s]
  double wbar_normal = 0.0;    // gddot_N - W_N^T udot: the part independent of udot [m/s^2]
  double wbar_tangent = 0.0;   // gddot_T - W_T^T udot [m/s^2]
  double restitution = 0.0;    // Newton's coefficient eps_i in [0, 1]
  double friction = 0.0;       // Coulomb's coefficient mu_i >= 0
  double stiffness = 0.0;      // the compliance method's Hertz k of this contact [kN/m^1.5],
                               // > 0; 0: the run's default, scaled to colliding_mass
                               // (contact_stiffness in compliance.hpp; the rigid
                               // methods ignore it)
  double colliding_mass = 0.0; // the mass this contact stops [t], > 0: a body against a
                               // fixed face its body's mass, two bodies their reduced mass
                               // m_a m_b / (m_a + m_b); scales the compliance method's
                               // default k where `stiffness` is 0; 0: not scaled
  bool far = false;            // the system guarantees this contact cannot close within
                               // the current step bound; integrators may skip it

  double gap_rate(const Vector& u) const { return w_normal.dot(u) + what_normal; }
  double slip_rate(const Vector& u) const { return w_tangent.dot(u) + what_tangent; }
};

// Instantaneous energy flows, for the energy balance. Powers in kW = kN m/s.
struct PowerTerms {
  double damping = 0.0;   // rate of energy dissipated by viscous damping (>= 0)
  double ground = 0.0;    // rate of energy put in through support motion
  double external = 0.0;  // rate of work of applied loads (gravity, forcing)
};

// Energies held by the system's internal state [kJ].
struct EnergyState {
  double stored = 0.0;      // recoverable potential: elastic springs, gravity
  double hysteretic = 0.0;  // energy dissipated by hysteresis since t0 (>= 0)
};

// The end of an accepted step, as every integrator hands it to System::accept_step.
struct AcceptedStep {
  double t = 0.0;                      // time at the end of the step [s]
  double h = 0.0;                      // the step's length [s]
  const Vector* q = nullptr;           // q and u at t (sizes dofs())
  const Vector* u = nullptr;
  // The normal contact impulse of each contact over the step [kN s] (size contacts()):
  // Moreau–Jean's P_N of the step; event-driven: the impacts' impulses plus the integral of
  // the closed phases' lambda_N; compliance: the integral of the law's force. Divided by h it
  // is the step's mean contact force.
  const Vector* normal_impulse = nullptr;
  // The part of normal_impulse delivered at an instant (event-driven's impact problems) [kN s]:
  // a percussion, whose mean force over any interval that shrinks to its instant grows
  // without bound. nullptr: the method delivers none apart (Moreau–Jean, compliance).
  const Vector* impact_impulse = nullptr;
};

// What the structure did in an accepted step (System::accept_step).
enum class StepVerdict {
  kContinue,         // nothing that changes the problem
  kContactsRemoved,  // a contact is gone for the rest of the run (a broken shear key): it is
                     //   far from now on, and an integrator that keeps a contact set rebuilds it
  kUnseated,         // a deck end lost its seat: the run stops here (RunStatus::kUnseated)
};

// One limit state the system watches (docs/limit-states.md): a result of the run, not a
// failure. margin > 0 while the limit is not reached, in `unit`.
struct LimitStateValue {
  std::string name;            // summary.json "limit_states" key, e.g. "unseating_left"
  std::string unit;            // unit of margin ("m", "kN", "-", "rad")
  bool exceeded = false;
  double time = std::numeric_limits<double>::quiet_NaN();    // first time exceeded [s]
  double margin = std::numeric_limits<double>::quiet_NaN();  // smallest margin over the run
  int removes_contact = 0;     // 1-based contact this limit state removes once exceeded (a
                               //   broken key's contact); 0 for none
};

class System {
 public:
  virtual ~System() = default;

  // Number of generalized coordinates.
  virtual int dofs() const = 0;
  // Column names of q and u in outputs, e.g. {"x","y","theta"} and {"vx","vy","omega"}.
  virtual std::vector<std::string> coordinate_names() const = 0;
  virtual std::vector<std::string> velocity_names() const = 0;

  // Constant, symmetric positive definite mass matrix [t, t m^2].
  virtual const Matrix& mass() const = 0;

  // Initial state at t0 (the scene's). Sizes dofs().
  virtual double initial_time() const { return 0.0; }
  virtual Vector initial_position() const = 0;
  virtual Vector initial_velocity() const = 0;

  // Smooth generalized force f(t, q, u) (damping, springs, hysteresis, loads) [kN].
  // Evaluates the *trial* internal state from the committed one; commit() accepts it,
  // revert() drops it. Writes into f, already of size dofs(): no allocation.
  virtual void forces(double t, const Vector& q, const Vector& u, Vector& f) = 0;
  // The same force with every history-dependent element on the branch of its committed state,
  // extended as its tangent line (committed force + committed tangent x the change of its
  // deformation), the trial state left as it is: the force a step linearised about the
  // committed state starts from (docs/moreau-jean.md, "Smooth forces"). Evaluating the law
  // itself at (t_k+1, q_k) would move an element along a path the step does not take (its
  // support moves, its body not yet) and can put it on another branch. Default: forces(),
  // right for a system without history.
  virtual void forces_on_committed_branches(double t, const Vector& q, const Vector& u,
                                            Vector& f) {
    forces(t, q, u, f);
  }
  // Tangent matrices K = -df/dq and C = -df/du at the trial state [kN/m, kN s/m].
  virtual void tangent(double t, const Vector& q, const Vector& u, Matrix& K, Matrix& C) = 0;
  // True when the tangent returned by tangent() has changed since the last commit
  // (e.g. a hysteretic spring changed branch). A linear system always returns false.
  virtual bool tangent_changed() const { return false; }
  virtual void commit() {}
  virtual void revert() {}

  // Number of potential contacts, and their data at (t, q, u). `out` is sized contacts()
  // with every vector of size dofs(); implementations write in place.
  virtual int contacts() const = 0;
  virtual void contact_data(double t, const Vector& q, const Vector& u,
                            std::vector<ContactData>& out) const = 0;
  // The normal part of contact_data(): gap_normal, w_normal, what_normal and far of every
  // contact at (t, q, u), the same numbers; the other fields of `out` keep their values.
  // Enough to choose an index set and to evaluate gdot_N = W_N^T u + what_N, which is all a
  // time-stepping scheme needs at the start of most steps. The default calls contact_data();
  // a system whose full contact data cost much more overrides it.
  virtual void contact_normals(double t, const Vector& q, const Vector& u,
                               std::vector<ContactData>& out) const {
    contact_data(t, q, u, out);
  }

  // Called by every integrator once per accepted step, after commit(): the system updates its
  // limit states (a key that breaks, a seat that is lost) and says whether the problem
  // changed or the run must stop. The default watches nothing.
  virtual StepVerdict accept_step(const AcceptedStep& /*step*/) { return StepVerdict::kContinue; }
  // The limit states as they stand (after a run: over the whole run). The default: none.
  virtual std::vector<LimitStateValue> limit_states() const { return {}; }

  // The history columns the system adds for an output group (kBents, kRelative, kGround; none
  // for the others), and their values at a recorded state (t, q, u) written to
  // out[0, output_columns(g).size()). Called after commit(), so the committed internal state
  // is the state of the last accepted step. Must not change what the integration computes.
  // The default adds none.
  virtual std::vector<std::string> output_columns(OutputGroup /*g*/) const { return {}; }
  virtual void output_values(OutputGroup /*g*/, double /*t*/, const Vector& /*q*/,
                             const Vector& /*u*/, double* /*out*/) const {}

  // Energy bookkeeping at the trial state.
  virtual PowerTerms power(double t, const Vector& q, const Vector& u) const = 0;
  virtual EnergyState energy(double t, const Vector& q) const = 0;

  // Helper: a ContactData vector with every column sized for this system.
  std::vector<ContactData> make_contact_buffer() const {
    std::vector<ContactData> c(static_cast<std::size_t>(contacts()));
    for (auto& ci : c) {
      ci.w_normal = Vector::Zero(dofs());
      ci.w_tangent = Vector::Zero(dofs());
    }
    return c;
  }
};

// The defaults of the optional answers, so that a system writes only what it has: a unit
// mass matrix and a state at rest unless set_mass() / set_initial_state() say otherwise, no
// smooth force, no tangent (K = C = 0, right for forces independent of q and u), no internal
// state (commit and revert do nothing, the tangent never changes), no contacts (and normal
// contact data that are the full contact_data(), System's default), no energy flows and no
// stored energy. A system whose forces depend on q or u overrides tangent();
// one with contacts overrides contacts() and contact_data(); one with springs or loads
// overrides power() and energy().
class SystemBase : public System {
 public:
  int dofs() const override { return static_cast<int>(coordinates_.size()); }
  std::vector<std::string> coordinate_names() const override { return coordinates_; }
  std::vector<std::string> velocity_names() const override { return velocities_; }
  const Matrix& mass() const override { return mass_; }
  Vector initial_position() const override { return q0_; }
  Vector initial_velocity() const override { return u0_; }
  void forces(double t, const Vector& q, const Vector& u, Vector& f) override;
  void tangent(double t, const Vector& q, const Vector& u, Matrix& K, Matrix& C) override;
  int contacts() const override { return 0; }
  void contact_data(double t, const Vector& q, const Vector& u,
                    std::vector<ContactData>& out) const override;
  PowerTerms power(double t, const Vector& q, const Vector& u) const override;
  EnergyState energy(double t, const Vector& q) const override;

 protected:
  // One degree of freedom per coordinate name; the velocity names, of the same count, label
  // u in the outputs. Throws std::invalid_argument for no names or unequal counts.
  SystemBase(std::vector<std::string> coordinate_names, std::vector<std::string> velocity_names);
  // M, dofs() x dofs() (checked_inverse_mass checks it is symmetric positive definite).
  void set_mass(Matrix mass);
  // q0, u0 of size dofs().
  void set_initial_state(Vector position, Vector velocity);

 private:
  std::vector<std::string> coordinates_, velocities_;
  Matrix mass_;
  Vector q0_, u0_;
};

// A contact with a fixed obstacle (scleronomic: no rheonomic terms) and constant columns
// W_N, W_T, so that gddot = W^T udot exactly (wbar = 0); never far.
void set_fixed_contact(ContactData& c, double gap, const Vector& w_normal,
                       const Vector& w_tangent, double restitution, double friction);

// The natural periods 2 pi / omega [s] of the undamped linearization at the initial state,
// longest first: omega^2 are the eigenvalues of K phi = omega^2 M phi (generalized symmetric
// eigenproblem, Eigen::GeneralizedSelfAdjointEigenSolver), with K the symmetric part of the
// tangent stiffness at (t0, q0, u0) and M the mass matrix. A mode with omega^2 <= 0 (a
// mechanism) has an infinite period. Empty when K is not finite or the eigensolver fails.
// Evaluates the system's tangent at its initial state and reverts the trial state. The
// trust checks take the shortest of these periods (runs/trust.hpp), the spectral scaling of
// the records the longest (docs/bridge.md, "Target spectral accelerations").
std::vector<double> natural_periods(System& system);

// Checks what every integrator relies on and throws std::invalid_argument, the message
// prefixed with `method`, when the system breaks it: dofs() > 0, contacts() >= 0, a finite
// symmetric positive definite dofs() x dofs() mass matrix, and a finite initial state of size
// dofs(). Returns M^-1.
Matrix checked_inverse_mass(const System& system, std::string_view method);

}  // namespace nsb::integrators
