#include "runs/digest.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace nsb::runs {

namespace {

using integrators::ColumnKind;
using integrators::Recorder;

// A column's peaks from its extremes over the accepted steps (Recorder::extremes()).
ColumnPeak column_peak(const Recorder& h, std::size_t c) {
  const integrators::StepExtremes& e = h.extremes()[c - 1];
  ColumnPeak p;
  p.column = h.columns()[c];
  const bool abs_is_max = std::abs(e.max) >= std::abs(e.min);
  p.max = e.max;
  p.t_max = e.t_max;
  p.min = e.min;
  p.t_min = e.t_min;
  p.abs_max = abs_is_max ? std::abs(e.max) : std::abs(e.min);
  p.t_abs_max = abs_is_max ? e.t_max : e.t_min;
  return p;
}

// An infinite value is the peak; NaN values are skipped (StepExtremes::magnitude).
CoordinatePeak coordinate_peak(const Recorder& h, std::size_t c) {
  CoordinatePeak p;
  p.name = h.columns()[c];
  if (h.rows() == 0 || h.extremes()[c - 1].steps == 0) {
    p.peak = p.residual = std::numeric_limits<double>::quiet_NaN();
    return p;
  }
  p.peak = h.extremes()[c - 1].magnitude;
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
      const integrators::StepExtremes& gap = history.gap_until_removal(info[c].index);
      if (gap.steps > 0) d.max_penetration = std::max(d.max_penetration, -gap.min);
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
