#include "sweep/fragility_sweep.hpp"

#include "integrators/recorder.hpp"
#include "io/csv.hpp"
#include "io/json.hpp"
#include "scene/scene_reader.hpp"
#include "sweep/runner.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

namespace nsb::sweep {

namespace {

std::string joined(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& i : items) out += (out.empty() ? "" : ", ") + i;
  return out;
}

void check_keys(const scene::Source& w, const toml::table& t, const std::string& where,
                const std::vector<std::string>& allowed) {
  for (const auto& [k, v] : t) {
    const std::string key(k.str());
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
      w.fail(&v, where + "." + key, "unknown key (allowed: " + joined(allowed) + ")");
  }
}

std::optional<double> parse_number(const std::string& s) {
  double v = 0.0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(v))
    return std::nullopt;
  return v;
}

// `im`: a factor of the design whose levels (or latin range) are numbers > 0.
std::string read_im(const scene::Source& w, const toml::table& t, const Design& d) {
  const auto* im = t.get("im");
  if (im == nullptr || !im->is_string())
    w.fail(im != nullptr ? im : &t, "fragility.im", "required: the key of the IM factor");
  const std::string key = *im->value<std::string>();
  const auto f = std::find_if(d.factors.begin(), d.factors.end(),
                              [&](const Factor& x) { return x.key == key; });
  if (f == d.factors.end()) {
    std::vector<std::string> keys;
    for (const auto& x : d.factors) keys.push_back("\"" + x.key + "\"");
    w.fail(im, "fragility.im",
           "\"" + key + "\" is not a factor of the design (factors: " + joined(keys) + ")");
  }
  for (const Level& l : f->levels) {
    const auto v = parse_number(l.label);
    if (!v || *v <= 0.0)
      w.fail(im, "fragility.im",
             "factor \"" + key + "\" has the level \"" + l.label +
                 "\": the stripes' levels must be numbers > 0 (an intensity measure)");
  }
  if (f->range && !((*f->range)[0] > 0.0))
    w.fail(im, "fragility.im", "factor \"" + key + "\": the range must be > 0 (an IM)");
  return key;
}

bool ends_with(const std::string& s, std::string_view end) {
  return s.size() > end.size() && s.compare(s.size() - end.size(), end.size(), end) == 0;
}

bool is_limit_column(const std::string& c) {
  return ends_with(c, "_exceeded") || ends_with(c, "_margin");
}

// `unseated` of a limit state or of the section: "exceeded" or "response".
UnseatedRuns read_unseated(const scene::Source& w, const toml::node& n, const std::string& key) {
  const auto v = n.value<std::string>();
  if (v && *v == "exceeded") return UnseatedRuns::kExceed;
  if (v && *v == "response") return UnseatedRuns::kResponse;
  w.fail(&n, key,
         "must be \"exceeded\" (an unseated run reaches the limit state) or \"response\" "
         "(its response up to the loss of seat is compared)");
}

// `limit_state = "<watched name>"`: the run's <name>_exceeded column, reached at 1. It stands
// for response and threshold, so neither they nor absolute and below may be given with it.
void read_watched(const scene::Source& w, const toml::table& t, const std::string& at, LimitState& ls) {
  const auto* watched = t.get("limit_state");
  if (!watched->is_string() || watched->value<std::string>()->empty())
    w.fail(watched, at + ".limit_state",
           "must be the name of a watched limit state (docs/limit-states.md: unseating_left, "
           "closure_hinge_1, drift_bent_2, residual_rotation, ...)");
  for (const char* other : {"response", "threshold", "absolute", "below"})
    if (const auto* n = t.get(other))
      w.fail(n, at + "." + other,
             "not allowed with limit_state (which reads <limit_state>_exceeded, threshold 1)");
  ls.watched = *watched->value<std::string>();
  ls.response = ls.watched + "_exceeded";
  ls.threshold = 1.0;
}

// `response`, `threshold`, `absolute` and `below` of a limit state on a results.csv column.
void read_response(const scene::Source& w, const toml::table& t, const std::string& at,
                   const std::vector<std::string>& columns, LimitState& ls) {
  const auto* response = t.get("response");
  if (response == nullptr || !response->is_string())
    w.fail(response != nullptr ? response : &t, at + ".response",
           "required: a results.csv column (" + joined(columns) +
               "), or limit_state = a watched limit state's name");
  ls.response = *response->value<std::string>();
  // A limit-state column (<name>_exceeded, <name>_margin) exists once the runs watch that
  // limit state: it is checked against results.csv after the runs.
  if (std::find(columns.begin(), columns.end(), ls.response) == columns.end() &&
      !is_limit_column(ls.response))
    w.fail(response, at + ".response",
           "\"" + ls.response + "\" is not a results.csv column of this design (allowed: " +
               joined(columns) + ", or a limit state's <name>_exceeded / <name>_margin)");
  const auto* threshold = t.get("threshold");
  const auto v = threshold != nullptr ? threshold->value<double>() : std::nullopt;
  if (threshold == nullptr || !(threshold->is_floating_point() || threshold->is_integer()) ||
      !v || !std::isfinite(*v))
    w.fail(threshold != nullptr ? threshold : &t, at + ".threshold",
           "required: a finite number, in the unit of the response column");
  ls.threshold = *v;
  if (const auto* absolute = t.get("absolute")) {
    if (!absolute->is_boolean()) w.fail(absolute, at + ".absolute", "must be true or false");
    ls.absolute = *absolute->value<bool>();
  }
  if (const auto* below = t.get("below")) {
    if (!below->is_boolean()) w.fail(below, at + ".below", "must be true or false");
    ls.below = *below->value<bool>();
  }
}

LimitState read_limit_state(const scene::Source& w, const toml::node& n, std::size_t index,
                            const std::vector<std::string>& columns, UnseatedRuns unseated) {
  const std::string at = "fragility.limit_state[" + std::to_string(index) + "]";
  const auto* t = n.as_table();
  if (t == nullptr) w.fail(&n, at, "must be a table {name, response, threshold}");
  check_keys(w, *t, at,
             {"name", "response", "threshold", "absolute", "below", "limit_state", "unseated"});
  LimitState ls;
  ls.unseated = unseated;
  if (t->get("limit_state") != nullptr) read_watched(w, *t, at, ls);
  else read_response(w, *t, at, columns, ls);
  const auto* name = t->get("name");
  if (name == nullptr && !ls.watched.empty()) {
    ls.name = ls.watched;  // a watched limit state names itself
  } else {
    if (name == nullptr || !name->is_string() || name->value<std::string>()->empty())
      w.fail(name != nullptr ? name : t, at + ".name", "required: a non-empty string");
    ls.name = *name->value<std::string>();
  }
  if (const auto* u = t->get("unseated")) ls.unseated = read_unseated(w, *u, at + ".unseated");
  return ls;
}

// The response columns of the design's results.csv: every result column but the texts.
std::vector<std::string> response_columns(const Design& d) {
  std::vector<std::string> out;
  for (const auto& c : result_columns(base_coordinates(d)))
    if (c != "status" && c != "message") out.push_back(c);
  return out;
}

}  // namespace

std::optional<FragilitySpec> read_fragility(const toml::table& root, const Design& d,
                                            const std::string& file) {
  const auto* node = root.get("fragility");
  if (node == nullptr) return std::nullopt;
  scene::Source w;
  w.file = file;
  const auto* t = node->as_table();
  if (t == nullptr) w.fail(node, "fragility", "must be a table [fragility]");
  check_keys(w, *t, "fragility", {"im", "limit_state", "unseated"});
  FragilitySpec spec;
  spec.im = read_im(w, *t, d);
  const auto* u = t->get("unseated");
  const UnseatedRuns unseated =
      u != nullptr ? read_unseated(w, *u, "fragility.unseated") : UnseatedRuns::kExceed;
  const auto* ls = t->get("limit_state");
  const auto* a = ls != nullptr ? ls->as_array() : nullptr;
  if (a == nullptr || a->empty() || !a->is_array_of_tables())
    w.fail(ls != nullptr ? ls : t, "fragility.limit_state",
           "required: one or more [[fragility.limit_state]] tables {name, response, threshold}");
  const std::vector<std::string> columns = response_columns(d);
  std::set<std::string> names;
  for (std::size_t k = 0; k < a->size(); ++k) {
    spec.limit_states.push_back(read_limit_state(w, (*a)[k], k, columns, unseated));
    if (!names.insert(spec.limit_states.back().name).second)
      w.fail(&(*a)[k], "fragility.limit_state[" + std::to_string(k) + "].name",
             "\"" + spec.limit_states.back().name + "\" appears twice");
  }
  return spec;
}

bool is_ida(const Design& d, const std::string& im) {
  if (d.mode != Mode::kGrid || d.factors.size() < 2) return false;
  const auto f = std::find_if(d.factors.begin(), d.factors.end(),
                              [&](const Factor& x) { return x.key == im; });
  return f != d.factors.end() && f->levels.size() >= 2;
}

namespace {

// The columns of results that a fit reads: the factor columns lie between "run" and
// "status".
struct Columns {
  std::size_t im = 0, status = 0;
  std::vector<std::size_t> others;  // the other factors' columns: together they name a record
};

Columns columns_of(const Results& t, const std::string& im) {
  Columns c;
  c.status = t.column("status");
  try {
    c.im = t.column(im);
  } catch (const std::invalid_argument&) {
    throw std::invalid_argument("fragility.im: results.csv has no column \"" + im + "\"");
  }
  for (std::size_t k = 1; k < c.status; ++k)
    if (k != c.im) c.others.push_back(k);
  return c;
}

// An unseated run counts: it is a result up to the loss of seat (docs/limit-states.md), and
// its limit-state columns say which seat was lost.
bool unseated(const Row& row) {
  return integrators::parse_run_status(row.status) == integrators::RunStatus::kUnseated;
}

// One row's outcome for a limit state: std::nullopt when it does not count (not completed,
// or no value of the response). An unseated run reaches every limit state unless the limit
// state compares its response (UnseatedRuns::kResponse).
std::optional<bool> reached(const Results& t, const Row& row, std::size_t response,
                            const LimitState& ls) {
  if (!is_result(row)) return std::nullopt;
  if (ls.unseated == UnseatedRuns::kExceed && unseated(row)) return true;
  const auto v = t.number(row, response);
  if (!v) return std::nullopt;
  const double r = ls.absolute ? std::abs(*v) : *v;
  return ls.below ? r <= ls.threshold : r >= ls.threshold;
}

std::vector<StripeCount> count_stripes(const Results& t, const Columns& c, std::size_t response,
                                       const LimitState& ls) {
  std::map<double, StripeCount> levels;
  for (const auto& row : t.rows) {
    const auto im = t.number(row, c.im);
    if (!im || *im <= 0.0) continue;  // no IM: the row belongs to no stripe
    StripeCount& s = levels[*im];
    s.im = *im;
    const auto r = reached(t, row, response, ls);
    if (!r) {
      ++s.left_out;
    } else {
      ++s.n;
      s.exceeded += *r ? 1 : 0;
      s.unseated += unseated(row) ? 1 : 0;
    }
  }
  std::vector<StripeCount> out;
  for (const auto& [im, s] : levels) out.push_back(s);
  return out;
}

MomentsFit fit_capacities(const Results& t, const Columns& c, std::size_t response,
                          const LimitState& ls) {
  // record -> (IM -> reached), completed runs only; the map keeps the IMs ascending.
  std::map<std::string, std::map<double, bool>> curves;
  for (const auto& row : t.rows) {
    const auto im = t.number(row, c.im);
    std::string record;
    for (const std::size_t k : c.others) record += t.cell(row, k) + '\x1f';
    auto& curve = curves[record];
    const auto r = reached(t, row, response, ls);
    if (im && *im > 0.0 && r) curve[*im] = *r;
  }
  MomentsFit m;
  std::vector<double> capacities;
  double highest = 0.0;
  for (const auto& [record, curve] : curves) {
    ++m.records;
    const auto first = std::find_if(curve.begin(), curve.end(), [](auto& p) { return p.second; });
    if (first == curve.end()) ++m.censored;
    else capacities.push_back(first->first);
    if (!curve.empty()) highest = std::max(highest, curve.rbegin()->first);
  }
  if (m.censored > 0) {
    m.status = "censored";
    m.message = std::to_string(m.censored) + " of " + std::to_string(m.records) +
                " records did not reach the limit state by the highest IM (" +
                io::csv_number(highest) +
                "): their capacities are unknown, and the method of moments needs every one";
    return m;
  }
  const FragilityFit f = fit_moments(capacities);
  m.status = std::string(to_string(f.status));
  m.message = f.message;
  m.theta = f.theta;
  m.beta = f.beta;
  return m;
}

// The column of a limit state's response; a missing column names the limit states the runs
// watch when the limit state is one of them.
std::size_t response_column(const Results& results, const LimitState& ls) {
  try {
    return results.column(ls.response);
  } catch (const std::invalid_argument&) {
    if (ls.watched.empty())
      throw std::invalid_argument("fragility.limit_state " + ls.name +
                                  ": results.csv has no column \"" + ls.response + "\"");
    std::vector<std::string> watched;
    for (const auto& h : results.columns)
      if (ends_with(h.name, "_exceeded")) watched.push_back(h.name.substr(0, h.name.size() - 9));
    throw std::invalid_argument(
        "fragility.limit_state " + ls.name + ": no run of the sweep watches \"" + ls.watched +
        "\" (results.csv has no column " + ls.response + "; watched: " +
        (watched.empty() ? std::string("none") : joined(watched)) + ")");
  }
}

}  // namespace

FragilityReport fit_fragility(const FragilitySpec& spec, const Results& results, bool ida,
                              const FitOptions& options) {
  const Columns c = columns_of(results, spec.im);
  FragilityReport report{spec.im, {}};
  for (const LimitState& ls : spec.limit_states) {
    const std::size_t response = response_column(results, ls);
    LimitStateFit fit{ls, count_stripes(results, c, response, ls), {}, std::nullopt};
    std::vector<Stripe> stripes;
    for (const auto& s : fit.stripes)
      if (s.n > 0) stripes.push_back({s.im, s.n, s.exceeded});
    fit.mle = fit_mle(stripes, options);
    if (ida) fit.moments = fit_capacities(results, c, response, ls);
    report.fits.push_back(std::move(fit));
  }
  return report;
}

namespace {

void number_or_null(std::string& out, bool present, double v) {
  if (present) io::append_json_number(out, v);
  else out += "null";
}

void band(std::string& out, bool present, const Band& b) {
  if (!present || (b[0] == 0.0 && b[1] == 0.0)) {
    out += "null";
    return;
  }
  out += '[';
  io::append_json_number(out, b[0]);
  out += ", ";
  io::append_json_number(out, b[1]);
  out += ']';
}

void moments_json(std::string& out, const std::optional<MomentsFit>& m) {
  if (!m) {
    out += "null";
    return;
  }
  const bool fitted = m->theta > 0.0 && m->beta > 0.0;
  out += "{\"status\": " + io::json_string(m->status);
  out += ", \"message\": " + io::json_string(m->message) + ", \"theta\": ";
  number_or_null(out, fitted, m->theta);
  out += ", \"beta\": ";
  number_or_null(out, fitted, m->beta);
  out += ", \"records\": " + std::to_string(m->records);
  out += ", \"censored\": " + std::to_string(m->censored) + "}";
}

void limit_state_json(std::string& out, const LimitStateFit& f) {
  const bool est = has_estimate(f.mle.status);
  out += "    " + io::json_string(f.limit.name) + ": {\n";
  out += "      \"response\": " + io::json_string(f.limit.response) + ", \"threshold\": ";
  io::append_json_number(out, f.limit.threshold);
  out += std::string(", \"absolute\": ") + (f.limit.absolute ? "true" : "false");
  if (f.limit.below) out += ", \"below\": true";  // written only when set: older files stay
  if (!f.limit.watched.empty()) out += ", \"limit_state\": " + io::json_string(f.limit.watched);
  // How unseated runs counted, written when a stripe has one (sweeps without seats unchanged).
  const bool unseated = std::any_of(f.stripes.begin(), f.stripes.end(),
                                    [](const StripeCount& s) { return s.unseated > 0; });
  if (unseated)
    out += std::string(", \"unseated\": ") +
           (f.limit.unseated == UnseatedRuns::kExceed ? "\"exceeded\"" : "\"response\"");
  out += ",\n";
  out += "      \"status\": " + io::json_string(to_string(f.mle.status)) + ",\n";
  out += "      \"message\": " + io::json_string(f.mle.message) + ",\n";
  out += "      \"theta\": ";
  number_or_null(out, est, f.mle.theta);
  out += ", \"beta\": ";
  number_or_null(out, est, f.mle.beta);
  out += ",\n      \"ci95_theta\": ";
  band(out, est, f.mle.ci95_theta);
  out += ", \"ci95_beta\": ";
  band(out, est, f.mle.ci95_beta);
  out += ",\n      \"stripes\": [";
  for (std::size_t k = 0; k < f.stripes.size(); ++k) {
    const StripeCount& s = f.stripes[k];
    out += k == 0 ? "\n" : ",\n";
    out += "        {\"im\": ";
    io::append_json_number(out, s.im);
    out += ", \"n\": " + std::to_string(s.n) + ", \"exceeded\": " + std::to_string(s.exceeded) +
           ", \"left_out\": " + std::to_string(s.left_out);
    if (unseated) out += ", \"unseated\": " + std::to_string(s.unseated);
    out += "}";
  }
  out += "],\n      \"moments\": ";
  moments_json(out, f.moments);
  out += "\n    }";
}

}  // namespace

std::string fragility_json(const FragilityReport& report) {
  std::string out = "{\n  \"im\": " + io::json_string(report.im) + ",\n  \"limit_states\": {";
  for (std::size_t k = 0; k < report.fits.size(); ++k) {
    out += k == 0 ? "\n" : ",\n";
    limit_state_json(out, report.fits[k]);
  }
  return out + "\n  }\n}\n";
}

}  // namespace nsb::sweep
