#include "runs/trust.hpp"

#include "integrators/compliance.hpp"
#include "io/csv.hpp"
#include "runs/estimate.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace nsb::runs {

namespace {

// Penetrations below this depth [m] are round-off in the gap of a closed contact (1e-16
// relative to positions of order 10 m), not a result: they never warn.
constexpr double kRoundoffDepth = 1e-9;

// Three significant digits for messages (printf's %.3g).
std::string brief(double x) { return io::three_digits(x); }

// The compliance contacts that penetrate deeper than limits.compliance_penetration of their gap
// at t0 (the history's first row); a contact closed at t0 (a resting contact) has no gap to
// compare with and is not checked.
void compliance_penetration_warnings(const integrators::Recorder& history,
                                     const TrustLimits& limits, std::vector<std::string>& w) {
  if (history.rows() == 0) return;
  const auto& info = history.column_info();
  for (std::size_t c = 1; c < info.size(); ++c) {
    if (info[c].kind != integrators::ColumnKind::kGap) continue;
    const int contact = info[c].index;
    const double gap = history.at(0, c);
    if (!(gap > kRoundoffDepth)) continue;
    const integrators::StepExtremes& extremes = history.gap_until_removal(contact);
    const double depth = -extremes.min;
    if (depth > limits.compliance_penetration * gap) {
      w.push_back("penetration: contact " + std::to_string(contact + 1) + " penetrates " +
                  brief(depth) + " m at t = " + brief(extremes.t_min) + " s, " +
                  brief(100.0 * depth / gap) + " % of its gap " + brief(gap) +
                  " m at t0; the compliance model is trusted up to " +
                  brief(100.0 * limits.compliance_penetration) +
                  " % (raise the contact family's compliance_stiffness or "
                  "solver.contact_stiffness)");
    }
  }
}

// Under the compliance method, one warning per restitution e of the system's contacts whose
// single-impact restitution under the run's damping law (floored as the law floors it) differs
// from e by more than limits.restitution_mismatch, naming the contacts (1-based) that have it.
void restitution_warnings(const integrators::System& system,
                          const integrators::ComplianceOptions& options,
                          const TrustLimits& limits, std::vector<std::string>& w) {
  std::vector<integrators::ContactData> contacts = system.make_contact_buffer();
  system.contact_data(system.initial_time(), system.initial_position(),
                      system.initial_velocity(), contacts);
  std::vector<std::pair<double, std::vector<int>>> by_restitution;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const double e = contacts[i].restitution;
    auto same = std::find_if(by_restitution.begin(), by_restitution.end(),
                             [e](const auto& group) { return group.first == e; });
    if (same == by_restitution.end()) {
      by_restitution.push_back({e, {}});
      same = std::prev(by_restitution.end());
    }
    same->second.push_back(static_cast<int>(i) + 1);
  }
  for (const auto& [e, members] : by_restitution) {
    const double returned = integrators::hunt_crossley_restitution(
        integrators::damping_factor(options.law, e));
    const double asked = std::max(e, integrators::kMinLawRestitution);
    if (std::abs(returned - asked) <= limits.restitution_mismatch) continue;
    std::string list;
    for (const int c : members) list += (list.empty() ? "" : ", ") + std::to_string(c);
    w.push_back("restitution: solver.damping_law = " +
                std::string(integrators::to_string(options.law)) + " returns " +
                brief(returned) + " from an impact where the restitution is " + brief(e) +
                " (contacts " + list + "); the law holds within " +
                brief(limits.restitution_mismatch) + " (solver.damping_law = "
                "\"hunt_crossley_exact\" returns the restitution given; docs/compliance.md, "
                "\"Damping laws\")");
  }
}

}  // namespace

void TrustLimits::validate() const {
  auto bad = [](const char* field, const char* what) {
    throw std::invalid_argument(std::string("TrustLimits.") + field + ": " + what);
  };
  if (!(energy_error > 0.0 && energy_error < 1.0)) bad("energy_error", "must be in (0, 1)");
  if (!(penetration > 0.0 && penetration < 1.0)) bad("penetration", "must be in (0, 1)");
  if (!(compliance_penetration > 0.0 && compliance_penetration < 1.0)) {
    bad("compliance_penetration", "must be in (0, 1)");
  }
  if (!(steps_per_period >= 1.0 && std::isfinite(steps_per_period)))
    bad("steps_per_period", "must be finite and >= 1");
  if (!(record_steps > 0.0 && std::isfinite(record_steps))) bad("record_steps", "must be > 0");
  if (!(restitution_mismatch > 0.0 && restitution_mismatch < 1.0)) {
    bad("restitution_mismatch", "must be in (0, 1)");
  }
}

double shortest_period(integrators::System& system) {
  const std::vector<double> periods = integrators::natural_periods(system);
  return periods.empty() ? 0.0 : periods.back();
}

void check_initial_state(const integrators::System& system) {
  const integrators::Vector q = system.initial_position();
  const integrators::Vector u = system.initial_velocity();
  const double kinetic = 0.5 * u.dot(system.mass() * u);
  if (!std::isfinite(kinetic)) {
    throw std::invalid_argument(
        "the initial velocity (" + io::shortest(u.cwiseAbs().maxCoeff()) +
        " in magnitude) makes the kinetic energy 1/2 u^T M u overflow; expected an initial "
        "velocity whose energy is a finite number");
  }
  const double stored = system.energy(system.initial_time(), q).stored;
  if (!std::isfinite(stored)) {
    throw std::invalid_argument(
        "the initial position (" + io::shortest(q.cwiseAbs().maxCoeff()) +
        " in magnitude) makes the stored energy overflow; expected an initial position whose "
        "energy is a finite number");
  }
}

// A step equal to the record's sampling interval is not longer than it: the interval is the
// smallest difference of the record's times, which are i DT (and then times time_scale), so
// it can come out a few units of round-off below DT (0.005 s read from an .AT2 header gives
// 0.0049999999999999...).
constexpr double kRecordStepSlack = 1e-9;

std::vector<std::string> step_warnings(integrators::System& system,
                                       const integrators::RunConfig& config, double record_step,
                                       const TrustLimits& limits) {
  limits.validate();
  std::vector<std::string> w;
  if (const auto* c = std::get_if<integrators::ComplianceOptions>(&config)) {
    restitution_warnings(system, *c, limits, w);
  }
  const auto* mj = std::get_if<integrators::MoreauJeanOptions>(&config);
  // The adaptive methods, and Moreau–Jean with adaptive steps, choose their steps by their
  // tolerance.
  if (mj == nullptr || mj->local_tolerance > 0.0) return w;
  const double h = mj->step;
  const double period = shortest_period(system);
  if (std::isfinite(period) && h * limits.steps_per_period > period) {
    w.push_back("step_period: solver.step = " + brief(h) + " s resolves the shortest natural "
                "period " + brief(period) + " s with " + brief(period / h) +
                " steps; the method needs >= " + brief(limits.steps_per_period) +
                " (solver.step <= " + brief(period / limits.steps_per_period) + " s)");
  }
  if (record_step > 0.0 && h > limits.record_steps * record_step * (1.0 + kRecordStepSlack)) {
    w.push_back("step_record: solver.step = " + brief(h) + " s is longer than the record's "
                "sampling interval " + brief(record_step) + " s (after time_scale): samples of "
                "the excitation fall between steps; the method needs solver.step <= " +
                brief(limits.record_steps * record_step) + " s");
  }
  return w;
}

std::vector<std::string> result_warnings(const integrators::Recorder& history,
                                         const Digest& digest,
                                         const integrators::RunResult& result,
                                         const TrustLimits& limits) {
  limits.validate();
  std::vector<std::string> w;
  if (std::string a = accuracy_warning(digest); !a.empty()) w.push_back(std::move(a));
  const double e = result.energy.error;
  if (!std::isfinite(e)) {
    w.push_back("energy_balance: the energy balance is not a finite number; the run cannot "
                "be checked");
  } else if (e > limits.energy_error) {
    w.push_back("energy_balance: error " + brief(100.0 * e) + " % of the largest energy term; "
                "the method is trusted up to " + brief(100.0 * limits.energy_error) +
                " % (reduce solver.step or solver.tolerance)");
  }
  // With rigid contacts (Moreau–Jean, event-driven) g_N >= 0 is the contact law and a
  // penetration is its numerical violation. The compliance method's penetration is the Hertz
  // deformation of the contact, a result of its model, checked against the contact's gap.
  if (result.method == "compliance") {
    compliance_penetration_warnings(history, limits, w);
    return w;
  }
  const auto& info = history.column_info();
  for (std::size_t c = 1; c < info.size(); ++c) {
    if (info[c].kind != integrators::ColumnKind::kGap) continue;
    // Over the accepted steps; a removed contact (a broken shear key) is checked up to its
    // removal only: after it, its gap is no contact's.
    const int contact = info[c].index;
    const integrators::StepExtremes& gap = history.gap_until_removal(contact);
    const double lo = gap.min, hi = gap.max;
    if (!(lo < -kRoundoffDepth)) continue;
    const double depth = -lo;
    const double range = hi - lo;
    if (depth > limits.penetration * range) {
      w.push_back("penetration: contact " + std::to_string(contact + 1) + " penetrates " +
                  brief(depth) + " m at t = " + brief(gap.t_min) + " s, " +
                  brief(100.0 * depth / range) + " % of its range of gaps " + brief(range) +
                  " m; the method is trusted up to " + brief(100.0 * limits.penetration) +
                  " % (reduce solver.step)");
    }
  }
  return w;
}

}  // namespace nsb::runs
