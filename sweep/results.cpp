#include "sweep/results.hpp"

#include "integrators/recorder.hpp"
#include "io/csv.hpp"
#include "sweep/csv.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace nsb::sweep {

namespace {

// The fields of results.csv after the peaks, in order, with their types.
struct Fixed {
  const char* name;
  Field field;
  ValueKind kind;
};
constexpr Fixed kFixed[] = {
    {"impacts", Field::kImpacts, ValueKind::kInteger},
    {"max_penetration", Field::kMaxPenetration, ValueKind::kReal},
    {"energy_error", Field::kEnergyError, ValueKind::kReal},
    {"end_time", Field::kEndTime, ValueKind::kReal},
    {"steps", Field::kSteps, ValueKind::kInteger},
    {"lcp_solves", Field::kLcpSolves, ValueKind::kInteger},
    {"lcp_fallbacks", Field::kLcpFallbacks, ValueKind::kInteger},
    {"lcp_unsolved", Field::kLcpUnsolved, ValueKind::kInteger},
    {"failure_time", Field::kFailureTime, ValueKind::kReal},
    {"message", Field::kMessage, ValueKind::kText},
};

// A field written by io::csv_number: the shortest round-trip text, read back to the very
// double; empty (a value that was not finite) is NaN.
double real_of(const std::string& f) {
  double v = kNotANumber;
  if (!f.empty()) std::from_chars(f.data(), f.data() + f.size(), v);
  return v;
}

std::optional<std::int64_t> count_of(const std::string& f) {
  std::int64_t v = 0;
  const auto r = std::from_chars(f.data(), f.data() + f.size(), v);
  if (f.empty() || r.ec != std::errc() || r.ptr != f.data() + f.size()) return std::nullopt;
  return v;
}

std::string count_text(const std::optional<std::int64_t>& n) {
  return n ? std::to_string(*n) : std::string();
}

// The number a text stands for, when the whole of it is one and finite.
std::optional<double> number_of(const std::string& s) {
  double v = 0.0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(v))
    return std::nullopt;
  return v;
}

std::optional<double> finite(double v) {
  return std::isfinite(v) ? std::optional<double>(v) : std::nullopt;
}
std::optional<double> finite(const std::optional<std::int64_t>& n) {
  return n ? std::optional<double>(static_cast<double>(*n)) : std::nullopt;
}

// The kind of a label as a TOML value (a level's name, a list design's cell).
ValueKind kind_of_text(const std::string& s) {
  if (s == "true" || s == "false") return ValueKind::kBoolean;
  if (count_of(s)) return ValueKind::kInteger;
  if (number_of(s)) return ValueKind::kReal;
  return ValueKind::kText;
}

ValueKind combined(std::optional<ValueKind> a, ValueKind b) {
  if (!a || *a == b) return b;
  const auto numeric = [](ValueKind k) {
    return k == ValueKind::kReal || k == ValueKind::kInteger;
  };
  return numeric(*a) && numeric(b) ? ValueKind::kReal : ValueKind::kText;
}

const LimitCell* find_limit(const Row& row, const std::string& name) {
  for (const auto& l : row.limit_states)
    if (l.name == name) return &l;
  return nullptr;
}

// The columns of a design's results.csv without the limit states: run, factors, status,
// peaks, residual, the fixed fields and wall_s.
std::vector<Column> base_columns(const std::vector<std::string>& factors,
                                 const std::vector<ValueKind>& factor_kinds,
                                 const std::vector<std::string>& coordinates,
                                 bool cross_check = false) {
  std::vector<Column> c{{"run", Field::kRun, 0, ValueKind::kText}};
  for (std::size_t k = 0; k < factors.size(); ++k)
    c.push_back({factors[k], Field::kFactor, k, factor_kinds[k]});
  c.push_back({"status", Field::kStatus, 0, ValueKind::kText});
  for (std::size_t k = 0; k < coordinates.size(); ++k) {
    c.push_back({"peak_" + coordinates[k], Field::kPeak, k, ValueKind::kReal});
    c.push_back({"peak_" + coordinates[k] + "_error", Field::kPeakError, k, ValueKind::kReal});
  }
  if (!coordinates.empty())
    c.push_back({"residual_" + coordinates.back(), Field::kResidual, 0, ValueKind::kReal});
  for (const Fixed& f : kFixed) c.push_back({f.name, f.field, 0, f.kind});
  if (cross_check) {
    c.push_back({"cross_check_status", Field::kCrossStatus, 0, ValueKind::kText});
    for (std::size_t k = 0; k < coordinates.size(); ++k) {
      c.push_back({"cross_check_peak_" + coordinates[k], Field::kCrossPeak, k, ValueKind::kReal});
      c.push_back({"cross_check_peak_" + coordinates[k] + "_error", Field::kCrossPeakError, k,
                   ValueKind::kReal});
    }
    c.push_back({"cross_check_impacts", Field::kCrossImpacts, 0, ValueKind::kInteger});
    c.push_back({"cross_check_agrees", Field::kCrossAgrees, 0, ValueKind::kBoolean});
  }
  c.push_back({"wall_s", Field::kWall, 0, ValueKind::kReal});
  return c;
}

// Adds the limit-state columns before wall_s (the last column).
void add_limit_columns(Results& r) {
  std::vector<Column> limits;
  for (std::size_t k = 0; k < r.limit_states.size(); ++k) {
    limits.push_back({r.limit_states[k] + "_exceeded", Field::kExceeded, k, ValueKind::kBoolean});
    limits.push_back({r.limit_states[k] + "_margin", Field::kMargin, k, ValueKind::kReal});
  }
  r.columns.insert(r.columns.end() - 1, limits.begin(), limits.end());
}

// Sets the field of a column from its text in results.csv (the inverse of Results::cell).
void read_cell(Row& row, const Column& c, const std::string& text,
               const std::vector<std::string>& limit_names) {
  switch (c.field) {
    case Field::kRun: row.run = text; break;
    case Field::kFactor: row.labels.at(c.index) = text; break;
    case Field::kStatus: row.status = text; break;
    case Field::kPeak: row.peaks.at(c.index) = real_of(text); break;
    case Field::kPeakError: row.peak_errors.at(c.index) = real_of(text); break;
    case Field::kResidual: row.residual = real_of(text); break;
    case Field::kImpacts: row.impacts = count_of(text); break;
    case Field::kMaxPenetration: row.max_penetration = real_of(text); break;
    case Field::kEnergyError: row.energy_error = real_of(text); break;
    case Field::kEndTime: row.end_time = real_of(text); break;
    case Field::kSteps: row.steps = count_of(text); break;
    case Field::kLcpSolves: row.lcp_solves = count_of(text); break;
    case Field::kLcpFallbacks: row.lcp_fallbacks = count_of(text); break;
    case Field::kLcpUnsolved: row.lcp_unsolved = count_of(text); break;
    case Field::kFailureTime: row.failure_time = real_of(text); break;
    case Field::kMessage: row.message = text; break;
    case Field::kExceeded:
    case Field::kMargin: {
      if (text.empty()) break;  // the run does not have this limit state
      const std::string& name = limit_names.at(c.index);
      auto it = std::find_if(row.limit_states.begin(), row.limit_states.end(),
                             [&](const LimitCell& l) { return l.name == name; });
      if (it == row.limit_states.end())
        it = row.limit_states.insert(it, {name, false, kNotANumber});
      if (c.field == Field::kExceeded) it->exceeded = text == "1";
      else it->margin = real_of(text);
      break;
    }
    case Field::kWall: row.wall_s = real_of(text); break;
    case Field::kCrossStatus: row.cross_status = text; break;
    case Field::kCrossPeak: row.cross_peaks.at(c.index) = real_of(text); break;
    case Field::kCrossPeakError: row.cross_peak_errors.at(c.index) = real_of(text); break;
    case Field::kCrossImpacts: row.cross_impacts = count_of(text); break;
    case Field::kCrossAgrees:
      if (!text.empty()) row.cross_agrees = text == "1";
      break;
  }
}

}  // namespace

std::string_view to_string(ValueKind kind) {
  switch (kind) {
    case ValueKind::kReal: return "real";
    case ValueKind::kInteger: return "integer";
    case ValueKind::kBoolean: return "boolean";
    case ValueKind::kText: return "text";
  }
  return "text";
}

std::vector<std::string> result_columns(const std::vector<std::string>& coordinates) {
  std::vector<std::string> names;
  for (const Column& c : base_columns({}, {}, coordinates))
    if (c.field != Field::kRun) names.push_back(c.name);
  return names;
}

ValueKind factor_kind(const Factor& factor) {
  std::optional<ValueKind> kind;
  if (factor.range) kind = ValueKind::kReal;
  for (const Level& l : factor.levels) {
    if (l.label.empty() && !l.kind) continue;
    kind = combined(kind, l.kind ? *l.kind : kind_of_text(l.label));
  }
  return kind.value_or(ValueKind::kText);
}

Row make_row(const Design& d, std::size_t index, const runs::RunRecord& record, double wall) {
  const integrators::RunResult& result = record.result;
  const runs::Digest& digest = record.digest;
  Row row;
  row.run = d.runs.at(index).id;
  row.labels = d.runs[index].labels;
  row.status = std::string(integrators::to_string(result.status));
  const auto& coordinates = base_coordinates(d);
  // A coordinate the run's system does not have stays NaN (an empty field); the residual is
  // that of the last coordinate's peak entry.
  const runs::CoordinatePeak* last = nullptr;
  for (const auto& name : coordinates) {
    last = nullptr;
    for (const auto& c : digest.coordinates)
      if (c.name == name) last = &c;
    row.peaks.push_back(last ? last->peak : kNotANumber);
    row.peak_errors.push_back(last ? last->error : kNotANumber);
  }
  if (last) row.residual = last->residual;
  row.impacts = digest.count(integrators::EventKind::kImpact);
  row.max_penetration = digest.max_penetration;
  row.energy_error = digest.energy.error;
  row.end_time = result.end_time;
  row.steps = result.steps;
  row.lcp_solves = result.lcp_solves;
  row.lcp_fallbacks = result.lcp_fallbacks;
  row.lcp_unsolved = result.lcp_unsolved;
  if (!integrators::succeeded(result.status)) row.failure_time = result.failure_time;
  if (!result.completed) row.message = result.message;
  for (const auto& l : digest.limit_states)
    row.limit_states.push_back({l.name, l.exceeded, l.margin});
  row.wall_s = wall;
  const runs::CrossCheck& x = digest.cross_check;
  row.cross_peaks.assign(coordinates.size(), kNotANumber);
  row.cross_peak_errors = row.cross_peaks;
  if (!x.method.empty()) {
    row.cross_status = x.status;
    if (x.compared) {
      bool agrees = true;
      for (std::size_t k = 0; k < coordinates.size(); ++k) {
        for (const auto& p : x.coordinates) {
          if (p.name != coordinates[k]) continue;
          row.cross_peaks[k] = p.peak;
          row.cross_peak_errors[k] = p.error;
        }
      }
      for (const auto& p : x.coordinates) agrees = agrees && p.agrees;
      row.cross_impacts = x.impacts;
      row.cross_agrees = agrees;
    }
  }
  return row;
}

Row rejected_row(const Design& d, std::size_t index, const std::string& message, double wall) {
  Row row;
  row.run = d.runs.at(index).id;
  row.labels = d.runs[index].labels;
  row.status = "rejected";
  row.peaks.assign(base_coordinates(d).size(), kNotANumber);
  row.peak_errors = row.peaks;
  row.cross_peaks = row.peaks;
  row.cross_peak_errors = row.peaks;
  row.message = message;
  row.wall_s = wall;
  return row;
}

bool is_result(const Row& row) {
  // "rejected" is no RunStatus: a run the scene refused did not complete either.
  const auto s = integrators::parse_run_status(row.status);
  return s && integrators::is_result(*s);
}

std::size_t Results::column(const std::string& name) const {
  for (std::size_t k = 0; k < columns.size(); ++k)
    if (columns[k].name == name) return k;
  throw std::invalid_argument("no column \"" + name + "\"");
}

std::optional<double> Results::number(const Row& row, std::size_t column) const {
  const Column& c = columns.at(column);
  switch (c.field) {
    case Field::kRun: return number_of(row.run);
    case Field::kFactor: return number_of(row.labels.at(c.index));
    case Field::kStatus:
    case Field::kMessage: return std::nullopt;
    case Field::kPeak: return finite(row.peaks.at(c.index));
    case Field::kPeakError: return finite(row.peak_errors.at(c.index));
    case Field::kResidual: return finite(row.residual);
    case Field::kImpacts: return finite(row.impacts);
    case Field::kMaxPenetration: return finite(row.max_penetration);
    case Field::kEnergyError: return finite(row.energy_error);
    case Field::kEndTime: return finite(row.end_time);
    case Field::kSteps: return finite(row.steps);
    case Field::kLcpSolves: return finite(row.lcp_solves);
    case Field::kLcpFallbacks: return finite(row.lcp_fallbacks);
    case Field::kLcpUnsolved: return finite(row.lcp_unsolved);
    case Field::kFailureTime: return finite(row.failure_time);
    case Field::kExceeded: {
      const LimitCell* l = find_limit(row, limit_states.at(c.index));
      return l ? std::optional<double>(l->exceeded ? 1.0 : 0.0) : std::nullopt;
    }
    case Field::kMargin: {
      const LimitCell* l = find_limit(row, limit_states.at(c.index));
      return l ? finite(l->margin) : std::nullopt;
    }
    case Field::kWall: return finite(row.wall_s);
    case Field::kCrossStatus: return std::nullopt;
    case Field::kCrossPeak: return finite(row.cross_peaks.at(c.index));
    case Field::kCrossPeakError: return finite(row.cross_peak_errors.at(c.index));
    case Field::kCrossImpacts: return finite(row.cross_impacts);
    case Field::kCrossAgrees:
      return row.cross_agrees ? std::optional<double>(*row.cross_agrees ? 1.0 : 0.0)
                              : std::nullopt;
  }
  return std::nullopt;
}

std::string Results::cell(const Row& row, std::size_t column) const {
  const Column& c = columns.at(column);
  switch (c.field) {
    case Field::kRun: return row.run;
    case Field::kFactor: return row.labels.at(c.index);
    case Field::kStatus: return row.status;
    case Field::kPeak: return io::csv_number(row.peaks.at(c.index));
    case Field::kPeakError: return io::csv_number(row.peak_errors.at(c.index));
    case Field::kResidual: return io::csv_number(row.residual);
    case Field::kImpacts: return count_text(row.impacts);
    case Field::kMaxPenetration: return io::csv_number(row.max_penetration);
    case Field::kEnergyError: return io::csv_number(row.energy_error);
    case Field::kEndTime: return io::csv_number(row.end_time);
    case Field::kSteps: return count_text(row.steps);
    case Field::kLcpSolves: return count_text(row.lcp_solves);
    case Field::kLcpFallbacks: return count_text(row.lcp_fallbacks);
    case Field::kLcpUnsolved: return count_text(row.lcp_unsolved);
    case Field::kFailureTime: return io::csv_number(row.failure_time);
    case Field::kMessage: return row.message;
    case Field::kExceeded: {
      const LimitCell* l = find_limit(row, limit_states.at(c.index));
      return l ? (l->exceeded ? "1" : "0") : "";
    }
    case Field::kMargin: {
      const LimitCell* l = find_limit(row, limit_states.at(c.index));
      return l ? io::csv_number(l->margin) : "";
    }
    case Field::kWall: return io::csv_number(row.wall_s);
    case Field::kCrossStatus: return row.cross_status;
    case Field::kCrossPeak: return io::csv_number(row.cross_peaks.at(c.index));
    case Field::kCrossPeakError: return io::csv_number(row.cross_peak_errors.at(c.index));
    case Field::kCrossImpacts: return count_text(row.cross_impacts);
    case Field::kCrossAgrees: return row.cross_agrees ? (*row.cross_agrees ? "1" : "0") : "";
  }
  return {};
}

namespace {

std::string line_of(const Results& r, const Row& row) {
  std::string line;
  for (std::size_t k = 0; k < r.columns.size(); ++k) {
    if (k > 0) line += ',';
    // Numbers and ids hold no comma or quote; the texts (labels, status, message) are quoted.
    line += csv_quote(r.cell(row, k));
  }
  return line;
}

Results design_table(const Design& d) {
  Results r;
  std::vector<ValueKind> kinds;
  for (const auto& f : d.factors) {
    r.factors.push_back(f.key);
    kinds.push_back(factor_kind(f));
  }
  r.coordinates = base_coordinates(d);
  r.columns = base_columns(r.factors, kinds, r.coordinates, !d.cross_check.empty());
  return r;
}

}  // namespace

std::string Results::csv() const {
  std::string text;
  for (std::size_t k = 0; k < columns.size(); ++k) {
    if (k > 0) text += ',';
    text += csv_quote(columns[k].name);
  }
  text += '\n';
  for (const auto& row : rows) text += line_of(*this, row) + '\n';
  return text;
}

Results results_of(const Design& d, const std::vector<std::optional<Row>>& rows) {
  Results r = design_table(d);
  for (const auto& row : rows) {
    if (!row) continue;
    for (const auto& l : row->limit_states)
      if (std::find(r.limit_states.begin(), r.limit_states.end(), l.name) == r.limit_states.end())
        r.limit_states.push_back(l.name);
    r.rows.push_back(*row);
  }
  add_limit_columns(r);
  return r;
}

Results results_of(const Table& t) {
  Results r;
  const auto status = std::find(t.header.begin(), t.header.end(), "status");
  if (t.header.empty() || t.header[0] != "run" || status == t.header.end())
    throw std::invalid_argument("results: the header must start with run and hold status");
  std::vector<ValueKind> kinds;
  for (auto it = t.header.begin() + 1; it != status; ++it) {
    r.factors.push_back(*it);
    Factor f;
    const std::size_t k = static_cast<std::size_t>(it - t.header.begin());
    for (const auto& row : t.rows) f.levels.push_back({row[k], {}});
    kinds.push_back(factor_kind(f));
  }
  // The columns after status, each by its name.
  const std::vector<Column> fixed = base_columns({}, {}, {});
  for (auto it = status + 1; it != t.header.end(); ++it) {
    const std::string& h = *it;
    const auto ends = [&h](std::string_view e) {
      return h.size() > e.size() && h.compare(h.size() - e.size(), e.size(), e) == 0;
    };
    Column c;
    c.name = h;
    c.kind = ValueKind::kReal;
    if (const auto f = std::find_if(fixed.begin(), fixed.end(),
                                    [&h](const Column& x) { return x.name == h; });
        f != fixed.end() && f->field != Field::kRun && f->field != Field::kStatus) {
      c = *f;
    } else if (h == "cross_check_status" || h == "cross_check_impacts" ||
               h == "cross_check_agrees") {
      c.field = h == "cross_check_status"    ? Field::kCrossStatus
                : h == "cross_check_impacts" ? Field::kCrossImpacts
                                             : Field::kCrossAgrees;
      c.kind = h == "cross_check_status"    ? ValueKind::kText
               : h == "cross_check_impacts" ? ValueKind::kInteger
                                            : ValueKind::kBoolean;
    } else if (h.rfind("cross_check_peak_", 0) == 0) {
      // cross_check_peak_<q>[_error], after every peak_<q>: the coordinate by its name.
      const bool error = ends("_error");
      const std::string q = h.substr(17, h.size() - 17 - (error ? 6 : 0));
      const auto at = std::find(r.coordinates.begin(), r.coordinates.end(), q);
      if (at == r.coordinates.end())
        throw std::invalid_argument("results: \"" + h + "\" names no peak_ column's coordinate");
      c.field = error ? Field::kCrossPeakError : Field::kCrossPeak;
      c.index = static_cast<std::size_t>(at - r.coordinates.begin());
    } else if (h.rfind("peak_", 0) == 0 && ends("_error")) {
      // peak_<q>_error follows peak_<q>: the coordinate is the last one read.
      c.field = Field::kPeakError;
      c.index = r.coordinates.empty() ? 0 : r.coordinates.size() - 1;
    } else if (h.rfind("peak_", 0) == 0) {
      c.field = Field::kPeak;
      c.index = r.coordinates.size();
      r.coordinates.push_back(h.substr(5));
    } else if (h.rfind("residual_", 0) == 0) {
      c.field = Field::kResidual;
    } else if (ends("_exceeded") || ends("_margin")) {
      const bool exceeded = ends("_exceeded");
      const std::string name = h.substr(0, h.size() - (exceeded ? 9 : 7));
      const auto at = std::find(r.limit_states.begin(), r.limit_states.end(), name);
      c.index = static_cast<std::size_t>(at - r.limit_states.begin());
      if (at == r.limit_states.end()) r.limit_states.push_back(name);
      c.field = exceeded ? Field::kExceeded : Field::kMargin;
      c.kind = exceeded ? ValueKind::kBoolean : ValueKind::kReal;
    } else {
      throw std::invalid_argument("results: \"" + h + "\" is not a results.csv column");
    }
    r.columns.push_back(c);
  }
  std::vector<Column> head{{"run", Field::kRun, 0, ValueKind::kText}};
  for (std::size_t k = 0; k < r.factors.size(); ++k)
    head.push_back({r.factors[k], Field::kFactor, k, kinds[k]});
  head.push_back({"status", Field::kStatus, 0, ValueKind::kText});
  r.columns.insert(r.columns.begin(), head.begin(), head.end());
  for (const auto& fields : t.rows) {
    Row row;
    row.labels.resize(r.factors.size());
    row.peaks.assign(r.coordinates.size(), kNotANumber);
    row.peak_errors = row.peaks;
    row.cross_peaks = row.peaks;
    row.cross_peak_errors = row.peaks;
    for (std::size_t k = 0; k < r.columns.size(); ++k)
      read_cell(row, r.columns[k], fields.at(k), r.limit_states);
    r.rows.push_back(std::move(row));
  }
  return r;
}

std::string row_line(const Design& d, const Row& row) {
  Results r = design_table(d);
  return line_of(r, row);
}

std::string limit_states_csv(const std::vector<LimitCell>& limit_states) {
  std::string out = "name,exceeded,margin\n";
  for (const auto& v : limit_states) {
    out.append(csv_quote(v.name)).append(v.exceeded ? ",1," : ",0,");
    io::append_csv_number(out, v.margin);
    out += '\n';
  }
  return out;
}

std::optional<Row> parse_row(const Design& d, std::size_t index, const std::string& line,
                             const std::string& limit_states) {
  const Run& run = d.runs.at(index);
  if (line.rfind(run.id + ",", 0) != 0) return std::nullopt;
  const Results r = design_table(d);
  const std::vector<std::string> fields = csv_fields(line);
  if (fields.size() != r.columns.size()) return std::nullopt;
  Row row;
  row.labels.resize(r.factors.size());
  row.peaks.assign(r.coordinates.size(), kNotANumber);
  row.peak_errors = row.peaks;
  row.cross_peaks = row.peaks;
  row.cross_peak_errors = row.peaks;
  for (std::size_t k = 0; k < r.columns.size(); ++k) read_cell(row, r.columns[k], fields[k], {});
  // The design's own labels, not their text read back (csv_fields trims unquoted blanks).
  row.labels = run.labels;
  std::size_t at = limit_states.find('\n');  // after the header
  while (at != std::string::npos && at + 1 < limit_states.size()) {
    const std::size_t end = limit_states.find('\n', at + 1);
    const auto f = csv_fields(limit_states.substr(at + 1, end - at - 1));
    if (f.size() == 3) row.limit_states.push_back({f[0], f[1] == "1", real_of(f[2])});
    at = end;
  }
  return row;
}

}  // namespace nsb::sweep
