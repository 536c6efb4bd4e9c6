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

namespace {

namespace fs = std::filesystem;

// The output directory as a path with a last component: "out/ball/" and "out/ball/." name
// "out/ball", "." names the current directory by its own name.
fs::path target_of(const fs::path& dir) {
  std::error_code ec;
  fs::path d = fs::absolute(dir, ec);
  if (ec) d = dir;
  d = d.lexically_normal();
  if (d.filename().empty() && d.has_parent_path() && d != d.root_path()) d = d.parent_path();
  return d;
}

// A fresh name beside target: ".<name>.<tag>-<pid>-<n>", hidden, unique within the process.
fs::path beside(const fs::path& target, const char* tag) {
  static int counter = 0;
  std::string name = ".";
  name.append(target.filename().string());
  name.append(".").append(tag).append("-");
  name.append(std::to_string(static_cast<long>(::getpid())));
  name.append("-").append(std::to_string(counter++));
  return target.parent_path() / name;
}

// True when every entry of dir is one of `names`: the directory then holds nothing but a set
// of these outputs, and may be replaced as a whole.
bool holds_only(const fs::path& dir, const std::vector<std::string>& names) {
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string n = it->path().filename().string();
    if (std::find(names.begin(), names.end(), n) == names.end()) return false;
    if (!it->is_regular_file(ec)) return false;
  }
  return !ec;
}

[[noreturn]] void io_error(const std::string& what, const fs::path& p, const std::error_code& ec) {
  throw std::runtime_error(what + " '" + p.string() + "': " + ec.message());
}

}  // namespace

void prepare_output_dir(const std::filesystem::path& dir) {
  if (dir.empty()) throw std::invalid_argument("empty path; expected a directory");
  const fs::path target = target_of(dir);
  std::error_code ec;
  fs::create_directories(target, ec);
  if (ec || !fs::is_directory(target)) {
    throw std::invalid_argument("cannot create the directory '" + target.string() + "': " +
                                (ec ? ec.message() : "a file of that name exists"));
  }
  // write_file_set needs a new directory beside the target and write access to the target.
  const fs::path probe = beside(target, "probe");
  if (!fs::create_directory(probe, ec) || ec) {
    throw std::invalid_argument("cannot write beside '" + target.string() + "' in '" +
                                target.parent_path().string() + "': " +
                                (ec ? ec.message() : "the name is taken"));
  }
  fs::remove(probe, ec);
  if (::access(target.c_str(), W_OK | X_OK) != 0) {
    throw std::invalid_argument("cannot write into '" + target.string() + "': permission denied");
  }
}

void write_file_set(const std::filesystem::path& dir,
                    const std::vector<std::pair<std::string, std::string>>& files) {
  if (dir.empty()) throw std::invalid_argument("empty path; expected a directory");
  const fs::path target = target_of(dir);
  std::error_code ec;
  fs::create_directories(target.parent_path(), ec);
  if (ec) io_error("cannot create the directory", target.parent_path(), ec);

  // 1. Every file, complete, in a new directory beside the target.
  const fs::path staging = beside(target, "tmp");
  if (!fs::create_directory(staging, ec) || ec) io_error("cannot create", staging, ec);
  std::vector<std::string> names;
  try {
    for (const auto& [name, text] : files) {
      write_file(staging / name, text);
      names.push_back(name);
    }
  } catch (...) {
    fs::remove_all(staging, ec);
    throw;
  }

  // 2. The set replaces the old one. A target that is absent, or holds nothing but files of
  // this set, is replaced as a whole by two renames: a reader sees the old set, no directory
  // for an instant, then the new set; never a mix.
  if (!fs::exists(target, ec) || (fs::is_directory(target, ec) && holds_only(target, names))) {
    const fs::path old = beside(target, "old");
    const bool had_old = fs::exists(target, ec);
    if (had_old) {
      fs::rename(target, old, ec);
      if (ec) {
        fs::remove_all(staging, ec);
        io_error("cannot move the previous outputs aside", target, ec);
      }
    }
    fs::rename(staging, target, ec);
    if (ec) {
      const std::error_code failure = ec;
      if (had_old) fs::rename(old, target, ec);
      fs::remove_all(staging, ec);
      io_error("cannot rename '" + staging.string() + "' to", target, failure);
    }
    if (had_old) fs::remove_all(old, ec);
    return;
  }
  // A target that holds other files too (the user's own) keeps them: the files of the set
  // move in one by one, the last one named last, after its old version has been removed
  // first. A set is therefore complete exactly when its last file is present.
  if (!fs::is_directory(target, ec)) {
    fs::remove_all(staging, ec);
    throw std::runtime_error("'" + target.string() + "' is not a directory");
  }
  if (!names.empty()) {
    fs::remove(target / names.back(), ec);
    if (ec) {
      const std::error_code failure = ec;
      fs::remove_all(staging, ec);
      io_error("cannot remove the previous", target / names.back(), failure);
    }
  }
  for (const auto& name : names) {
    fs::rename(staging / name, target / name, ec);
    if (ec) {
      const std::error_code failure = ec;
      fs::remove_all(staging, ec);
      io_error("cannot move '" + (staging / name).string() + "' to", target / name, failure);
    }
  }
  fs::remove_all(staging, ec);
}

void write_outputs(const std::filesystem::path& dir, const std::string& scene_name,
                   const Recorder& recorder, const RunResult& stats) {
  write_file_set(dir, {{"history.csv", history_csv(recorder)},
                       {"events.csv", events_csv(recorder)},
                       {"summary.json", summary_json(scene_name, recorder, stats)}});
}

}  // namespace nsb::integrators
