#include "sweep/pelicun.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <regex>
#include <stdexcept>

#include "io/csv.hpp"
#include "scene/scene.hpp"
#include "sweep/csv.hpp"
#include "sweep/design.hpp"
#include "sweep/fragility_sweep.hpp"
#include "sweep/results.hpp"

namespace nsb::sweep {

namespace fs = std::filesystem;

namespace {

// One demand column: its pelicun name and unit, and how its value comes from a row.
struct Demand {
  std::string name;             // "1-PFD-1-1"
  std::string unit;             // pelicun's unit name: "m", "rad", "g"
  std::size_t column = 0;       // the results.csv column read
  bool absolute = false;        // |value|
  int bent = 0;                 // > 0: divided by the height of bent `bent` (1-based)
};

bool exported(const std::string& status) {
  return status == "completed" || status == "completed_with_fallbacks" || status == "unseated";
}

std::string join(const std::vector<std::string>& cells) {
  std::string out;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    if (k > 0) out += ',';
    out += io::csv_quote(cells[k]);
  }
  return out + '\n';
}

fs::path design_of(const fs::path& dir, const std::optional<fs::path>& given) {
  if (given) return *given;
  const fs::path manifest = dir / "manifest.toml";
  toml::table m;
  try {
    m = toml::parse_file(manifest.string());
  } catch (const toml::parse_error& e) {
    throw std::invalid_argument(manifest.string() + ": " + std::string(e.description()) +
                                " (give the design with --design)");
  }
  const auto name = m["design"].value<std::string>();
  if (!name) throw std::invalid_argument(manifest.string() + ": no key design (give it with --design)");
  std::error_code ec;
  if (fs::is_regular_file(*name, ec)) return *name;
  const fs::path beside = dir.parent_path() / *name;
  if (fs::is_regular_file(beside, ec)) return beside;
  throw std::invalid_argument(manifest.string() + ": design file " + *name +
                              " not found (give it with --design)");
}

// The fragility's demand type and unit of an IM factor; empty for one pelicun has no name for.
std::pair<std::string, std::string> im_type(const std::string& key) {
  if (key == "model.excitation.target_pga") return {"Peak Ground Acceleration", "g"};
  if (key == "model.excitation.target_sa") return {"Spectral Acceleration", "g"};
  return {};
}

}  // namespace

const std::vector<PelicunType>& pelicun_types() {
  static const std::vector<PelicunType> types{
      {"PGA", "Peak Ground Acceleration"},  {"SA", "Spectral Acceleration"},
      {"PFD", "Peak Floor Displacement"},   {"LR", "Peak Link Rotation Angle"},
      {"RID", "Residual Interstory Drift Ratio"}, {"PID", "Peak Interstory Drift Ratio"}};
  return types;
}

PelicunExport pelicun_export(const fs::path& dir, const std::optional<fs::path>& design) {
  const fs::path results_file = dir / "results.csv";
  const Table table = read_csv(results_file);
  const std::size_t c_run = table.column("run"), c_status = table.column("status");
  auto find = [&](const std::string& name) -> std::optional<std::size_t> {
    for (std::size_t k = 0; k < table.header.size(); ++k) {
      if (table.header[k] == name) return k;
    }
    return std::nullopt;
  };

  PelicunExport out;
  std::vector<Demand> demands;
  if (const auto c = find("model.excitation.target_pga")) demands.push_back({"1-PGA-0-2", "g", *c});
  if (const auto c = find("model.excitation.target_sa")) demands.push_back({"1-SA-0-2", "g", *c});
  if (const auto c = find("peak_x")) demands.push_back({"1-PFD-1-1", "m", *c});
  if (const auto c = find("peak_y")) demands.push_back({"1-PFD-1-2", "m", *c});
  if (const auto c = find("peak_theta")) demands.push_back({"1-LR-1-0", "rad", *c});
  if (const auto c = find("residual_theta")) demands.push_back({"1-RID-1-0", "rad", *c, true});
  const std::regex bent_column(R"(peak_bent([1-9][0-9]*)_u([xy]))");
  int bents = 0;
  for (std::size_t k = 0; k < table.header.size(); ++k) {
    std::smatch m;
    if (std::regex_match(table.header[k], m, bent_column)) {
      const int i = std::stoi(m[1].str());
      demands.push_back({"1-PID-" + m[1].str() + (m[2].str() == "x" ? "-1" : "-2"), "rad", k, true, i});
      bents = std::max(bents, i);
    }
  }
  for (const auto& name : table.header) {
    if (name.rfind("unseating_", 0) == 0 && name.size() > 7 &&
        name.compare(name.size() - 7, 7, "_margin") == 0) {
      out.notes.push_back(name + ": not exported (pelicun's EDP types have no seat margin)");
    }
  }
  if (demands.empty()) {
    throw std::invalid_argument(results_file.string() + ":1: no column pelicun has a type for "
                                "(peak_x, peak_y, peak_theta, residual_theta, peak_bent<i>_ux, "
                                "model.excitation.target_pga, ...)");
  }

  // The design, when a bent height or the fragility fit needs it.
  const bool has_fragility = fs::exists(dir / "fragility.json");
  std::optional<Design> d;
  if (bents > 0 || has_fragility) d = load_design(design_of(dir, design));
  std::map<std::string, const Run*> runs;
  if (d) {
    for (const auto& r : d->runs) runs[r.id] = &r;
  }

  std::vector<std::string> head{""}, units{"Units"};
  for (const auto& dm : demands) {
    head.push_back(dm.name);
    units.push_back(dm.unit);
  }
  out.demands = join(head) + join(units);
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const auto& row = table.rows[r];
    ++out.runs;
    if (!exported(row[c_status])) {
      ++out.left_out;
      continue;
    }
    const std::string where = results_file.string() + ":" + std::to_string(r + 2);
    std::vector<double> heights;
    if (bents > 0) {
      const auto it = runs.find(row[c_run]);
      if (it == runs.end()) {
        throw std::invalid_argument(where + ": run " + row[c_run] + " is not a run of " +
                                    d->file.string());
      }
      scene::SceneTable t = d->base;
      scene::apply_overrides(t, it->second->overrides);
      for (int i = 1; i <= bents; ++i) {
        const std::string key = "model.bents[" + std::to_string(i - 1) + "].height";
        const auto h = t.table.at_path(key).value<double>();
        if (!h || !(*h > 0)) {
          throw std::invalid_argument(where + ": column peak_bent" + std::to_string(i) +
                                      "_u*: the run's scene has no " + key + " > 0 (the bent "
                                      "height a drift divides by)");
        }
        heights.push_back(*h);
      }
    }
    std::vector<std::string> cells{row[c_run]};
    for (const auto& dm : demands) {
      const std::string& text = row[dm.column];
      if (!dm.absolute && dm.bent == 0) {
        cells.push_back(text);  // as results.csv writes it: the same double
        continue;
      }
      char* end = nullptr;
      const double v = std::strtod(text.c_str(), &end);
      if (text.empty() || *end != '\0' || !std::isfinite(v)) {
        throw std::invalid_argument(where + ": column " + table.header[dm.column] + ": '" + text +
                                    "' is not a number");
      }
      const double x = dm.bent > 0 ? std::abs(v) / heights[static_cast<std::size_t>(dm.bent - 1)]
                                   : std::abs(v);
      cells.push_back(io::csv_number(x));
    }
    out.demands += join(cells);
  }

  if (has_fragility) {
    if (!d->fragility) {
      throw std::invalid_argument(d->file.string() + ": no [fragility] section, but " +
                                  (dir / "fragility.json").string() + " exists");
    }
    const auto [type, unit] = im_type(d->fragility->im);
    if (type.empty()) {
      out.notes.push_back("fragility: the IM " + d->fragility->im +
                          " has no pelicun demand type (target_pga or target_sa have): not exported");
    } else {
      const FragilityReport report =
          fit_fragility(*d->fragility, results_of(table), is_ida(*d, d->fragility->im));
      out.fragility = join({"ID", "Incomplete", "Demand-Type", "Demand-Unit", "Demand-Offset",
                            "Demand-Directional", "LS1-Family", "LS1-Theta_0", "LS1-Theta_1"});
      for (const auto& fit : report.fits) {
        const bool ok = has_estimate(fit.mle.status);
        out.fragility += join({"nsbridge." + fit.limit.name, ok ? "0" : "1", type, unit, "0", "0",
                               "lognormal", ok ? io::csv_number(fit.mle.theta) : "",
                               ok ? io::csv_number(fit.mle.beta) : ""});
      }
    }
  }
  return out;
}

}  // namespace nsb::sweep
