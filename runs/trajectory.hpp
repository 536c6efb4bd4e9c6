// A peak's error estimate from the trajectories of the run and its companion, not from their
// peaks alone (docs/error-estimates.md, "The trajectory bound"). For two runs a and b of one
// coordinate q,
//
//   | max_t |q_a(t)| - max_t |q_b(t)| |  <=  max_t | |q_a(t)| - |q_b(t)| |,
//
// which does not cancel when the two runs reach their peaks at different instants (another
// impact, another cycle), where the difference of the peaks can be near zero while both are
// off. The right side is taken over a window around the instants where either run peaks,
// on a grid on which both runs' coordinates are kept (TracedSystem). Moreau–Jean's estimate
// of a run with impacts is also at least kImpactShiftBound h |u|max: the method dates an
// impact at the end of the step that contains it, up to a step late, and a coordinate whose
// velocity jumps from u- to u+ at the impact ends up (u- - u+) times that delay away from
// the trajectory of the true instant; |u- - u+| <= |u-| + |u+| <= 2 |u|max.
#pragma once

#include "integrators/run.hpp"
#include "integrators/system.hpp"
#include "runs/digest.hpp"
#include "runs/estimate.hpp"

#include <cstddef>
#include <limits>
#include <vector>

namespace nsb::runs {

// The grid of the compared trajectories: about kTraceInterval, a whole multiple of
// Moreau–Jean's companion step so that both runs have a state on every grid time; the
// window: kPeakWindow before the earlier and after the later of the two runs' peak instants.
inline constexpr double kTraceInterval = 1e-3;  // [s]
inline constexpr double kPeakWindow = 0.1;      // [s]

// The bound of a velocity jump at an impact in units of the coordinate's largest speed: a
// rotation or a tangential velocity can reverse at an eccentric impact (u+ = -u-).
inline constexpr double kImpactShiftBound = 2.0;

// The generalized coordinates of a run at the times t0 + k dt, k = 0, 1, ...
struct CoordinateTrace {
  double t0 = 0.0;
  double dt = 0.0;  // [s]; 0: nothing kept
  int dofs = 0;
  std::vector<double> q;  // q at t0 + k dt in [k dofs, (k + 1) dofs)
  std::size_t rows() const { return dofs > 0 ? q.size() / static_cast<std::size_t>(dofs) : 0; }
};

// The system `inner`, unchanged, that keeps a CoordinateTrace of the accepted steps
// (System::accept_step, which every integrator calls once per accepted step): each grid time
// gets q linearly interpolated between the two accepted steps around it, the initial state
// filling the grid times up to t0. Every call is forwarded as it is, so a run of the traced
// system is bit for bit the run of `inner`. duration [s]: the run's, for which the trace is
// sized once, so that no step allocates.
class TracedSystem final : public integrators::System {
 public:
  TracedSystem(integrators::System& inner, double dt, double duration);
  const CoordinateTrace& trace() const { return trace_; }

  int dofs() const override { return inner_.dofs(); }
  std::vector<std::string> coordinate_names() const override { return inner_.coordinate_names(); }
  std::vector<std::string> velocity_names() const override { return inner_.velocity_names(); }
  const integrators::Matrix& mass() const override { return inner_.mass(); }
  double initial_time() const override { return inner_.initial_time(); }
  integrators::Vector initial_position() const override { return inner_.initial_position(); }
  integrators::Vector initial_velocity() const override { return inner_.initial_velocity(); }
  void forces(double t, const integrators::Vector& q, const integrators::Vector& u,
              integrators::Vector& f) override {
    inner_.forces(t, q, u, f);
  }
  void forces_on_committed_branches(double t, const integrators::Vector& q,
                                    const integrators::Vector& u,
                                    integrators::Vector& f) override {
    inner_.forces_on_committed_branches(t, q, u, f);
  }
  void tangent(double t, const integrators::Vector& q, const integrators::Vector& u,
               integrators::Matrix& K, integrators::Matrix& C) override {
    inner_.tangent(t, q, u, K, C);
  }
  bool tangent_changed() const override { return inner_.tangent_changed(); }
  void commit() override { inner_.commit(); }
  void revert() override { inner_.revert(); }
  int contacts() const override { return inner_.contacts(); }
  void contact_data(double t, const integrators::Vector& q, const integrators::Vector& u,
                    std::vector<integrators::ContactData>& out) const override {
    inner_.contact_data(t, q, u, out);
  }
  void contact_normals(double t, const integrators::Vector& q, const integrators::Vector& u,
                       std::vector<integrators::ContactData>& out) const override {
    inner_.contact_normals(t, q, u, out);
  }
  integrators::StepVerdict accept_step(const integrators::AcceptedStep& step) override;
  std::vector<integrators::LimitStateValue> limit_states() const override {
    return inner_.limit_states();
  }
  std::vector<std::string> output_columns(integrators::OutputGroup g) const override {
    return inner_.output_columns(g);
  }
  void output_values(integrators::OutputGroup g, double t, const integrators::Vector& q,
                     const integrators::Vector& u, double* out) const override {
    inner_.output_values(g, t, q, u, out);
  }
  integrators::PowerTerms power(double t, const integrators::Vector& q,
                                const integrators::Vector& u) const override {
    return inner_.power(t, q, u);
  }
  integrators::EnergyState energy(double t, const integrators::Vector& q) const override {
    return inner_.energy(t, q);
  }

 private:
  // Appends the grid times up to t, interpolated between the last state kept and (t, q).
  void keep(double t, const integrators::Vector& q);

  integrators::System& inner_;
  CoordinateTrace trace_;
  double last_t_ = std::numeric_limits<double>::quiet_NaN();
  integrators::Vector last_q_;
};

// The grid interval of the compared trajectories for a run with these options [s]: the
// Moreau–Jean companion's step times the whole number nearest kTraceInterval / (that step),
// at least 1; kTraceInterval for the adaptive methods.
double trace_interval(const integrators::RunConfig& config);

// The largest | |q_i^a| - |q_i^b| | over the grid times in [from, to] that both traces hold;
// 0 when they hold none there or their grids differ.
double trace_difference(const CoordinateTrace& a, const CoordinateTrace& b, int i, double from,
                        double to);

// Raises the errors of the run's generalized coordinates (digest coordinates, and their
// columns in peaks) to the trajectory bound above, times the plan's factor, and for
// Moreau–Jean with an impact in either run to at least h |u_i|max over the run's steps
// (run_history's velocity columns).
// apply_estimate has set the errors from the peaks before.
void bound_by_trajectories(Digest& run, const integrators::Recorder& run_history,
                           const CoordinateTrace& run_trace, const Digest& companion,
                           const CoordinateTrace& companion_trace, const CompanionPlan& plan);

}  // namespace nsb::runs
