#include "runs/files.hpp"

#include "io/csv.hpp"
#include "io/files.hpp"
#include "io/json.hpp"

#include <cmath>
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
        {"t_min", p.t_min},     {"abs_max", p.abs_max}, {"t_abs_max", p.t_abs_max}};
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
  std::string out = "t,contact,kind,note\n";
  for (const integrators::Event& e : history.events()) {
    io::append_csv_number(out, e.t);
    out += ',';
    io::append_integer(out, e.contact);
    out += ',';
    out += integrators::to_string(e.kind);
    out += ',';
    out += io::csv_quote(e.note);
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
  write_peaks(j, record.digest);
  write_limit_states(j, record.digest);
  j.key("warnings");
  j.o += "[";
  for (std::size_t i = 0; i < record.digest.warnings.size(); ++i) {
    j.o += i ? ", " : "";
    j.o += io::json_string(record.digest.warnings[i]);
  }
  j.o += "]\n}\n";
  return std::move(j.o);
}

void write_record(const std::filesystem::path& dir, const RunRecord& record) {
  io::write_file_set(dir, {{"history.csv", history_csv(record.history)},
                           {"events.csv", events_csv(record.history)},
                           {"summary.json", summary_json(record)}});
}

}  // namespace nsb::runs
