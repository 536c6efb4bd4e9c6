#include "integrators/output.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <utility>
#include <vector>

#include <unistd.h>

namespace nsb::integrators {

namespace {

// Shortest text that reads back to the same double (std::to_chars), "nan"/"inf" never
// appear in CSV: a non-finite value is written empty, and as null in JSON.
void append_number(std::string& out, double v, bool json) {
  if (!std::isfinite(v)) {
    if (json) out += "null";
    return;
  }
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  out.append(buf, r.ptr);
}

void append_integer(std::string& out, std::int64_t v) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  out.append(buf, r.ptr);
}

std::string json_string(std::string_view s) {
  std::string out = "\"";
  for (char ch : s) {
    switch (ch) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(ch) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof(buf), "\\u%04x", static_cast<unsigned>(ch));
          out += buf;
        } else {
          out += ch;
        }
    }
  }
  out += '"';
  return out;
}

// RFC 4180 quoting for the free-text column of events.csv.
std::string csv_field(std::string_view s) {
  if (s.find_first_of(",\"\n\r") == std::string_view::npos) return std::string(s);
  std::string out = "\"";
  for (char ch : s) {
    if (ch == '"') out += '"';
    out += ch;
  }
  out += '"';
  return out;
}

constexpr EventKind kEventKinds[] = {EventKind::kImpact, EventKind::kClose, EventKind::kOpen,
                                     EventKind::kStick,  EventKind::kSlip,  EventKind::kWarning};

void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) throw std::runtime_error("cannot open '" + path.string() + "' for writing");
  f.write(text.data(), static_cast<std::streamsize>(text.size()));
  f.flush();
  if (!f) throw std::runtime_error("cannot write '" + path.string() + "'");
}

}  // namespace

std::string history_csv(const Recorder& recorder) {
  std::string out;
  const auto& cols = recorder.columns();
  out.reserve((recorder.rows() + 1) * cols.size() * 14);
  for (std::size_t c = 0; c < cols.size(); ++c) {
    if (c) out += ',';
    out += cols[c];
  }
  out += '\n';
  for (std::size_t r = 0; r < recorder.rows(); ++r) {
    for (std::size_t c = 0; c < cols.size(); ++c) {
      if (c) out += ',';
      append_number(out, recorder.at(r, c), false);
    }
    out += '\n';
  }
  return out;
}

std::string events_csv(const Recorder& recorder) {
  std::string out = "t,contact,kind,note\n";
  for (const Event& e : recorder.events()) {
    append_number(out, e.t, false);
    out += ',';
    append_integer(out, e.contact);
    out += ',';
    out += to_string(e.kind);
    out += ',';
    out += csv_field(e.note);
    out += '\n';
  }
  return out;
}

std::string summary_json(const std::string& scene_name, const Recorder& recorder,
                         const RunResult& stats) {
  std::string o = "{\n";
  auto key = [&](std::string_view k) {
    o += "  ";
    o += json_string(k);
    o += ": ";
  };
  auto num = [&](std::string_view k, double v) {
    key(k);
    append_number(o, v, true);
    o += ",\n";
  };
  auto integer = [&](std::string_view k, std::int64_t v) {
    key(k);
    append_integer(o, v);
    o += ",\n";
  };
  key("scene");
  o += json_string(scene_name) + ",\n";
  key("method");
  o += json_string(stats.method) + ",\n";
  key("status");
  o += json_string(to_string(stats.status)) + ",\n";
  key("completed");
  o += stats.completed ? "true,\n" : "false,\n";
  key("message");
  o += json_string(stats.message) + ",\n";
  num("end_time", stats.end_time);
  integer("steps", stats.steps);
  integer("rejected_steps", stats.rejected_steps);
  integer("steps_with_lcp", stats.steps_with_lcp);
  integer("lcp_solves", stats.lcp_solves);
  integer("lcp_fallbacks", stats.lcp_fallbacks);
  integer("lcp_unsolved", stats.lcp_unsolved);
  if (!succeeded(stats.status)) num("failure_time", stats.failure_time);
  key("lcp_status");
  o += "{";
  {
    bool first = true;
    for (const auto& [name, count] : stats.lcp_status) {
      o += first ? "" : ", ";
      first = false;
      o += json_string(name) + ": ";
      append_integer(o, count);
    }
  }
  o += "},\n";
  integer("factorizations", stats.factorizations);
  num("wall_time", stats.wall_time);
  integer("samples", static_cast<std::int64_t>(recorder.rows()));

  const EnergyBalance& e = stats.energy;
  key("energy");
  o += "{";
  const std::pair<const char*, double> terms[] = {
      {"kinetic", e.kinetic},   {"stored", e.stored},         {"initial", e.initial},
      {"external", e.external}, {"ground", e.ground},         {"damping", e.damping},
      {"hysteretic", e.hysteretic}, {"impacts", e.impacts}, {"friction", e.friction},
      {"error", e.error}};
  for (std::size_t i = 0; i < std::size(terms); ++i) {
    o += i ? ", " : "";
    o += json_string(terms[i].first) + ": ";
    append_number(o, terms[i].second, true);
  }
  o += "},\n";

  // Event counts, in total and per contact (1-based; contact 0 = not tied to a contact).
  key("events");
  o += "{";
  for (std::size_t i = 0; i < std::size(kEventKinds); ++i) {
    o += i ? ", " : "";
    o += json_string(to_string(kEventKinds[i])) + ": ";
    append_integer(o, static_cast<std::int64_t>(recorder.count(kEventKinds[i])));
  }
  o += "},\n";
  int contacts = 0;
  for (const Event& ev : recorder.events()) contacts = std::max(contacts, ev.contact);
  int columns_contacts = 0;
  for (const auto& c : recorder.columns()) {
    if (c.rfind("gN", 0) == 0) ++columns_contacts;
  }
  contacts = std::max(contacts, columns_contacts);
  key("contact_events");
  o += "[";
  for (int ci = 1; ci <= contacts; ++ci) {
    o += ci > 1 ? ", " : "";
    o += "{\"contact\": ";
    append_integer(o, ci);
    for (EventKind k : kEventKinds) {
      if (k == EventKind::kWarning) continue;
      std::int64_t n = 0;
      for (const Event& ev : recorder.events()) n += (ev.contact == ci && ev.kind == k);
      o += ", " + json_string(to_string(k)) + ": ";
      append_integer(o, n);
    }
    o += "}";
  }
  o += "],\n";

  // Peaks of every history column but t: extreme values and when they occur.
  key("peaks");
  o += "{";
  const auto& cols = recorder.columns();
  bool first = true;
  for (std::size_t c = 1; c < cols.size(); ++c) {
    double vmax = -INFINITY, vmin = INFINITY, tmax = NAN, tmin = NAN;
    for (std::size_t r = 0; r < recorder.rows(); ++r) {
      const double v = recorder.at(r, c);
      if (!std::isfinite(v)) continue;
      if (v > vmax) vmax = v, tmax = recorder.at(r, 0);
      if (v < vmin) vmin = v, tmin = recorder.at(r, 0);
    }
    const bool abs_is_max = std::abs(vmax) >= std::abs(vmin);
    o += first ? "\n    " : ",\n    ";
    first = false;
    o += json_string(cols[c]) + ": {\"max\": ";
    append_number(o, vmax, true);
    o += ", \"t_max\": ";
    append_number(o, tmax, true);
    o += ", \"min\": ";
    append_number(o, vmin, true);
    o += ", \"t_min\": ";
    append_number(o, tmin, true);
    o += ", \"abs_max\": ";
    append_number(o, abs_is_max ? std::abs(vmax) : std::abs(vmin), true);
    o += ", \"t_abs_max\": ";
    append_number(o, abs_is_max ? tmax : tmin, true);
    o += "}";
  }
  o += first ? "},\n" : "\n  },\n";

  key("warnings");
  o += "[";
  for (std::size_t i = 0; i < stats.warnings.size(); ++i) {
    o += i ? ", " : "";
    o += json_string(stats.warnings[i]);
  }
  o += "]\n}\n";
  return o;
}

void write_outputs(const std::filesystem::path& dir, const std::string& scene_name,
                   const Recorder& recorder, const RunResult& stats) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) {
    throw std::runtime_error("cannot create output directory '" + dir.string() +
                             "': " + (ec ? ec.message() : "not a directory"));
  }
  const std::pair<const char*, std::string> files[] = {
      {"history.csv", history_csv(recorder)},
      {"events.csv", events_csv(recorder)},
      {"summary.json", summary_json(scene_name, recorder, stats)}};
  const std::string suffix = ".tmp" + std::to_string(static_cast<long>(::getpid()));
  std::vector<std::filesystem::path> temps;
  try {
    for (const auto& [name, text] : files) {
      temps.push_back(dir / (std::string(".") + name + suffix));
      write_file(temps.back(), text);
    }
    for (std::size_t i = 0; i < temps.size(); ++i) {
      const auto target = dir / files[i].first;
      std::filesystem::rename(temps[i], target, ec);
      if (ec) {
        throw std::runtime_error("cannot rename '" + temps[i].string() + "' to '" +
                                 target.string() + "': " + ec.message());
      }
    }
  } catch (...) {
    for (const auto& t : temps) std::filesystem::remove(t, ec);
    throw;
  }
}

}  // namespace nsb::integrators
