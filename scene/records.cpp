// Ground-motion record files: the PEER .AT2, whitespace-text and CSV readers
// (scene/records.hpp). Formats and units: docs/ground-motions.md.
#include "scene/records.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <istream>
#include <optional>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace nsb::scene {

using models::kMinRecordSamples;
using models::Record;

namespace {

// Longest AT2 line 4 read ('NPTS= n, DT= dt SEC' and the filter data some files append).
constexpr std::size_t kMaxHeaderLine = 512;
// Longest fragment of a file quoted in a message.
constexpr std::size_t kMaxQuoted = 60;
// A step of a time column agrees with the caller's dt within this fraction of dt: the times
// of a text file are printed with at least 7 significant digits.
constexpr double kStepAgreement = 1e-6;

// Units written in a header, with their factor to SI (m/s^2, rad/s^2, s). Sources:
// standard gravity g_n = 9.80665 m/s^2 exactly (3rd CGPM, 1901; NIST SP 811, 2008, B.8);
// 1 in = 0.0254 m and 1 ft = 0.3048 m exactly (NIST SP 811, B.8); 1 Gal = 0.01 m/s^2
// (NIST SP 811, B.8). A header's [g] is this standard value; the .AT2 reader and a scene's
// target_pga use the caller's g (9.81 in scenes).
struct UnitName {
  std::string_view name;
  double factor;
};
constexpr double kGn = 9.80665;
constexpr std::array<UnitName, 16> kAccelerationUnits{{
    {"g", kGn},          {"m/s^2", 1.0},       {"m/s2", 1.0},      {"m/s/s", 1.0},
    {"cm/s^2", 0.01},    {"cm/s2", 0.01},      {"cm/s/s", 0.01},   {"gal", 0.01},
    {"mm/s^2", 1e-3},    {"mm/s2", 1e-3},      {"in/s^2", 0.0254}, {"in/s2", 0.0254},
    {"ft/s^2", 0.3048},  {"ft/s2", 0.3048},    {"in/s/s", 0.0254}, {"ft/s/s", 0.3048},
}};
constexpr std::array<UnitName, 2> kAngularUnits{{{"rad/s^2", 1.0}, {"rad/s2", 1.0}}};
constexpr std::array<UnitName, 4> kTimeUnits{{{"s", 1.0}, {"sec", 1.0}, {"ms", 1e-3}, {"msec", 1e-3}}};

template <std::size_t N>
double find_unit(const std::array<UnitName, N>& units, std::string_view u) {
  for (const auto& k : units) {
    if (k.name == u) return k.factor;
  }
  return 0.0;
}

template <std::size_t N>
std::string unit_list(const std::array<UnitName, N>& units) {
  std::string out;
  for (const auto& k : units) out += (out.empty() ? "" : ", ") + std::string(k.name);
  return out;
}

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw std::invalid_argument(where + ": " + what);
}

std::string at(const std::string& file, std::size_t line) {
  return file + ":" + std::to_string(line);
}

// A fragment of the file for a message: non-printable bytes as \xNN, at most kMaxQuoted
// characters (then "...").
std::string printable(std::string_view s) {
  std::string out;
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (out.size() >= kMaxQuoted) return out + "...";
    if (c >= 0x20 && c < 0x7f) {
      out += ch;
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    }
  }
  return out;
}

// A number in a message: at most 6 significant digits (1e+300, not 300 digits).
std::string number_text(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

// Whole token as a double (a leading '+' allowed); nullopt when it is not one.
std::optional<double> to_number(std::string_view s, std::errc* error = nullptr) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (error != nullptr) *error = ec;
  if (ec == std::errc::result_out_of_range && ptr == s.data() + s.size() && !s.empty()) {
    return std::nullopt;
  }
  if (ec != std::errc() || ptr != s.data() + s.size() || s.empty()) return std::nullopt;
  return v;
}

// Strict conversion of a whole token to double: no trailing characters, finite.
// Subnormal values are read as they are; a value beyond the range of a double (1e400, or
// 1e-400, which would silently become 0) is refused by name.
double parse_number(std::string_view tok, const std::string& file, std::size_t line) {
  std::errc ec{};
  const auto v = to_number(tok, &ec);
  if (!v) {
    if (ec == std::errc::result_out_of_range) {
      fail(at(file, line), "value '" + printable(tok) + "' is outside the range of a double");
    }
    fail(at(file, line), "non-numeric token '" + printable(tok) + "'");
  }
  if (!std::isfinite(*v)) fail(at(file, line), "value '" + printable(tok) + "' is not finite");
  return *v;
}

std::vector<std::string_view> split_ws(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    std::size_t j = i;
    while (j < s.size() && !std::isspace(static_cast<unsigned char>(s[j]))) ++j;
    if (j > i) out.push_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return out;
}

// A unit as written, compared case- and space-insensitively, with "²" read as "^2".
std::string normalize_unit(std::string_view u) {
  std::string out;
  for (std::size_t i = 0; i < u.size(); ++i) {
    const auto c = static_cast<unsigned char>(u[i]);
    if (c == 0xC2 && i + 1 < u.size() && static_cast<unsigned char>(u[i + 1]) == 0xB2) {
      out += "^2";
      ++i;
    } else if (!std::isspace(c)) {
      out += static_cast<char>(std::tolower(c));
    }
  }
  return out;
}

// Only regular files are read: a FIFO or a device could block or never end.
std::ifstream open_or_throw(const std::filesystem::path& file) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (ec || !std::filesystem::exists(status)) fail(file.string(), "record file does not exist");
  if (!std::filesystem::is_regular_file(status)) {
    fail(file.string(), "not a regular file; expected a record file");
  }
  std::ifstream in(file);
  if (!in) fail(file.string(), "cannot open the record file for reading");
  return in;
}

void check_keys(const RecordKeys& k, const std::string& file) {
  const std::string unit_key = k.unit_key.empty() ? "unit" : k.unit_key;
  if (!(k.unit > 0.0) || !std::isfinite(k.unit)) fail(file, unit_key + " must be finite and > 0");
  if (!(k.dt >= 0.0) || !std::isfinite(k.dt)) fail(file, k.dt_key + " must be finite and >= 0");
}

bool agree(double a, double b) { return std::abs(a - b) <= kUnitAgreement * std::max(a, b); }

// The caller's keys for a plain unit factor: a factor other than 1 counts as given.
RecordKeys keys_of_unit(double unit) {
  RecordKeys k;
  k.unit = unit;
  if (unit != 1.0) k.unit_key = "unit";
  return k;
}

// Appends one sample, checking that time increases strictly.
void push_sample(Record& r, double t, double a, const std::string& file, std::size_t line) {
  if (!std::isfinite(t)) {
    fail(at(file, line), "time " + number_text(t) + " s is not finite");
  }
  if (!r.t.empty() && !(t > r.t.back())) {
    fail(at(file, line), "time " + number_text(t) + " is not greater than the previous time " +
                             number_text(r.t.back()) + " (time must increase strictly)");
  }
  r.t.push_back(t);
  r.a.push_back(a);
}

void check_size(const Record& r, const std::string& file) {
  if (r.t.size() < kMinRecordSamples) {
    fail(file, "a record needs at least " + std::to_string(kMinRecordSamples) +
                   " samples, found " + std::to_string(r.t.size()));
  }
}

// A unit the file names for its values, and the line that names it.
struct FileUnit {
  std::string text;  // as written, for messages
  double factor = 0.0;
  bool angular = false;
  std::size_t line = 0;
};

// The factor of the values to m/s^2 (rad/s^2): the file's unit where it names one (the
// caller's where the caller gave one that agrees), else the caller's.
double value_factor(const RecordKeys& k, const std::optional<FileUnit>& u, const std::string& file) {
  if (!u) return k.unit;
  const std::string where = at(file, u->line);
  if (u->angular != k.angular) {
    fail(where, "unit [" + u->text + "] is " +
                    (u->angular ? "an angular acceleration; this record is a ground acceleration "
                                  "(m/s^2)"
                                : "a linear acceleration; this record is an angular "
                                  "acceleration (rad/s^2)"));
  }
  if (k.unit_key.empty()) return u->factor;
  if (!agree(k.unit, u->factor)) {
    fail(where, "unit [" + u->text + "] (" + number_text(u->factor) + (k.angular ? " rad" : " m") +
                    "/s^2 per value) conflicts with " + k.unit_key + " = " + number_text(k.unit) +
                    "; give one of them, or make them agree");
  }
  return k.unit;
}

// The columns of a text record and the units of their headers.
struct Columns {
  std::size_t count = 2;
  std::size_t t = 0, a = 1;
  bool values_only = false;   // acceleration values only, t_i = i dt
  double time_factor = 1.0;   // [s per file time unit]
  std::optional<FileUnit> unit;
};

// "a [g]" or "a (g)": the name and the unit between brackets (bracket false: none). A bracket
// that is not closed leaves a unit no table knows, so that it is refused by name.
struct HeaderField {
  std::string name, unit;
  bool bracket = false;
};

HeaderField header_field(std::string_view f) {
  HeaderField h;
  const std::size_t open = f.find_first_of("[(");
  if (open == std::string_view::npos) {
    h.name = lower(trim(f));
    return h;
  }
  h.bracket = true;
  h.name = lower(trim(f.substr(0, open)));
  const char close = f[open] == '[' ? ']' : ')';
  const std::size_t end = f.find(close, open + 1);
  h.unit = std::string(trim(f.substr(open + 1, end == std::string_view::npos ? std::string_view::npos
                                                                              : end - open - 1)));
  if (end == std::string_view::npos) h.unit += " (no closing bracket)";
  return h;
}

std::vector<std::string_view> split_csv(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = s.find(',', start);
    out.push_back(trim(s.substr(start, comma == std::string_view::npos ? comma : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

// The unit of the time column: [s] or [ms].
double time_unit(const HeaderField& h, const std::string& file, std::size_t line) {
  if (!h.bracket) return 1.0;
  const double f = find_unit(kTimeUnits, normalize_unit(h.unit));
  if (f == 0.0) {
    fail(at(file, line), "unknown time unit [" + printable(h.unit) + "] of column '" +
                             printable(h.name) + "'; known: " + unit_list(kTimeUnits));
  }
  return f;
}

// The unit of the acceleration column: one of kAccelerationUnits or kAngularUnits.
std::optional<FileUnit> value_unit(const HeaderField& h, const std::string& file, std::size_t line) {
  if (!h.bracket) return std::nullopt;
  FileUnit u;
  u.text = printable(h.unit);
  u.line = line;
  const std::string n = normalize_unit(h.unit);
  u.factor = find_unit(kAccelerationUnits, n);
  if (u.factor == 0.0) {
    u.factor = find_unit(kAngularUnits, n);
    u.angular = u.factor != 0.0;
  }
  if (u.factor == 0.0) {
    fail(at(file, line), "unknown unit [" + u.text + "] of column '" + printable(h.name) +
                             "'; known: " + unit_list(kAccelerationUnits) + " (" +
                             unit_list(kAngularUnits) + " for rotation records)");
  }
  return u;
}

// CSV header: columns named t (or time) and a (or acc, accel, acceleration), each with an
// optional unit in brackets; with exactly two columns of other names, the first is time and
// the second acceleration; one column alone holds acceleration values (its step is dt).
Columns csv_header(const std::vector<std::string_view>& fields, std::string_view line,
                   const std::string& file, std::size_t line_no) {
  Columns c;
  c.count = fields.size();
  std::vector<HeaderField> h;
  for (const auto f : fields) h.push_back(header_field(f));
  if (c.count == 1) {
    if (h[0].name == "t" || h[0].name == "time") {
      fail(at(file, line_no), "the only column is time; a record needs an acceleration column");
    }
    c.values_only = true;
    c.a = 0;
    c.unit = value_unit(h[0], file, line_no);
    return c;
  }
  bool found_t = false, found_a = false;
  for (std::size_t i = 0; i < h.size(); ++i) {
    const std::string& name = h[i].name;
    if (name == "t" || name == "time") { c.t = i; found_t = true; }
    if (name == "a" || name == "acc" || name == "accel" || name == "acceleration") {
      c.a = i;
      found_a = true;
    }
  }
  if (!(found_t && found_a) && c.count != 2) {
    fail(at(file, line_no), "header must name the columns 't' and 'a', found '" +
                                printable(line) + "'");
  }
  if (!(found_t && found_a)) { c.t = 0; c.a = 1; }
  c.time_factor = time_unit(h[c.t], file, line_no);
  c.unit = value_unit(h[c.a], file, line_no);
  return c;
}

// The message for a file of values only without a step.
[[noreturn]] void need_dt(const RecordKeys& k, const std::string& file, std::size_t line) {
  fail(at(file, line), "a single column of acceleration values has no time axis: give its "
                       "sample step with the key " + k.dt_key + " [s] beside the record");
}

// The samples of a text record (whitespace or CSV): blank lines and '#' comments are skipped.
// The first other line of a CSV file is its header unless all its fields are numbers; a
// whitespace file is "t a" per line, or acceleration values only when the caller gives dt.
Record read_text_record(std::istream& in, const std::string& file, const RecordKeys& keys,
                        bool csv) {
  check_keys(keys, file);
  Record r;
  r.source = file;
  Columns columns;
  double factor = keys.unit;
  bool started = false;
  std::size_t first_line = 0;
  // A whitespace file read as values only that holds two numbers per line whose first one
  // increases strictly looks like a "t a" file: refused rather than read as accelerations.
  bool pairs_like_time = true;
  std::size_t value_lines = 0;
  std::string line;
  std::size_t line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const auto s = trim(line);
    if (s.empty() || s.front() == '#') continue;
    const auto fields = csv ? split_csv(s) : split_ws(s);
    if (!started) {
      started = true;
      first_line = line_no;
      if (csv) {
        std::size_t numbers = 0;
        for (const auto f : fields) numbers += to_number(f).has_value() ? 1 : 0;
        if (numbers == 0) {
          columns = csv_header(fields, s, file, line_no);
          factor = value_factor(keys, columns.unit, file);
          if (columns.values_only && keys.dt == 0.0) need_dt(keys, file, line_no);
          continue;
        }
        // A first line of numbers is data; one with a number among words is a bad cell.
        for (const auto f : fields) parse_number(f, file, line_no);
        columns.count = fields.size();
        if (columns.count == 1) {
          columns.values_only = true;
          columns.a = 0;
        } else if (columns.count != 2) {
          fail(at(file, line_no), std::to_string(columns.count) + " columns and no header line: "
                                  "name the columns 't' and 'a' in a first line");
        }
      } else {
        columns.values_only = keys.dt > 0.0;
        if (!columns.values_only && fields.size() == 1) need_dt(keys, file, line_no);
      }
      if (columns.values_only && keys.dt == 0.0) need_dt(keys, file, line_no);
    }
    if (columns.values_only) {
      if (csv && fields.size() != 1) {
        fail(at(file, line_no), "expected 1 comma-separated field, found " +
                                    std::to_string(fields.size()));
      }
      if (fields.size() != 2) pairs_like_time = false;
      for (const auto f : fields) {
        const double v = parse_number(f, file, line_no);
        r.t.push_back(static_cast<double>(r.a.size()) * keys.dt);
        r.a.push_back(v * factor);
      }
      if (pairs_like_time && value_lines > 0 && !(r.a[r.a.size() - 2] > r.a[r.a.size() - 4])) {
        pairs_like_time = false;
      }
      ++value_lines;
      continue;
    }
    if (fields.size() != columns.count) {
      fail(at(file, line_no),
           csv ? "expected " + std::to_string(columns.count) + " comma-separated fields, found " +
                     std::to_string(fields.size())
               : "expected two numbers 't a', found " + std::to_string(fields.size()) +
                     " fields (a file of acceleration values only needs " + keys.dt_key + ")");
    }
    const double t = parse_number(fields[columns.t], file, line_no) * columns.time_factor;
    const double a = parse_number(fields[columns.a], file, line_no);
    push_sample(r, t, a * factor, file, line_no);
    if (keys.dt > 0.0 && r.t.size() >= 2) {
      const double step = r.t.back() - r.t[r.t.size() - 2];
      if (std::abs(step - keys.dt) > kStepAgreement * keys.dt) {
        fail(at(file, line_no), "time step " + number_text(step) + " s differs from " +
                                    keys.dt_key + " = " + number_text(keys.dt) +
                                    " s (a file with a time column keeps its own)");
      }
    }
  }
  if (!started) fail(file, "empty record file: no samples");
  if (columns.values_only && !csv && value_lines >= kMinRecordSamples && pairs_like_time) {
    fail(at(file, first_line), "every line holds two numbers and the first increases strictly, "
                               "as in a 't a' file, but " + keys.dt_key +
                               " reads the file as acceleration values only; remove " +
                               keys.dt_key + " for a two-column file");
  }
  check_size(r, file);
  return r;
}

// Line 3 of a PEER file names the unit ("ACCELERATION TIME SERIES IN UNITS OF G"); an
// acceleration file is in g. Returns whether the line names a unit.
bool check_at2_unit(const std::string& line, const std::string& file) {
  if (line.size() > kMaxHeaderLine) return false;
  static const std::regex units(R"(UNITS\s+OF\s+([^\s,]+))", std::regex::icase);
  std::smatch m;
  if (!std::regex_search(line, m, units)) return false;
  const std::string u = normalize_unit(m[1].str());
  if (u != "g" && u != "(g)") {
    fail(at(file, 3), "the values are in '" + printable(m[1].str()) +
                          "' (line 3); an .AT2 acceleration record is in g");
  }
  return true;
}

}  // namespace

double acceleration_unit(std::string_view unit) {
  return find_unit(kAccelerationUnits, normalize_unit(unit));
}

Record read_at2(const std::filesystem::path& file, double g) {
  return read_at2(file, g, RecordKeys{});
}

Record read_at2(const std::filesystem::path& file, double g, const RecordKeys& keys) {
  if (!(g > 0.0) || !std::isfinite(g)) fail(file.string(), "g must be finite and > 0");
  std::ifstream in = open_or_throw(file);
  return read_at2(in, file.string(), g, keys);
}

Record read_at2(std::istream& in, const std::string& file, double g) {
  return read_at2(in, file, g, RecordKeys{});
}

Record read_at2(std::istream& in, const std::string& file, double g, const RecordKeys& keys) {
  if (!(g > 0.0) || !std::isfinite(g)) fail(file, "g must be finite and > 0");
  check_keys(keys, file);
  std::string line;
  std::size_t line_no = 0;
  // Lines 1-3: free text (database, event and station, units).
  for (int i = 0; i < 3; ++i) {
    if (!std::getline(in, line)) {
      fail(at(file, line_no + 1), line_no == 0 ? "empty record file: expected the PEER .AT2 header"
                                               : "missing AT2 header line");
    }
    ++line_no;
  }
  const bool named = check_at2_unit(line, file);
  if (!keys.unit_key.empty() && !agree(keys.unit, g)) {
    fail(at(file, named ? 3 : 4), "an .AT2 record is in g (" + number_text(g) +
                                      " m/s^2 per value), which conflicts with " + keys.unit_key +
                                      " = " + number_text(keys.unit) + "; remove " +
                                      keys.unit_key + " or make it agree");
  }
  if (!std::getline(in, line)) fail(at(file, 4), "missing the 'NPTS= n, DT= dt SEC' line");
  ++line_no;
  // Line 4 in the PEER forms: NGA "NPTS=  1559, DT= .02000 SEC" and
  // "NPTS=   8773, DT=   .0050 SEC,   4 POLE @ ..." (filter data may follow), and the older
  // database's "  2000   0.0100   NPTS, DT" (the numbers first).
  // PEER header lines are about 80 characters; a longer line is not one, and std::regex's
  // recursive matcher is kept away from unbounded input.
  if (line.size() > kMaxHeaderLine) {
    fail(at(file, 4), "line 4 has " + std::to_string(line.size()) + " characters; expected "
                      "'NPTS= <count>, DT= <step> SEC' (at most " +
                      std::to_string(kMaxHeaderLine) + ")");
  }
  static const std::regex nga(R"(NPTS\s*=\s*([0-9]+)\s*,\s*DT\s*=\s*([-+0-9.eE]+))",
                              std::regex::icase);
  static const std::regex older(R"(^\s*([0-9]+)\s*,?\s+([-+0-9.eE]+)\s*,?\s*NPTS\s*,\s*DT)",
                                std::regex::icase);
  std::smatch m;
  if (!std::regex_search(line, m, nga) && !std::regex_search(line, m, older)) {
    fail(at(file, 4), "expected 'NPTS= <count>, DT= <step> SEC' or '<count> <step> NPTS, DT', "
                      "found '" + printable(trim(line)) + "'");
  }
  const std::string npts_s = m[1].str();
  const std::string dt_s = m[2].str();
  // At most 9 digits: far more samples than any record, and no overflow in the conversion.
  if (npts_s.size() > 9) fail(at(file, 4), "NPTS = " + printable(npts_s) + " is too large");
  const long npts = std::stol(npts_s);
  const double dt = parse_number(dt_s, file, 4);
  if (npts < static_cast<long>(kMinRecordSamples)) {
    fail(at(file, 4), "NPTS must be >= " + std::to_string(kMinRecordSamples));
  }
  if (!(dt > 0.0)) fail(at(file, 4), "DT must be > 0, found " + number_text(dt));
  if (keys.dt > 0.0 && std::abs(dt - keys.dt) > kStepAgreement * keys.dt) {
    fail(at(file, 4), "DT = " + number_text(dt) + " s differs from " + keys.dt_key + " = " +
                          number_text(keys.dt) + " s (an .AT2 file keeps its own DT)");
  }
  if (!std::isfinite(dt * static_cast<double>(npts - 1))) {
    fail(at(file, 4), "DT = " + number_text(dt) + " s makes the record's duration infinite");
  }
  Record r;
  r.source = file;
  std::size_t last_data_line = 4;
  while (std::getline(in, line)) {
    ++line_no;
    for (auto tok : split_ws(line)) {
      const double v = parse_number(tok, file, line_no);
      if (static_cast<long>(r.a.size()) >= npts) {
        fail(at(file, line_no), "more values than NPTS = " + npts_s + " (line 4)");
      }
      r.a.push_back(v * g);
      last_data_line = line_no;
    }
  }
  if (static_cast<long>(r.a.size()) != npts) {
    fail(at(file, last_data_line), "NPTS = " + npts_s + " (line 4) but " +
                                       std::to_string(r.a.size()) + " values found");
  }
  r.t.resize(r.a.size());
  for (std::size_t i = 0; i < r.t.size(); ++i) r.t[i] = static_cast<double>(i) * dt;
  return r;
}

Record read_two_column(const std::filesystem::path& file, double unit) {
  return read_two_column(file, keys_of_unit(unit));
}

Record read_two_column(const std::filesystem::path& file, const RecordKeys& keys) {
  check_keys(keys, file.string());
  std::ifstream in = open_or_throw(file);
  return read_two_column(in, file.string(), keys);
}

Record read_two_column(std::istream& in, const std::string& file, double unit) {
  return read_two_column(in, file, keys_of_unit(unit));
}

Record read_two_column(std::istream& in, const std::string& file, const RecordKeys& keys) {
  return read_text_record(in, file, keys, false);
}

Record read_csv(const std::filesystem::path& file, double unit) {
  return read_csv(file, keys_of_unit(unit));
}

Record read_csv(const std::filesystem::path& file, const RecordKeys& keys) {
  check_keys(keys, file.string());
  std::ifstream in = open_or_throw(file);
  return read_csv(in, file.string(), keys);
}

Record read_csv(std::istream& in, const std::string& file, double unit) {
  return read_csv(in, file, keys_of_unit(unit));
}

Record read_csv(std::istream& in, const std::string& file, const RecordKeys& keys) {
  return read_text_record(in, file, keys, true);
}

}  // namespace nsb::scene
