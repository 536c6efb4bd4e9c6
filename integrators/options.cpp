// The schema of the three methods' options: every field's scene key ([solver] table), unit,
// range and meaning, declared once. validate() checks these ranges, the scene reader reads the
// keys with them and docs/scenes.md's [solver] tables are generated from them.
#include "integrators/compliance.hpp"
#include "integrators/event_driven.hpp"
#include "integrators/moreau_jean.hpp"

#include <array>
#include <stdexcept>
#include <string>

namespace nsb::integrators {

namespace c = config;

namespace {

// The LCP solvers a scene's solver.lcp_solver may name, spelled as lcp::to_string spells them.
constexpr auto kSolverNames = [] {
  std::array<c::Name<lcp::Solver>, lcp::kSolvers.size()> names{};
  for (std::size_t i = 0; i < names.size(); ++i) {
    names[i] = {lcp::to_string(lcp::kSolvers[i]), lcp::kSolvers[i]};
  }
  return names;
}();

}  // namespace

std::span<const c::Field<MoreauJeanOptions>> MoreauJeanOptions::fields() {
  using O = MoreauJeanOptions;
  static const c::Field<O> f[] = {
      c::number<&O::end_time>("end_time", "s", c::positive(),
                              "final time (bridge with an excitation: default the end of the "
                              "longest support motion)"),
      c::number<&O::step>("step", "s", c::positive(),
                          "time step h; at most end_time; the last step is shortened to end "
                          "at end_time"),
      c::number<&O::theta>("theta", "-", c::closed(0.5, 1.0), "θ of the θ-method"),
      c::choice<&kSolverNames, &O::solver>("lcp_solver", "solver of each step's contact problem"),
      c::number<&O::lcp_tolerance>("lcp_tolerance", "-", c::positive(),
                                   "residual at which an LCP counts as solved"),
      c::boolean<&O::lcp_fallback>("lcp_fallback",
                                   "when the solver fails, try the fallback chain (Lemke, PGS, "
                                   "enumeration)"),
      c::number<&O::event_velocity_tolerance>(
          "event_velocity_tolerance", "m/s", c::positive(),
          "contact velocity below which a contact counts as resting or sticking, for events "
          "only"),
      c::number<&O::local_tolerance>(
          "local_tolerance", "-", c::closed_open(0.0, 1.0),
          "adaptive steps: relative local error of each coordinate per step; 0: the fixed "
          "step `step` (solver.adapt sets it to 0.01 × accuracy when not given)"),
      c::number<&O::min_step>("min_step", "s", c::positive(),
                              "adaptive steps: the smallest step, to which a step where a "
                              "contact impacts or changes state is reduced (solver.adapt sets "
                              "it to 0.01 s × accuracy, at most step, when not given)"),
      c::number<&O::max_step>("max_step", "s", c::non_negative(),
                              "adaptive steps: the largest step; 0: 10 × step (solver.adapt sets "
                              "it to 0.1 s × accuracy when not given)"),
  };
  return f;
}

void MoreauJeanOptions::validate() const {
  c::validate_fields<MoreauJeanOptions>(*this, fields());
  if (step > end_time) {
    throw std::invalid_argument("step: must be <= end_time (" + c::format_value(end_time) +
                                " s)");
  }
}

std::span<const c::Field<EventDrivenOptions>> EventDrivenOptions::fields() {
  using O = EventDrivenOptions;
  static const c::Field<O> f[] = {
      c::number<&O::end_time>("end_time", "s", c::positive(),
                              "final time (bridge with an excitation: default the end of the "
                              "longest support motion)"),
      c::number<&O::tolerance>("tolerance", "-", c::open(0.0, 1.0),
                               "absolute and relative error tolerance of the smooth phases"),
      c::choice<&kSolverNames, &O::solver>("lcp_solver", "solver of the impact and contact LCPs"),
      c::number<&O::lcp_tolerance>("lcp_tolerance", "-", c::positive(),
                                   "residual at which an LCP counts as solved"),
      c::number<&O::event_time_tolerance>("event_time_tolerance", "s", c::positive(),
                                          "width of the bracket that locates an event"),
      c::number<&O::closing_velocity>("closing_velocity", "m/s", c::non_negative(),
                                      "post-impact normal velocity below which the contact "
                                      "closes (Zeno); 0: 10 × tolerance"),
      c::number<&O::stick_velocity>("stick_velocity", "m/s", c::non_negative(),
                                    "slip velocity below which a closed contact may stick; "
                                    "0: 10 × tolerance"),
      c::number<&O::gap_tolerance>("gap_tolerance", "m", c::non_negative(),
                                   "gap below which a contact counts as touching at an event; "
                                   "0: 1e-9 m"),
      c::number<&O::max_step>("max_step", "s", c::non_negative(),
                              "largest smooth-phase step; 0: limited by the tolerance only"),
      c::number<&O::initial_step>("initial_step", "s", c::positive(),
                                  "first trial step of a smooth phase"),
      c::integer<&O::max_events_per_window>("max_events_per_window", c::closed(1, 1e9),
                                            "events in any event_window before the contact is "
                                            "forced closed (with a warning event)"),
      c::number<&O::event_window>("event_window", "s", c::positive(),
                                  "window of max_events_per_window"),
  };
  return f;
}

void EventDrivenOptions::validate() const { c::validate_fields<EventDrivenOptions>(*this, fields()); }

std::span<const c::Field<ComplianceOptions>> ComplianceOptions::fields() {
  using O = ComplianceOptions;
  static const c::Field<O> f[] = {
      c::number<&O::end_time>("end_time", "s", c::positive(),
                              "final time (bridge with an excitation: default the end of the "
                              "longest support motion)"),
      c::number<&O::tolerance>("tolerance", "-", c::open(0.0, 0.1),
                               "absolute and relative error tolerance of the Rosenbrock steps"),
      c::number<&O::stiffness>("contact_stiffness", "kN/m^1.5", c::positive(),
                               "Hertz k of eq. (9) (868.7 kN/mm^1.5, Muthukumar & DesRoches "
                               "2006)"),
      c::number<&O::stiffness_factor>("stiffness_factor", "-", c::positive(),
                                      "multiplies contact_stiffness (the paper's 1e-4 … 1e2)"),
      c::number<&O::reference_mass>("reference_mass", "t", c::non_negative(),
                                    "colliding mass at which a contact's default Hertz k is "
                                    "contact_stiffness (the benchmark deck's m_d); a bridge "
                                    "contact of colliding mass m_c gets contact_stiffness × "
                                    "m_c / reference_mass (Goldsmith's Hertz impact of one "
                                    "duration, docs/compliance.md); 0: no scaling"),
      c::choice<&kDampingLawNames, &O::law>("damping_law",
                                            "how χ of eq. (9) follows from the restitution "
                                            "(docs/compliance.md)"),
      c::number<&O::stick_slip_velocity>("stick_slip_velocity", "m/s", c::positive(),
                                         "ε of eq. (10)"),
      c::number<&O::max_step>("max_step", "s", c::positive(),
                              "largest step (one history row per accepted step)"),
      c::number<&O::min_impact_velocity>("min_impact_velocity", "m/s", c::positive(),
                                         "floor on the impact velocity v⁻ of eq. (9)"),
      c::number<&O::initial_step>("initial_step", "s", c::positive(), "first trial step"),
      c::integer<&O::max_steps>("max_steps", c::closed(1, 9e18),
                                "accepted and rejected steps before the run stalls"),
  };
  return f;
}

void ComplianceOptions::validate() const { c::validate_fields<ComplianceOptions>(*this, fields()); }

}  // namespace nsb::integrators
