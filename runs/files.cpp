#include "runs/files.hpp"

#include "io/csv.hpp"
#include "io/files.hpp"
#include "io/json.hpp"

#include <cmath>
#include <initializer_list>
#include <limits>
#include <string_view>
#include <utility>

namespace nsb::runs {

namespace {

using integrators::EventKind;
using integrators::RunResult;

// summary.json under construction: one key per line, two spaces in, as docs/outputs.md shows.
struct JsonText {
  std::string o = "{\n";
  void key(std::string_view k) {
    o += "  ";
    o += io::json_string(k);
    o += ": ";
  }
  void text(std::string_view k, std::string_view v) {
    key(k);
    o += io::json_string(v) + ",\n";
  }
  void number(std::string_view k, double v) {
    key(k);
    io::append_json_number(o, v);
    o += ",\n";
  }
  void integer(std::string_view k, std::int64_t v) {
    key(k);
    io::append_integer(o, v);
    o += ",\n";
  }
};

// The run's status and statistics, "method" through "samples".
void write_result(JsonText& j, const RunResult& r, std::size_t samples) {
  j.text("method", r.method);
  j.text("status", integrators::to_string(r.status));
  j.key("completed");
  j.o += r.completed ? "true,\n" : "false,\n";
  j.text("message", r.message);
  j.number("end_time", r.end_time);
  j.integer("steps", r.steps);
  j.integer("rejected_steps", r.rejected_steps);
  j.integer("steps_with_lcp", r.steps_with_lcp);
  j.integer("lcp_solves", r.lcp_solves);
  j.integer("lcp_fallbacks", r.lcp_fallbacks);
  j.integer("lcp_unsolved", r.lcp_unsolved);
  if (!integrators::succeeded(r.status)) j.number("failure_time", r.failure_time);
  j.key("lcp_status");
  j.o += "{";
  bool first = true;
  for (const auto& [name, count] : r.lcp_status) {
    j.o += first ? "" : ", ";
    first = false;
    j.o += io::json_string(name) + ": ";
    io::append_integer(j.o, count);
  }
  j.o += "},\n";
  j.integer("factorizations", r.factorizations);
  j.number("wall_time", r.wall_time);
  j.integer("samples", static_cast<std::int64_t>(samples));
}

void write_energy(JsonText& j, const integrators::EnergyBalance& e) {
  j.key("energy");
  j.o += "{";
  const std::pair<const char*, double> terms[] = {
      {"kinetic", e.kinetic},       {"stored", e.stored},   {"initial", e.initial},
      {"external", e.external},     {"ground", e.ground},   {"damping", e.damping},
      {"hysteretic", e.hysteretic}, {"impacts", e.impacts}, {"friction", e.friction},
      {"error", e.error}};
  for (std::size_t i = 0; i < std::size(terms); ++i) {
    j.o += i ? ", " : "";
    j.o += io::json_string(terms[i].first) + ": ";
    io::append_json_number(j.o, terms[i].second);
  }
  j.o += "},\n";
}

// Event counts, in total and per contact (1-based; contact 0 = not tied to a contact).
void write_events(JsonText& j, const Digest& d) {
  const auto& kinds = integrators::kEventKindNames;
  j.key("events");
  j.o += "{";
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    j.o += i ? ", " : "";
    j.o += io::json_string(kinds[i].name) + ": ";
    io::append_integer(j.o, d.events[i]);
  }
  j.o += "},\n";
  j.key("contact_events");
  j.o += "[";
  for (std::size_t c = 0; c < d.contact_events.size(); ++c) {
    j.o += c ? ", " : "";
    j.o += "{\"contact\": ";
    io::append_integer(j.o, d.contact_events[c].contact);
    for (std::size_t i = 0; i < kinds.size(); ++i) {
      if (kinds[i].value == EventKind::kWarning) continue;
      j.o += ", " + io::json_string(kinds[i].name) + ": ";
      io::append_integer(j.o, d.contact_events[c].counts[i]);
    }
    j.o += "}";
  }
  j.o += "],\n";
}

// The family and name of each contact (1-based), when the model names them.
void write_contacts(JsonText& j, const Digest& d) {
  j.key("contacts");
  j.o += "[";
  for (std::size_t c = 0; c < d.contacts.size(); ++c) {
    j.o += c ? ", " : "";
    j.o += "{\"contact\": ";
    io::append_integer(j.o, static_cast<std::int64_t>(c + 1));
    j.o += ", \"family\": " + io::json_string(d.contacts[c].family);
    j.o += ", \"name\": " + io::json_string(d.contacts[c].name) + "}";
  }
  j.o += "],\n";
}

// Peaks of every history column but t: extreme values and when they occur.
void write_peaks(JsonText& j, const Digest& d) {
  j.key("peaks");
  j.o += "{";
  bool first = true;
  for (const ColumnPeak& p : d.peaks) {
    j.o += first ? "\n    " : ",\n    ";
    first = false;
    const std::pair<const char*, double> fields[] = {
        {"max", p.max},         {"t_max", p.t_max},     {"min", p.min},
        {"t_min", p.t_min},     {"abs_max", p.abs_max}, {"t_abs_max", p.t_abs_max},
        {"error", p.error}};
    j.o += io::json_string(p.column) + ": {";
    for (std::size_t i = 0; i < std::size(fields); ++i) {
      j.o += i ? ", " : "";
      j.o += io::json_string(fields[i].first) + ": ";
      io::append_json_number(j.o, fields[i].second);
    }
    j.o += "}";
  }
  j.o += first ? "},\n" : "\n  },\n";
}

// The scaling of each excitation component present: "transverse", then "longitudinal".
void write_input(JsonText& j, const models::InputMotion& in) {
  j.key("input");
  j.o += "{";
  bool first = true;
  for (const auto& [name, c] : {std::pair{"transverse", &in.transverse},
                                std::pair{"longitudinal", &in.longitudinal}}) {
    if (!*c) continue;
    j.o += first ? "" : ", ";
    first = false;
    const std::pair<const char*, double> fields[] = {{"pga_g", (*c)->pga_g},
                                                     {"sa_g", (*c)->sa_g},
                                                     {"sa_period", (*c)->sa_period},
                                                     {"sa_damping", (*c)->sa_damping},
                                                     {"scale_factor", (*c)->scale_factor}};
    j.o += io::json_string(name) + ": {";
    for (std::size_t i = 0; i < std::size(fields); ++i) {
      j.o += i ? ", " : "";
      j.o += io::json_string(fields[i].first) + ": ";
      io::append_json_number(j.o, fields[i].second);
    }
    j.o += "}";
  }
  j.o += "},\n";
}

// The system's limit states (docs/limit-states.md): whether each was exceeded, first when
// (null when not), its smallest margin over the run and the margin's unit.
void write_limit_states(JsonText& j, const Digest& d) {
  j.key("limit_states");
  j.o += "{";
  bool first = true;
  for (const auto& v : d.limit_states) {
    j.o += first ? "\n    " : ",\n    ";
    first = false;
    j.o += io::json_string(v.name) + ": {\"exceeded\": ";
    j.o += v.exceeded ? "true" : "false";
    j.o += ", \"time\": ";
    io::append_json_number(j.o, v.time);
    j.o += ", \"margin\": ";
    io::append_json_number(j.o, v.margin);
    j.o += ", \"unit\": " + io::json_string(v.unit) + "}";
  }
  j.o += first ? "},\n" : "\n  },\n";
}

// `"name": {"k1": v1, ...}` of numbers, a null for each non-finite one.
void append_object(std::string& o, std::string_view name,
                   std::initializer_list<std::pair<const char*, double>> fields) {
  o += io::json_string(name) + ": {";
  bool first = true;
  for (const auto& [k, v] : fields) {
    o += first ? "" : ", ";
    first = false;
    o += io::json_string(k) + ": ";
    io::append_json_number(o, v);
  }
  o += "}";
}

// The error estimate (runs/estimate.hpp): whether it was made, what the companion changed and
// how it ended, the extrapolation (order, ratio, factor), the impact count and the first
// impact's time with their errors, and its cost in CPU seconds.
void write_estimate(JsonText& j, const Digest& d) {
  const ErrorEstimate& e = d.estimate;
  j.key("error_estimate");
  j.o += "{\"enabled\": ";
  j.o += e.enabled ? "true" : "false";
  j.o += ", \"computed\": ";
  j.o += e.computed ? "true" : "false";
  if (e.enabled) {
    j.o += ", \"companion\": {\"setting\": " + io::json_string(e.setting) + ", \"value\": ";
    io::append_json_number(j.o, e.companion_value);
    j.o += ", \"status\": " + io::json_string(e.companion_status) + "}";
    j.o += ", \"order\": ";
    io::append_json_number(j.o, e.order);
    j.o += ", \"ratio\": ";
    io::append_json_number(j.o, e.ratio);
    j.o += ", \"factor\": ";
    io::append_json_number(j.o, e.factor);
    j.o += ",\n    ";
    append_object(j.o, "impacts",
                  {{"count", static_cast<double>(e.impacts)}, {"error", e.impacts_error}});
    j.o += ", ";
    append_object(j.o, "first_impact", {{"time", e.first_impact}, {"error", e.first_impact_error}});
    j.o += ",\n    \"impact_order\": ";
    if (e.impact_order.found) {
      const UnresolvedImpactOrder& o = e.impact_order;
      j.o += "{\"time\": ";
      io::append_json_number(j.o, o.time);
      j.o += ", \"contact\": " + std::to_string(o.contact) +
             ", \"other\": " + std::to_string(o.other) + ", \"separation\": ";
      io::append_json_number(j.o, o.separation);
      j.o += ", \"uncertainty\": ";
      io::append_json_number(j.o, o.uncertainty);
      j.o += "}";
    } else {
      j.o += "null";
    }
  }
  j.o += ",\n    ";
  const double ratio = e.run_cpu_seconds > 0.0
                           ? (e.run_cpu_seconds + e.companion_cpu_seconds) / e.run_cpu_seconds
                           : std::numeric_limits<double>::quiet_NaN();
  append_object(j.o, "cost", {{"run_cpu_seconds", e.run_cpu_seconds},
                              {"companion_cpu_seconds", e.companion_cpu_seconds},
                              {"ratio", ratio}});
  j.o += "},\n";
}

// The run judged against solver.accuracy: the target, whether it is met (null without an
// estimate), the step or tolerance used, and the coordinate of the largest relative error.
void write_accuracy(JsonText& j, const Digest& d) {
  const Accuracy& a = d.accuracy;
  j.key("accuracy");
  j.o += "{\"target\": ";
  io::append_json_number(j.o, a.target);
  j.o += ", \"met\": ";
  j.o += !a.judged ? "null" : a.met ? "true" : "false";
  j.o += ", " + io::json_string(d.estimate.setting) + ": ";
  io::append_json_number(j.o, d.estimate.value);
  j.o += ", \"worst\": " + io::json_string(a.worst) + ", \"worst_relative_error\": ";
  io::append_json_number(j.o, a.worst_relative);
  const Adaptation& ad = d.adaptation;
  if (ad.enabled) {
    // solver.adapt: every attempt's step or tolerance, its estimate and its cost.
    j.o += ", \"adapt\": true, \"attempts\": [";
    for (std::size_t i = 0; i < ad.attempts.size(); ++i) {
      const AdaptAttempt& t = ad.attempts[i];
      j.o += i ? ",\n      {" : "\n      {";
      j.o += io::json_string(d.estimate.setting) + ": ";
      io::append_json_number(j.o, t.value);
      j.o += ", \"worst_relative_error\": ";
      io::append_json_number(j.o, t.worst_relative);
      j.o += ", \"met\": ";
      j.o += t.met ? "true" : "false";
      j.o += ", \"status\": " + io::json_string(t.status) + ", \"cpu_seconds\": ";
      io::append_json_number(j.o, t.cpu_seconds);
      j.o += "}";
    }
    j.o += "],\n    \"total_cpu_seconds\": ";
    io::append_json_number(j.o, ad.cpu_seconds);
  }
  j.o += "}";
}

// The cross-check (runs::RunRequest::cross_check): the other method, its status, each
// coordinate's peak and error under it with the difference from the run's and what the
// estimates allow, its impact count and first impact with the differences, the floor, its
// own warnings and its cost.
void write_cross_check(JsonText& j, const Digest& d) {
  const CrossCheck& x = d.cross_check;
  j.key("cross_check");
  j.o += "{\"method\": " + io::json_string(x.method) + ", \"status\": " +
         io::json_string(x.status) + ", \"compared\": ";
  j.o += x.compared ? "true" : "false";
  j.o += ", \"floor\": ";
  io::append_json_number(j.o, x.floor);
  j.o += ",\n    \"peaks\": {";
  for (std::size_t c = 0; c < x.coordinates.size(); ++c) {
    const CrossPeak& p = x.coordinates[c];
    j.o += c ? ",\n      " : "\n      ";
    j.o += io::json_string(p.name) + ": {\"abs_max\": ";
    io::append_json_number(j.o, p.peak);
    j.o += ", \"error\": ";
    io::append_json_number(j.o, p.error);
    j.o += ", \"difference\": ";
    io::append_json_number(j.o, p.difference);
    j.o += ", \"allowed\": ";
    io::append_json_number(j.o, p.allowed);
    j.o += ", \"agrees\": ";
    j.o += p.agrees ? "true" : "false";
    j.o += "}";
  }
  j.o += "},\n    ";
  append_object(j.o, "impacts", {{"count", static_cast<double>(x.impacts)},
                                 {"error", x.impacts_error},
                                 {"difference", x.impacts_difference}});
  j.o += ", ";
  append_object(j.o, "first_impact", {{"time", x.first_impact},
                                      {"error", x.first_impact_error},
                                      {"difference", x.first_impact_difference}});
  j.o += ",\n    \"warnings\": [";
  for (std::size_t i = 0; i < x.warnings.size(); ++i) {
    j.o += i ? ", " : "";
    j.o += io::json_string(x.warnings[i]);
  }
  j.o += "], \"cpu_seconds\": ";
  io::append_json_number(j.o, x.cpu_seconds);
  j.o += "}";
}

}  // namespace

std::string history_csv(const integrators::Recorder& history) {
  std::string out;
  const auto& cols = history.columns();
  out.reserve((history.rows() + 1) * cols.size() * 14);
  for (std::size_t c = 0; c < cols.size(); ++c) {
    if (c) out += ',';
    out += cols[c];
  }
  out += '\n';
  for (std::size_t r = 0; r < history.rows(); ++r) {
    for (std::size_t c = 0; c < cols.size(); ++c) {
      if (c) out += ',';
      io::append_csv_number(out, history.at(r, c));
    }
    out += '\n';
  }
  return out;
}

std::string events_csv(const integrators::Recorder& history) {
  // Under the group "impulses", two more columns: an impact's impulses, empty elsewhere.
  const bool impulses = history.groups().has(integrators::OutputGroup::kImpulses);
  std::string out = impulses ? "t,contact,kind,note,impulse_N,impulse_T\n" : "t,contact,kind,note\n";
  for (const integrators::Event& e : history.events()) {
    io::append_csv_number(out, e.t);
    out += ',';
    io::append_integer(out, e.contact);
    out += ',';
    out += integrators::to_string(e.kind);
    out += ',';
    out += io::csv_quote(e.note);
    if (impulses) {
      out += ',';
      io::append_csv_number(out, e.impulse_normal);
      out += ',';
      io::append_csv_number(out, e.impulse_tangent);
    }
    out += '\n';
  }
  return out;
}

std::string summary_json(const RunRecord& record) {
  JsonText j;
  j.text("scene", record.scene_name);
  write_result(j, record.result, record.history.rows());
  write_input(j, record.digest.input);
  write_energy(j, record.digest.energy);
  write_events(j, record.digest);
  write_contacts(j, record.digest);
  write_peaks(j, record.digest);
  write_limit_states(j, record.digest);
  j.key("warnings");
  j.o += "[";
  for (std::size_t i = 0; i < record.digest.warnings.size(); ++i) {
    j.o += i ? ", " : "";
    j.o += io::json_string(record.digest.warnings[i]);
  }
  j.o += "],\n";
  write_estimate(j, record.digest);
  write_accuracy(j, record.digest);
  if (!record.digest.cross_check.method.empty()) {
    j.o += ",\n";
    write_cross_check(j, record.digest);
  }
  // Under the group "forces": the mass matrix, row by row, for the equilibrium check from
  // the files (docs/outputs.md, "forces").
  if (const auto& m = record.history.mass(); m.size() > 0) {
    j.o += ",\n";
    j.key("mass");
    j.o += "[";
    for (Eigen::Index r = 0; r < m.rows(); ++r) {
      j.o += r ? ", [" : "[";
      for (Eigen::Index c = 0; c < m.cols(); ++c) {
        if (c) j.o += ", ";
        io::append_json_number(j.o, m(r, c));
      }
      j.o += "]";
    }
    j.o += "]";
  }
  j.o += "\n}\n";
  return std::move(j.o);
}

void write_record(const std::filesystem::path& dir, const RunRecord& record) {
  io::write_file_set(dir, {{"history.csv", history_csv(record.history)},
                           {"events.csv", events_csv(record.history)},
                           {"summary.json", summary_json(record)}});
}

}  // namespace nsb::runs
