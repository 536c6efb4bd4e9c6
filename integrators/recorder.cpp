#include "integrators/recorder.hpp"

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

Recorder::Recorder(const System& system, double sample_dt)
    : ndof_(system.dofs()), ncontacts_(system.contacts()), sample_dt_(sample_dt) {
  if (!(sample_dt >= 0.0) || !std::isfinite(sample_dt)) {
    throw std::invalid_argument("output.sample_dt must be a finite number >= 0 [s]");
  }
  removed_at_.assign(static_cast<std::size_t>(ncontacts_), std::numeric_limits<double>::infinity());
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
  for (const auto& c : column_info_) columns_.push_back(c.name);
  extremes_.resize(columns_.size() - 1);
  gap_until_removal_.resize(static_cast<std::size_t>(ncontacts_));
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

void Recorder::sample(double t, const Vector& q, const Vector& u,
                      const std::vector<ContactData>& c, const Vector& lambda_n,
                      const Vector& lambda_t, double energy_error) {
  // A small slack keeps round-off in t from skipping a sample.
  if (t + 1e-9 * std::max(1.0, sample_dt_) < next_sample_) return;
  write_row(data_, ndof_, ncontacts_, t, q, u, c, lambda_n, lambda_t, energy_error);
  next_sample_ = (sample_dt_ > 0.0) ? (std::floor(t / sample_dt_ + 1e-9) + 1.0) * sample_dt_
                                    : -1e300;
}

void Recorder::sample_now(double t, const Vector& q, const Vector& u,
                          const std::vector<ContactData>& c, const Vector& lambda_n,
                          const Vector& lambda_t, double energy_error) {
  write_row(data_, ndof_, ncontacts_, t, q, u, c, lambda_n, lambda_t, energy_error);
  observe(t, q, u, c, lambda_n, lambda_t, energy_error);
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
    extremes_[k++].fold(i < lambda_n.size() ? lambda_n[i] : 0.0, t);
    extremes_[k++].fold(i < lambda_t.size() ? lambda_t[i] : 0.0, t);
  }
  extremes_[k].fold(energy_error, t);
}

void Recorder::event(double t, int contact, EventKind kind, std::string note) {
  events_.push_back(Event{t, contact, kind, std::move(note)});
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
