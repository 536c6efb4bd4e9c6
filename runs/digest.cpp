#include "runs/digest.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace nsb::runs {

namespace {

using integrators::ColumnKind;
using integrators::Recorder;

ColumnPeak column_peak(const Recorder& h, std::size_t c) {
  ColumnPeak p;
  p.column = h.columns()[c];
  double vmax = -INFINITY, vmin = INFINITY, tmax = NAN, tmin = NAN;
  for (std::size_t r = 0; r < h.rows(); ++r) {
    const double v = h.at(r, c);
    if (!std::isfinite(v)) continue;
    if (v > vmax) vmax = v, tmax = h.at(r, 0);
    if (v < vmin) vmin = v, tmin = h.at(r, 0);
  }
  const bool abs_is_max = std::abs(vmax) >= std::abs(vmin);
  p.max = vmax;
  p.t_max = tmax;
  p.min = vmin;
  p.t_min = tmin;
  p.abs_max = abs_is_max ? std::abs(vmax) : std::abs(vmin);
  p.t_abs_max = abs_is_max ? tmax : tmin;
  return p;
}

// std::max(p, NaN) keeps p: a NaN sample is skipped; an infinite one is the peak.
CoordinatePeak coordinate_peak(const Recorder& h, std::size_t c) {
  CoordinatePeak p;
  p.name = h.columns()[c];
  if (h.rows() == 0) {
    p.peak = p.residual = std::numeric_limits<double>::quiet_NaN();
    return p;
  }
  p.peak = 0.0;
  for (std::size_t r = 0; r < h.rows(); ++r) p.peak = std::max(p.peak, std::abs(h.at(r, c)));
  p.residual = h.at(h.rows() - 1, c);
  return p;
}

std::size_t kind_index(integrators::EventKind k) {
  const auto& names = integrators::kEventKindNames;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i].value == k) return i;
  }
  return 0;
}

void count_events(const Recorder& h, Digest& d) {
  int contacts = h.contacts();
  for (const auto& e : h.events()) contacts = std::max(contacts, e.contact);
  d.contact_events.resize(static_cast<std::size_t>(contacts));
  for (int i = 0; i < contacts; ++i) d.contact_events[static_cast<std::size_t>(i)].contact = i + 1;
  for (const auto& e : h.events()) {
    const std::size_t k = kind_index(e.kind);
    ++d.events[k];
    if (e.contact > 0) ++d.contact_events[static_cast<std::size_t>(e.contact - 1)].counts[k];
  }
}

}  // namespace

Digest make_digest(const Recorder& history, const integrators::RunResult& result,
                   std::vector<integrators::LimitStateValue> limit_states) {
  Digest d;
  d.limit_states = std::move(limit_states);
  const auto& info = history.column_info();
  for (std::size_t c = 1; c < info.size(); ++c) d.peaks.push_back(column_peak(history, c));
  for (std::size_t c = 0; c < info.size(); ++c) {
    if (info[c].kind == ColumnKind::kCoordinate) {
      d.coordinates.push_back(coordinate_peak(history, c));
    } else if (info[c].kind == ColumnKind::kGap) {
      // A removed contact (a broken shear key) counts up to its removal only.
      const double until = history.removed_at(info[c].index);
      for (std::size_t r = 0; r < history.rows() && history.at(r, 0) <= until; ++r) {
        d.max_penetration = std::max(d.max_penetration, -history.at(r, c));
      }
    }
  }
  count_events(history, d);
  d.energy = result.energy;
  d.warnings = result.warnings;
  d.integrator_warnings = result.warnings.size();
  return d;
}

std::int64_t Digest::count(integrators::EventKind kind) const { return events[kind_index(kind)]; }

const ColumnPeak* find_peak(const Digest& digest, const std::string& column) {
  for (const auto& p : digest.peaks) {
    if (p.column == column) return &p;
  }
  return nullptr;
}

}  // namespace nsb::runs
