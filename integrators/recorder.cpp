#include "integrators/recorder.hpp"

#include "io/spelling.hpp"

#include <cstdio>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace nsb::integrators {

std::string_view to_string(EventKind k) {
  return config::name_of(kEventKindNames, k);
}

std::optional<EventKind> parse_event_kind(std::string_view name) {
  return config::value_of(kEventKindNames, name);
}

std::string_view to_string(RunStatus s) {
  return config::name_of(kRunStatusNames, s);
}

std::optional<RunStatus> parse_run_status(std::string_view name) {
  return config::value_of(kRunStatusNames, name);
}

bool succeeded(RunStatus s) {
  return s == RunStatus::kCompleted || s == RunStatus::kCompletedWithFallbacks;
}

void record_removed_contacts(const System& system, double t, Recorder& recorder) {
  for (const LimitStateValue& v : system.limit_states()) {
    if (v.removes_contact > 0 && v.exceeded && v.time == t) {
      recorder.event(t, v.removes_contact, EventKind::kWarning,
                     v.name + " exceeded: contact removed");
      recorder.remove_contact(v.removes_contact - 1, t);
    }
  }
}

bool is_result(RunStatus s) { return succeeded(s) || s == RunStatus::kUnseated; }

void finish_status(RunResult& r, bool diverged, bool stalled, bool unseated, bool interrupted) {
  if (diverged) {
    r.status = RunStatus::kDiverged;
  } else if (interrupted) {
    r.status = RunStatus::kInterrupted;
  } else if (stalled) {
    r.status = RunStatus::kStalled;
  } else if (r.lcp_unsolved > 0) {
    r.status = RunStatus::kContactUnsolved;
  } else if (unseated) {
    r.status = RunStatus::kUnseated;
  } else if (r.lcp_fallbacks > 0) {
    r.status = RunStatus::kCompletedWithFallbacks;
  } else {
    r.status = RunStatus::kCompleted;
  }
}

void EnergyBalance::close() {
  const double lhs = kinetic + stored;
  const double rhs = initial + external + ground - damping - hysteretic + impacts + friction;
  double scale = 1.0;
  for (double v : {kinetic, stored, initial, external, ground, damping, hysteretic, impacts,
                   friction}) {
    scale = std::max(scale, std::abs(v));
  }
  error = std::abs(lhs - rhs) / scale;
}

std::string OutputGroups::names() const {
  std::string out;
  for (const auto& n : kOutputGroupNames) {
    if (!has(n.value)) continue;
    if (!out.empty()) out += ',';
    out += n.name;
  }
  return out;
}

OutputGroups OutputGroups::parse(std::string_view list) {
  OutputGroups g;
  while (!list.empty()) {
    const std::size_t comma = list.find(',');
    std::string_view name = list.substr(0, comma);
    list = comma == std::string_view::npos ? std::string_view{} : list.substr(comma + 1);
    while (!name.empty() && name.front() == ' ') name.remove_prefix(1);
    while (!name.empty() && name.back() == ' ') name.remove_suffix(1);
    if (name.empty()) continue;
    if (const auto v = config::value_of(kOutputGroupNames, name)) {
      g.add(*v);
      continue;
    }
    std::string allowed, best;
    std::size_t best_distance = std::max<std::size_t>(1, name.size() / 3) + 1;
    for (const auto& n : kOutputGroupNames) {
      allowed += (allowed.empty() ? "" : ", ") + std::string(n.name);
      const std::size_t d = io::edit_distance(name, n.name);
      if (d < best_distance) best = n.name, best_distance = d;
    }
    throw std::invalid_argument("unknown output group '" + std::string(name) + "'" +
                                (best.empty() ? "" : "; did you mean `" + best + "`?") +
                                " (allowed: " + allowed + ")");
  }
  return g;
}

Recorder::Recorder(const System& system, double sample_dt, OutputGroups groups)
    : system_(&system), groups_(groups), ndof_(system.dofs()), ncontacts_(system.contacts()),
      sample_dt_(sample_dt) {
  if (!(sample_dt >= 0.0) || !std::isfinite(sample_dt)) {
    throw std::invalid_argument("output.sample_dt must be a finite number >= 0 [s]");
  }
  removed_at_.assign(static_cast<std::size_t>(ncontacts_), std::numeric_limits<double>::infinity());
  observed_gaps_.assign(static_cast<std::size_t>(ncontacts_), 0.0);
  observed_gap_rates_.assign(static_cast<std::size_t>(ncontacts_), 0.0);
  column_info_.push_back({"t", ColumnKind::kTime, 0});
  int i = 0;
  for (auto& n : system.coordinate_names()) column_info_.push_back({n, ColumnKind::kCoordinate, i++});
  i = 0;
  for (auto& n : system.velocity_names()) column_info_.push_back({n, ColumnKind::kVelocity, i++});
  for (int c = 0; c < ncontacts_; ++c) {
    const std::string number = std::to_string(c + 1);
    column_info_.push_back({"gN" + number, ColumnKind::kGap, c});
    column_info_.push_back({"lambdaN" + number, ColumnKind::kNormalForce, c});
    column_info_.push_back({"lambdaT" + number, ColumnKind::kTangentForce, c});
  }
  column_info_.push_back({"energy_error", ColumnKind::kEnergyError, 0});
  int g = 0;
  auto add_group_column = [&](std::string name) {
    column_info_.push_back({std::move(name), ColumnKind::kGroup, g++});
  };
  for (OutputGroup sg : {OutputGroup::kBents, OutputGroup::kRelative, OutputGroup::kGround}) {
    std::vector<std::string> names;
    if (groups_.has(sg)) names = system.output_columns(sg);
    system_columns_.push_back(names.size());
    for (auto& n : names) add_group_column(std::move(n));
  }
  if (groups_.has(OutputGroup::kEnergy)) {
    for (const char* n : {"energy_kinetic", "energy_elastic", "energy_hysteretic",
                          "energy_damping", "energy_contact", "energy_input"}) {
      add_group_column(n);
    }
  }
  if (groups_.has(OutputGroup::kForces)) {
    for (int c = 0; c < ncontacts_; ++c) {
      add_group_column("fN" + std::to_string(c + 1));
      add_group_column("fT" + std::to_string(c + 1));
    }
    for (const auto& n : system.coordinate_names()) add_group_column("fsmooth_" + n);
    for (const auto& n : system.coordinate_names()) add_group_column("fcontact_" + n);
    last_impact_.assign(static_cast<std::size_t>(ncontacts_),
                        std::numeric_limits<double>::quiet_NaN());
    group_contacts_ = system.make_contact_buffer();
    mass_ = system.mass();
  }
  group_values_.assign(static_cast<std::size_t>(g), std::numeric_limits<double>::quiet_NaN());
  for (const auto& c : column_info_) columns_.push_back(c.name);
  extremes_.resize(columns_.size() - 1);
  gap_until_removal_.resize(static_cast<std::size_t>(ncontacts_));
}

void Recorder::evaluate_groups(double t, const Vector& q, const Vector& u, const Vector& lambda_n,
                               const Vector& lambda_t) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double* out = group_values_.data();
  const OutputGroup system_groups[] = {OutputGroup::kBents, OutputGroup::kRelative,
                                       OutputGroup::kGround};
  for (std::size_t k = 0; k < 3; ++k) {
    if (system_columns_[k] == 0) continue;
    system_->output_values(system_groups[k], t, q, u, out);
    out += system_columns_[k];
  }
  if (groups_.has(OutputGroup::kEnergy)) {
    // The balance's terms grouped so that (docs/outputs.md, "energy")
    //   kinetic + elastic + hysteretic + damping + contact - input = lhs - rhs
    // of EnergyBalance, whose magnitude is energy_error times its scale.
    const EnergyBalance* e = energy_;
    *out++ = e ? e->kinetic : kNaN;
    *out++ = e ? e->stored : kNaN;
    *out++ = e ? e->hysteretic : kNaN;
    *out++ = e ? e->damping : kNaN;
    *out++ = e ? -(e->impacts + e->friction) : kNaN;
    *out++ = e ? e->initial + e->external + e->ground : kNaN;
  }
  if (groups_.has(OutputGroup::kForces)) {
    // The contact force without the impulsive part: zero at a contact whose impact ended at
    // this state (Moreau-Jean's step impulse then holds a percussion; events.csv carries it).
    Vector fc = Vector::Zero(ndof_);
    system_->contact_data(t, q, u, group_contacts_);
    for (int i = 0; i < ncontacts_; ++i) {
      const auto ci = static_cast<std::size_t>(i);
      const bool impulsive = last_impact_[ci] == t;
      const double fn = impulsive ? 0.0 : (i < lambda_n.size() ? lambda_n[i] : 0.0);
      const double ft = impulsive ? 0.0 : (i < lambda_t.size() ? lambda_t[i] : 0.0);
      *out++ = fn;
      *out++ = ft;
      if (fn != 0.0) fc += fn * group_contacts_[ci].w_normal;
      if (ft != 0.0) fc += ft * group_contacts_[ci].w_tangent;
    }
    for (int k = 0; k < ndof_; ++k) *out++ = smooth_force_ ? (*smooth_force_)[k] : kNaN;
    for (int k = 0; k < ndof_; ++k) *out++ = fc[k];
  }
}

namespace {

// Appends one history row: t, q, u, (g_N, lambda_N, lambda_T) per contact, energy_error.
void write_row(std::vector<double>& data, int ndof, int ncontacts, double t, const Vector& q,
               const Vector& u, const std::vector<ContactData>& c, const Vector& lambda_n,
               const Vector& lambda_t, double energy_error) {
  data.push_back(t);
  for (int i = 0; i < ndof; ++i) data.push_back(q[i]);
  for (int i = 0; i < ndof; ++i) data.push_back(u[i]);
  for (int i = 0; i < ncontacts; ++i) {
    const auto k = static_cast<std::size_t>(i);
    data.push_back(k < c.size() ? c[k].gap_normal : 0.0);
    data.push_back(i < lambda_n.size() ? lambda_n[i] : 0.0);
    data.push_back(i < lambda_t.size() ? lambda_t[i] : 0.0);
  }
  data.push_back(energy_error);
}

}  // namespace

void Recorder::record(double t, const Vector& q, const Vector& u,
                      const std::vector<ContactData>& c, const Vector& lambda_n,
                      const Vector& lambda_t, double energy_error, bool evaluate) {
  write_row(data_, ndof_, ncontacts_, t, q, u, c, lambda_n, lambda_t, energy_error);
  if (!group_values_.empty()) {
    if (evaluate) evaluate_groups(t, q, u, lambda_n, lambda_t);
    data_.insert(data_.end(), group_values_.begin(), group_values_.end());
  }
}

void Recorder::advance_sampling(double t) {
  next_sample_ = (sample_dt_ > 0.0) ? (std::floor(t / sample_dt_ + 1e-9) + 1.0) * sample_dt_
                                    : -1e300;
}

void Recorder::sample(double t, const Vector& q, const Vector& u,
                      const std::vector<ContactData>& c, const Vector& lambda_n,
                      const Vector& lambda_t, double energy_error) {
  // A small slack keeps round-off in t from skipping a sample.
  if (!due(t)) return;
  record(t, q, u, c, lambda_n, lambda_t, energy_error, true);
  advance_sampling(t);
}

void Recorder::sample_now(double t, const Vector& q, const Vector& u,
                          const std::vector<ContactData>& c, const Vector& lambda_n,
                          const Vector& lambda_t, double energy_error) {
  observe(t, q, u, c, lambda_n, lambda_t, energy_error);
  record(t, q, u, c, lambda_n, lambda_t, energy_error, false);
}

void Recorder::observe(double t, const Vector& q, const Vector& u,
                       const std::vector<ContactData>& c, const Vector& lambda_n,
                       const Vector& lambda_t, double energy_error) {
  // The values in the order of sample_now's row, without t: extremes_[k] is column k + 1.
  std::size_t k = 0;
  for (int i = 0; i < ndof_; ++i) extremes_[k++].fold(q[i], t);
  for (int i = 0; i < ndof_; ++i) extremes_[k++].fold(u[i], t);
  for (int i = 0; i < ncontacts_; ++i) {
    const auto ci = static_cast<std::size_t>(i);
    const double gap = ci < c.size() ? c[ci].gap_normal : 0.0;
    extremes_[k++].fold(gap, t);
    if (t <= removed_at_[ci]) gap_until_removal_[ci].fold(gap, t);
    observed_gaps_[ci] = gap;
    observed_gap_rates_[ci] =
        ci < c.size() && c[ci].w_normal.size() == u.size() ? c[ci].gap_rate(u) : 0.0;
    extremes_[k++].fold(i < lambda_n.size() ? lambda_n[i] : 0.0, t);
    extremes_[k++].fold(i < lambda_t.size() ? lambda_t[i] : 0.0, t);
  }
  observed_t_ = t;
  for (std::size_t i : impacts_awaiting_rates_) events_[i].gap_rates_after = observed_gap_rates_;
  impacts_awaiting_rates_.clear();
  extremes_[k++].fold(energy_error, t);
  if (group_values_.empty()) return;
  evaluate_groups(t, q, u, lambda_n, lambda_t);
  for (double v : group_values_) extremes_[k++].fold(v, t);
}

void Recorder::snapshot_gaps(Event& e) {
  const double dt = std::isnan(observed_t_) ? 0.0 : e.t - observed_t_;
  e.gaps.resize(observed_gaps_.size());
  for (std::size_t i = 0; i < e.gaps.size(); ++i) {
    e.gaps[i] = observed_gaps_[i] + observed_gap_rates_[i] * dt;
  }
  e.gap_rates = observed_gap_rates_;
  e.gap_interval = dt;
  impacts_awaiting_rates_.push_back(events_.size());  // e is pushed next
}

void Recorder::event(double t, int contact, EventKind kind, std::string note) {
  Event e;
  e.t = t;
  e.contact = contact;
  e.kind = kind;
  e.note = std::move(note);
  if (kind == EventKind::kImpact) snapshot_gaps(e);
  events_.push_back(std::move(e));
}

void Recorder::impact(double t, int contact, double impulse_normal, double impulse_tangent) {
  Event e;
  e.t = t;
  e.contact = contact;
  e.kind = EventKind::kImpact;
  snapshot_gaps(e);
  if (groups_.has(OutputGroup::kImpulses)) {
    e.impulse_normal = impulse_normal;
    e.impulse_tangent = impulse_tangent;
  }
  if (!last_impact_.empty() && contact >= 1) {
    last_impact_[static_cast<std::size_t>(contact - 1)] = t;
  }
  events_.push_back(std::move(e));
}

void Recorder::set_impulses(std::size_t index, double impulse_normal, double impulse_tangent) {
  events_.at(index).impulse_normal = impulse_normal;
  events_.at(index).impulse_tangent = impulse_tangent;
}

std::size_t Recorder::column(std::string_view name) const {
  auto it = std::find(columns_.begin(), columns_.end(), name);
  if (it == columns_.end()) {
    throw std::out_of_range("no history column named '" + std::string(name) + "'");
  }
  return static_cast<std::size_t>(it - columns_.begin());
}

std::vector<double> Recorder::series(std::string_view name) const {
  const std::size_t col = column(name);
  std::vector<double> s(rows());
  for (std::size_t r = 0; r < s.size(); ++r) s[r] = at(r, col);
  return s;
}

std::size_t Recorder::count(EventKind kind) const {
  return static_cast<std::size_t>(std::count_if(
      events_.begin(), events_.end(), [kind](const Event& e) { return e.kind == kind; }));
}

}  // namespace nsb::integrators
