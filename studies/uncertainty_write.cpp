// The writing step of the uncertainty study: the rows of uncertainty.csv and
// uncertainty-oat.csv, uncertainty.json and uncertainty.md.
#include "studies/uncertainty_steps.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "io/csv.hpp"
#include "sweep/csv.hpp"

namespace nsb::studies {

using namespace paper_figures;  // the claims and the claim runs the study judges


namespace uncertainty {

// The claims' check quantities, in a fixed order: the columns of the CSV files.
std::vector<std::pair<std::string, std::string>> check_columns(const std::vector<Claim>& claims) {
  std::vector<std::pair<std::string, std::string>> cols;
  for (const auto& c : claims) {
    for (const auto& k : c.checks) cols.push_back({c.id, k.quantity});
  }
  return cols;
}

namespace {

std::string csv_number(double v) { return std::isfinite(v) ? io::csv_number(v) : std::string(); }

}  // namespace

// One row of uncertainty.csv or uncertainty-oat.csv: the values, the verdicts, the checks.
std::string csv_row(const std::vector<std::string>& lead, const std::vector<double>& values,
                    const std::vector<Claim>& claims,
                    const std::vector<std::pair<std::string, std::string>>& cols,
                    double tornado_peak) {
  std::string row;
  for (const auto& l : lead) row += sweep::csv_quote(l) + ",";
  for (double v : values) row += io::csv_number(v) + ",";
  for (const auto& c : claims) row += to_string(verdict_of(c)) + ",";
  for (const auto& [id, q] : cols) {
    double v = std::numeric_limits<double>::quiet_NaN();
    for (const auto& c : claims) {
      if (c.id != id) continue;
      for (const auto& k : c.checks) {
        if (k.quantity == q) v = k.value;
      }
    }
    row += csv_number(v) + ",";
  }
  return row + csv_number(tornado_peak) + "\n";
}

std::string csv_header(const std::vector<std::string>& lead,
                       const std::vector<std::pair<std::string, std::string>>& cols) {
  std::string h;
  for (const auto& l : lead) h += l + ",";
  for (const auto& a : assumptions()) h += a.key + ",";
  for (const auto& id : kStudyClaims) h += id + ",";
  for (const auto& [id, q] : cols) h += id + "." + q + ",";
  return h + kTornadoResponse + "_" + kTornadoRun + "\n";
}

}  // namespace uncertainty

using uncertainty::kTornadoResponse;
using uncertainty::kTornadoRun;

// ---------------------------------------------------------------------------------------------
// uncertainty.json and uncertainty.md.

namespace {

std::string short_number(double v) {
  std::ostringstream s;
  s << std::setprecision(3) << v;
  return s.str();
}

const Assumption& assumption(const std::string& key) {
  return assumptions()[assumption_index(key)];
}

// " (+12 %)": v relative to base, rounded to a percent; empty when either is missing.
std::string percent(double v, double base) {
  const double p = 100.0 * (v / base - 1.0);
  if (!std::isfinite(p)) return "";
  std::ostringstream s;
  s << " (" << (p >= 0 ? "+" : "") << std::lround(p) << " %)";
  return s.str();
}

}  // namespace

std::string uncertainty_json(const UncertaintyResult& r) {
  std::ostringstream s;
  s << "{\"samples\": " << r.samples << ", \"runs\": " << r.runs
    << ", \"wall_time_s\": " << json_number(r.wall_time) << ",\n \"assumptions\": [";
  const auto& as = assumptions();
  for (std::size_t k = 0; k < as.size(); ++k) {
    const auto& a = as[k];
    s << (k ? ",\n  " : "\n  ") << "{\"key\": " << json_string(a.key)
      << ", \"name\": " << json_string(a.name) << ", \"unit\": " << json_string(a.unit)
      << ", \"nominal\": " << json_number(a.nominal) << ", \"low\": " << json_number(a.low)
      << ", \"high\": " << json_number(a.high)
      << ", \"two_values\": " << (a.two_values ? "true" : "false")
      << ", \"reason\": " << json_string(a.reason) << "}";
  }
  s << "],\n \"claims\": [";
  for (std::size_t i = 0; i < r.claims.size(); ++i) {
    const std::string& id = r.claims[i];
    const auto sh = r.shares.count(id) ? r.shares.at(id) : Share{};
    const auto nom = r.nominal.count(id) ? r.nominal.at(id) : Verdict::kNotEvaluated;
    s << (i ? ",\n  " : "\n  ") << "{\"id\": " << json_string(id)
      << ", \"nominal\": " << json_string(to_string(nom)) << ", \"samples\": " << sh.evaluated
      << ", \"holds\": " << sh.holds << ", \"not_evaluated\": " << sh.not_evaluated
      << ", \"share\": " << json_number(sh.share)
      << ", \"standard_error\": " << json_number(sh.standard_error) << ", \"flips\": [";
    bool first = true;
    for (const auto& f : r.flips) {
      if (f.claim != id) continue;
      s << (first ? "" : ", ") << "{\"assumption\": " << json_string(f.assumption)
        << ", \"end\": " << json_string(f.end) << ", \"value\": " << json_number(f.value)
        << ", \"verdict\": " << json_string(to_string(f.flipped)) << "}";
      first = false;
    }
    s << "]}";
  }
  s << "],\n \"tornado\": {\"response\": " << json_string(kTornadoResponse + "_" + kTornadoRun)
    << ", \"base\": " << json_number(r.tornado_base) << ", \"bars\": [";
  for (std::size_t i = 0; i < r.tornado.size(); ++i) {
    const auto& b = r.tornado[i];
    s << (i ? ",\n   " : "\n   ") << "{\"assumption\": " << json_string(b.assumption)
      << ", \"low_end\": " << json_number(b.low_end)
      << ", \"high_end\": " << json_number(b.high_end) << "}";
  }
  s << "]}}\n";
  return s.str();
}

std::string uncertainty_markdown(const UncertaintyResult& r, bool quick) {
  std::ostringstream s;
  s << "# Uncertainty of the verdicts\n\n"
    << "The assumed values over their plausible ranges (docs/paper-figures.md, \"Uncertainty of "
       "the verdicts\"): "
    << r.runs << " runs, " << std::fixed << std::setprecision(0) << r.wall_time << " s wall time.\n"
    << std::defaultfloat;
  s << "\n## Share of the plausible space in which each claim holds\n\n"
    << "Latin hypercube of " << r.samples
    << " samples over every assumption at once (uncertainty.csv). C4 and C4' run the "
       "compliance method at tolerance "
    << io::csv_number(uncertainty::kStudyComplianceTolerance)
    << " and k factors 1e-4, 1e-3, 1e-2 and 1e2 (those their checks read), C5 and C5' at the "
       "scenes' tolerance (docs/benchmarks/compliance.md, \"Tolerance of the uncertainty "
       "study\").";
  if (quick) {
    s << " --quick draws only " << r.samples
      << " samples and integrates 20 s of the record: the shares are not meaningful, and the "
         "nominal verdicts are not judged.";
  }
  s << "\n\n| claim | nominal | holds in | share | standard error | not evaluated |\n"
    << "|---|---|---|---|---|---|\n";
  for (const auto& id : r.claims) {
    const auto sh = r.shares.count(id) ? r.shares.at(id) : Share{};
    const auto nom = r.nominal.count(id) ? r.nominal.at(id) : Verdict::kNotEvaluated;
    s << "| " << id << " | " << to_string(nom) << " | " << sh.holds << " of " << sh.evaluated
      << " | " << short_number(sh.share) << " | " << short_number(sh.standard_error) << " | "
      << sh.not_evaluated << " |\n";
  }
  s << "\n## Verdicts that one assumption flips\n\n";
  if (quick) {
    s << "Not run in --quick (the one-at-a-time design needs every claim's runs at 23 "
         "points); the full set has it.\n";
  } else if (r.flips.empty()) {
    s << "None: at either end of every range, with the others nominal, every verdict stays "
         "as at the nominal point.\n";
  } else {
    s << "| assumption | end | value | claim | nominal | there |\n|---|---|---|---|---|---|\n";
    for (const auto& f : r.flips) {
      const auto& a = assumption(f.assumption);
      s << "| " << a.name << " | " << f.end << " | " << short_number(f.value) << " " << a.unit
        << " | " << f.claim << " | " << to_string(f.nominal) << " | " << to_string(f.flipped)
        << " |\n";
    }
  }
  s << "\n## Tornado: peak rotation of run 7, one assumption at a time\n\n"
    << "Nominal: " << short_number(r.tornado_base) << " rad (uncertainty-tornado.png).\n\n"
    << "| assumption | range | peak at the low end [rad] | at the high end [rad] |\n"
    << "|---|---|---|---|\n";
  for (const auto& b : r.tornado) {
    const auto& a = assumption(b.assumption);
    s << "| " << a.name << " | " << short_number(a.low) << " ... " << short_number(a.high) << " "
      << a.unit << " | " << short_number(b.low_end) << percent(b.low_end, r.tornado_base) << " | "
      << short_number(b.high_end) << percent(b.high_end, r.tornado_base) << " |\n";
  }
  s << "\n## The ranges\n\n| assumption | nominal | range | reason |\n|---|---|---|---|\n";
  for (const auto& a : assumptions()) {
    s << "| " << a.name << " | " << short_number(a.nominal) << " " << a.unit << " | "
      << short_number(a.low) << (a.two_values ? " or " : " ... ") << short_number(a.high) << " | "
      << a.reason << " |\n";
  }
  if (!r.failed.empty()) {
    s << "\nRuns that did not complete (the claims that use them are not evaluated at their "
         "point):\n\n";
    for (const auto& f : r.failed) s << "- " << f << "\n";
  }
  return s.str();
}

}  // namespace nsb::studies
