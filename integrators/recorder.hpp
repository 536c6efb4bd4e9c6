// What a run records, shared by every integrator: a sampled time history, per-contact events,
// and the run's statistics with its energy balance. The column names and summary keys are a
// contract documented in docs/outputs.md.
#pragma once

#include "config/schema.hpp"
#include "integrators/system.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace nsb::integrators {

enum class EventKind {
  kImpact,   // an impact (velocity jump) at a contact
  kClose,    // a contact becomes closed (persistent contact starts)
  kOpen,     // a closed contact opens (lift-off)
  kStick,    // a closed contact starts to stick
  kSlip,     // a closed contact starts to slip (or reverses its slip direction)
  kWarning,  // the integrator reports something the user should see (see Event::note)
};
// The one list of event names (events.csv "kind", summary.json "events"), in this order.
inline constexpr std::array<config::Name<EventKind>, 6> kEventKindNames{
    {{"impact", EventKind::kImpact},
     {"close", EventKind::kClose},
     {"open", EventKind::kOpen},
     {"stick", EventKind::kStick},
     {"slip", EventKind::kSlip},
     {"warning", EventKind::kWarning}}};
std::string_view to_string(EventKind k);
// The kind of a name of kEventKindNames; std::nullopt for anything else.
std::optional<EventKind> parse_event_kind(std::string_view name);

struct Event {
  double t = 0.0;     // [s]
  int contact = 0;    // 1-based contact index; 0 when the event concerns no single contact
  EventKind kind = EventKind::kImpact;
  std::string note;   // free text, used by warnings
  // The impulses of an impact [kN s] (OutputGroup::kImpulses, docs/outputs.md, "impulses");
  // NaN for every other event and when the group is not asked for.
  double impulse_normal = std::numeric_limits<double>::quiet_NaN();
  double impulse_tangent = std::numeric_limits<double>::quiet_NaN();
  // An impact's configuration: every contact's gap [m] and gap rate [m/s] at t, before the
  // impact, extrapolated linearly from the last accepted step (the error estimate's check of
  // the order in which contacts close, runs/estimate.hpp); empty for every other event.
  std::vector<double> gaps{};
  std::vector<double> gap_rates{};
  double gap_interval = 0.0;  // [s]: t minus the last accepted step's time (Moreau–Jean: the
                              //   step that ends with the impact)
  std::vector<double> gap_rates_after{};  // [m/s] at the next accepted step (after the impact)
};

// The one list of output group names (`[output] groups`), in the order their columns follow
// energy_error in history.csv (kImpulses adds none: its columns are events.csv's).
inline constexpr std::array<config::Name<OutputGroup>, 6> kOutputGroupNames{
    {{"bents", OutputGroup::kBents},
     {"relative", OutputGroup::kRelative},
     {"ground", OutputGroup::kGround},
     {"energy", OutputGroup::kEnergy},
     {"forces", OutputGroup::kForces},
     {"impulses", OutputGroup::kImpulses}}};
// The groups a run asks for, a set of OutputGroup.
class OutputGroups {
 public:
  OutputGroups() = default;
  bool has(OutputGroup g) const { return (bits_ & bit(g)) != 0; }
  bool empty() const { return bits_ == 0; }
  void add(OutputGroup g) { bits_ |= bit(g); }
  // The names of the groups in the order of kOutputGroupNames, comma-separated.
  std::string names() const;
  // The set of a comma-separated list of names (spaces ignored, empty: none); throws
  // std::invalid_argument "unknown output group 'x'; did you mean `y`? (allowed: ...)".
  static OutputGroups parse(std::string_view list);

 private:
  static unsigned bit(OutputGroup g) { return 1U << static_cast<unsigned>(g); }
  unsigned bits_ = 0;
};

// Energy balance [kJ], accumulated from t0:
//   kinetic + stored = initial + external + ground - damping - hysteretic + impacts + friction
// where `impacts` and `friction` are the (non-positive) work of the contact impulses
// and forces. error = |lhs - rhs| / max(1, max of the magnitudes of the terms).
struct EnergyBalance {
  double kinetic = 0.0;
  double stored = 0.0;
  double initial = 0.0;     // kinetic + stored at t0
  double external = 0.0;    // work of applied loads
  double ground = 0.0;      // work put in through support motion
  double damping = 0.0;     // dissipated by viscous damping (>= 0)
  double hysteretic = 0.0;  // dissipated by hysteresis (>= 0)
  double impacts = 0.0;     // work of normal contact impulses/forces (<= 0 for eps <= 1)
  double friction = 0.0;    // work of tangential contact impulses/forces (<= 0)
  double error = 0.0;       // relative balance error, see above
  void close();             // computes `error` from the other fields
};

// How a run ended. Every integrator reports one; the app maps it to the exit code
// (docs/run-api.md): 0 for the two completed states and kUnseated, 1 for the others.
enum class RunStatus {
  kNotRun,                  // no integration took place (a default RunResult): nothing to use.
  kCompleted,               // reached end_time; every contact problem was solved by the
                            //   configured solver. The history is usable.
  kCompletedWithFallbacks,  // reached end_time; some contact problems needed the fallback
                            //   chain, and every one was solved. The history is usable.
  kContactUnsolved,         // reached end_time or stopped, but at least one contact problem
                            //   was solved by no solver of the chain: the history after
                            //   failure_time is not to be trusted.
  kDiverged,                // a non-finite state or energy: the run stopped at failure_time.
  kStalled,                 // an adaptive method could not advance (step size underflow, or
                            //   the event bound reached twice in a row): stopped at
                            //   failure_time.
  kUnseated,                // the system said a deck end lost its seat (StepVerdict::
                            //   kUnseated): the run stopped there, at failure_time. A result
                            //   (the collapse of the structure), not a numerical failure.
  kInterrupted,             // a stop was requested (RunHooks::stop: Ctrl-C): the run ended
                            //   at failure_time, short of end_time. Not a result: callers
                            //   write nothing of it.
};
// The one list of status names (summary.json "status", results.csv "status").
inline constexpr std::array<config::Name<RunStatus>, 8> kRunStatusNames{
    {{"not_run", RunStatus::kNotRun},
     {"completed", RunStatus::kCompleted},
     {"completed_with_fallbacks", RunStatus::kCompletedWithFallbacks},
     {"contact_unsolved", RunStatus::kContactUnsolved},
     {"diverged", RunStatus::kDiverged},
     {"stalled", RunStatus::kStalled},
     {"unseated", RunStatus::kUnseated},
     {"interrupted", RunStatus::kInterrupted}}};
std::string_view to_string(RunStatus s);
// The status of a name of kRunStatusNames; std::nullopt for anything else.
std::optional<RunStatus> parse_run_status(std::string_view name);
// True for kCompleted and kCompletedWithFallbacks.
bool succeeded(RunStatus s);
// True when the run's history is a result of the model up to its end: succeeded(s) or
// kUnseated (the structure collapsed; `nsbridge run` exits 0).
bool is_result(RunStatus s);

// The outcome and statistics of one run, written to summary.json. Every integrator returns
// one:  RunResult <method>(System&, const <Method>Options&, Recorder&).
struct RunResult {
  RunStatus status = RunStatus::kNotRun;  // set by finish_status() when a run ends
  std::string method;                  // "moreau", "event_driven" or "compliance"
  bool completed = false;              // reached end_time
  std::string message;                 // why it stopped early, if it did
  double end_time = 0.0;               // simulated time reached [s]
  double failure_time = 0.0;           // time of the first failure [s]; meaningful only
                                       //   when !succeeded(status)
  std::int64_t steps = 0;              // accepted steps
  std::int64_t rejected_steps = 0;
  std::int64_t steps_with_lcp = 0;     // steps or events that solved a contact problem
  std::int64_t lcp_solves = 0;
  std::int64_t lcp_fallbacks = 0;      // solves where the configured solver failed and the
                                       //   fallback chain produced the answer
  std::int64_t lcp_unsolved = 0;       // solves that no solver of the chain solved
  std::map<std::string, std::int64_t> lcp_status;  // count per lcp::Status name
  std::int64_t factorizations = 0;     // iteration-matrix factorizations
  double wall_time = 0.0;              // [s]
  EnergyBalance energy;
  std::vector<std::string> warnings;
};

// Sets r.status from what the run met, in order of severity: a non-finite state or energy
// (kDiverged), a stop request (kInterrupted), an adaptive method that could not advance
// (kStalled), a contact problem no
// solver of the chain solved (kContactUnsolved), one solved by a fallback
// (kCompletedWithFallbacks), else kCompleted; a run the system stopped as unseated is
// kUnseated unless it diverged, stalled or left a contact problem unsolved before. Each
// integrator calls it once, at its end, with what it recorded itself; failure_time is the
// integrator's.
void finish_status(RunResult& r, bool diverged, bool stalled, bool unseated = false,
                   bool interrupted = false);

// Called now and then with the simulated time reached [s], for a progress display. It must
// not throw; it may be empty. Every integrator takes one.
using Progress = std::function<void(double t)>;

// What a history column holds, so that callers find columns by type rather than by name.
enum class ColumnKind {
  kTime,         // t [s]
  kCoordinate,   // a generalized coordinate q_i
  kVelocity,     // a generalized velocity u_i
  kGap,          // g_N of a contact [m]
  kNormalForce,  // lambda_N of a contact [kN]
  kTangentForce, // lambda_T of a contact [kN]
  kEnergyError,  // the relative energy-balance error
  kGroup,        // a column of an output group (OutputGroups), after energy_error
};
struct Column {
  std::string name;
  ColumnKind kind = ColumnKind::kTime;
  int index = 0;  // 0-based coordinate, velocity or contact index; 0 for t and energy_error
};

// The extremes of one quantity over the accepted steps of a run, and when they occur (the
// first step that reaches each). NaN values are skipped; without a finite value max = -inf,
// min = +inf and the times NaN.
struct StepExtremes {
  double max = -std::numeric_limits<double>::infinity();
  double t_max = std::numeric_limits<double>::quiet_NaN();
  double min = std::numeric_limits<double>::infinity();
  double t_min = std::numeric_limits<double>::quiet_NaN();
  double magnitude = 0.0;  // max |v| over the non-NaN values, an infinite one included
  std::int64_t steps = 0;  // states folded in
  void fold(double v, double t) {
    ++steps;
    if (std::isnan(v)) return;
    magnitude = std::max(magnitude, std::abs(v));
    if (!std::isfinite(v)) return;
    if (v > max) max = v, t_max = t;
    if (v < min) min = v, t_min = t;
  }
};

// Collects the time history at a fixed sampling interval, every event, and the extremes of
// every column over every accepted step, recorded or not.
// Columns: t, <coordinate names>, <velocity names>, then per contact i = 1..m
// gN<i>, lambdaN<i>, lambdaT<i>, then energy_error, then the columns of the output groups
// asked for (docs/outputs.md), group by group in the order of kOutputGroupNames.
//
// Every integrator hands every accepted step's state (the initial and the final state
// included) to step(), observe() or sample_now(), so the peaks of a run (extremes()) are those
// of its steps: output.sample_dt changes the rows, never the peaks (docs/outputs.md). The
// event-driven method's rows between steps (from its dense output) go to sample() alone and
// do not count.
class Recorder {
 public:
  // sample_dt [s] >= 0; 0 records every call to sample(). groups: the optional columns
  // (none: the default files, and no work per step for them).
  Recorder(const System& system, double sample_dt, OutputGroups groups = {});

  // What the groups kEnergy and kForces read at every recorded state, kept up to date by the
  // integrator (both must hold the values at the state handed to step(), observe(),
  // sample() or sample_now(), and outlive the recorder's use): the run's energy balance
  // (closed at that state) and the smooth generalized force f(t, q, u) there. Until an
  // integrator calls it, those columns are NaN.
  void watch(const EnergyBalance* energy, const Vector* smooth_force) {
    energy_ = energy;
    smooth_force_ = smooth_force;
  }
  const OutputGroups& groups() const { return groups_; }

  // Records a row if t has reached the next sampling time (always the first call).
  // lambda_n, lambda_t are contact *forces* [kN] (impulse / step for time-stepping).
  // A row alone: it does not enter extremes() (the event-driven method's rows between steps).
  void sample(double t, const Vector& q, const Vector& u, const std::vector<ContactData>& c,
              const Vector& lambda_n, const Vector& lambda_t, double energy_error);
  // Records a row unconditionally (the initial and the final state): a step's state, which
  // enters extremes().
  void sample_now(double t, const Vector& q, const Vector& u, const std::vector<ContactData>& c,
                  const Vector& lambda_n, const Vector& lambda_t, double energy_error);
  // An accepted step's state: folds it into extremes() without recording a row.
  void observe(double t, const Vector& q, const Vector& u, const std::vector<ContactData>& c,
               const Vector& lambda_n, const Vector& lambda_t, double energy_error);
  // An accepted step's state: observe(), then sample().
  void step(double t, const Vector& q, const Vector& u, const std::vector<ContactData>& c,
            const Vector& lambda_n, const Vector& lambda_t, double energy_error) {
    observe(t, q, u, c, lambda_n, lambda_t, energy_error);
    if (!due(t)) return;
    record(t, q, u, c, lambda_n, lambda_t, energy_error, false);
    advance_sampling(t);
  }
  void event(double t, int contact, EventKind kind, std::string note = {});
  // An impact at a contact (1-based) with its normal and tangential impulse [kN s]; the
  // impulses are kept only under OutputGroup::kImpulses.
  void impact(double t, int contact, double impulse_normal, double impulse_tangent);
  // Sets the impulses of events()[index] (an event recorded before, whose impulses are known
  // only later: a compliance contact episode's, at its end).
  void set_impulses(std::size_t index, double impulse_normal, double impulse_tangent);
  // True when sample(t, ...) would record a row, so that an integrator computes what only a
  // recorded row needs (e.g. the energy balance) only then. Same rule as sample().
  bool due(double t) const { return !(t + 1e-9 * std::max(1.0, sample_dt_) < next_sample_); }

  // The sampling interval [s] given at construction (0 = every call to sample()).
  double sample_dt() const { return sample_dt_; }
  const std::vector<std::string>& columns() const { return columns_; }
  // The columns with their kinds, in the order of columns().
  const std::vector<Column>& column_info() const { return column_info_; }
  // The number of contacts recorded (gN, lambdaN, lambdaT columns each).
  int contacts() const { return ncontacts_; }
  std::size_t rows() const { return columns_.empty() ? 0 : data_.size() / columns_.size(); }
  double at(std::size_t row, std::size_t col) const { return data_[row * columns_.size() + col]; }
  // Index of a column by name; throws std::out_of_range if absent.
  std::size_t column(std::string_view name) const;
  // One column as a vector.
  std::vector<double> series(std::string_view name) const;
  const std::vector<Event>& events() const { return events_; }
  // The mass matrix of the system, kept under OutputGroup::kForces (summary.json "mass");
  // empty otherwise.
  const Matrix& mass() const { return mass_; }
  // Contact i (0-based) is gone from t on (System::accept_step removed it: a broken shear
  // key); its gap columns after t are no contact's (record_removed_contacts).
  void remove_contact(int i, double t) { removed_at_[static_cast<std::size_t>(i)] = t; }
  // The time contact i (0-based) was removed; +infinity while it was not.
  double removed_at(int i) const { return removed_at_[static_cast<std::size_t>(i)]; }
  std::size_t count(EventKind kind) const;
  // The extremes over the accepted steps of every column but t, in the order of columns()
  // (column c at c - 1).
  const std::vector<StepExtremes>& extremes() const { return extremes_; }
  // The extremes of contact i's (0-based) gap over the accepted steps up to its removal
  // (removed_at(i)) inclusive: after it, its gap column is no contact's.
  const StepExtremes& gap_until_removal(int i) const {
    return gap_until_removal_[static_cast<std::size_t>(i)];
  }

 private:
  // The output groups' values at a state into group_values_ (size: the group columns).
  void evaluate_groups(double t, const Vector& q, const Vector& u, const Vector& lambda_n,
                       const Vector& lambda_t);
  // Appends a row; evaluate: the group values are not yet those of this state (observe()
  // evaluated them otherwise).
  void record(double t, const Vector& q, const Vector& u, const std::vector<ContactData>& c,
              const Vector& lambda_n, const Vector& lambda_t, double energy_error, bool evaluate);
  // The next sampling time after a row sampled at t (sample(), step(); not sample_now()).
  void advance_sampling(double t);
  // Sets an impact event's gaps and gap rates at its time from the last accepted step.
  void snapshot_gaps(Event& e);

  const System* system_ = nullptr;
  OutputGroups groups_;
  const EnergyBalance* energy_ = nullptr;
  const Vector* smooth_force_ = nullptr;
  std::vector<std::size_t> system_columns_;  // per system group (bents, relative, ground)
  std::vector<double> group_values_;         // the group columns of the state last evaluated
  std::vector<double> last_impact_;          // per contact: time of its last impact [s]
  // The last accepted step's time [s] (NaN before the first), and its contacts' gaps [m] and
  // gap rates [m/s]: the configuration an impact's event extrapolates (Event::gaps).
  double observed_t_ = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> observed_gaps_;
  std::vector<double> observed_gap_rates_;
  std::vector<std::size_t> impacts_awaiting_rates_;  // events_ indices: gap_rates_after unset
  std::vector<ContactData> group_contacts_;  // kForces: the full contact data at a state
  Matrix mass_;                              // kForces: M
  int ndof_ = 0;
  int ncontacts_ = 0;
  double sample_dt_ = 0.0;
  double next_sample_ = -1e300;
  std::vector<std::string> columns_;
  std::vector<Column> column_info_;
  std::vector<double> data_;
  std::vector<Event> events_;
  std::vector<double> removed_at_;  // per contact [s]
  std::vector<StepExtremes> extremes_;           // per column but t
  std::vector<StepExtremes> gap_until_removal_;  // per contact
};

// After System::accept_step returned StepVerdict::kContactsRemoved at t: one "warning" event
// at t on each contact that a limit state exceeded at t removes (LimitStateValue::
// removes_contact), its note "<name> exceeded: contact removed" (a broken shear key). Only
// then, so its allocations do not recur per step.
void record_removed_contacts(const System& system, double t, Recorder& recorder);

}  // namespace nsb::integrators
