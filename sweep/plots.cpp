#include "sweep/plots.hpp"

#include "integrators/recorder.hpp"
#include "io/csv.hpp"
#include "io/gnuplot.hpp"
#include "sweep/design.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace nsb::sweep {

namespace fs = std::filesystem;

void PlotOptions::validate() const {
  if (pga_key.empty()) throw std::invalid_argument("--pga-key: must name a factor column");
  if (response.empty()) throw std::invalid_argument("--response: must name a results.csv column");
  if (!(limit > 0.0) || !std::isfinite(limit)) throw std::invalid_argument("--limit: must be > 0");
  if (gnuplot.empty()) throw std::invalid_argument("--gnuplot: must name the executable");
}

namespace {

// The factor columns lie between "run" and "status".
struct Layout {
  std::size_t first = 1, end = 1;  // factor columns [first, end)
  std::size_t status = 0, response = 0;
};
Layout layout(const Results& t, const PlotOptions& o) {
  Layout l;
  l.status = t.column("status");
  l.end = l.status;
  try {
    l.response = t.column(o.response);
  } catch (const std::invalid_argument&) {
    throw std::invalid_argument("--response: results.csv has no column \"" + o.response + "\"");
  }
  return l;
}

bool completed(const Row& row) {
  const auto status = integrators::parse_run_status(row.status);
  return status && integrators::succeeded(*status);
}

bool unseated(const Row& row) {
  return integrators::parse_run_status(row.status) == integrators::RunStatus::kUnseated;
}

std::optional<std::size_t> find_column(const Results& t, const std::string& name) {
  for (std::size_t k = 0; k < t.columns.size(); ++k)
    if (t.columns[k].name == name) return k;
  return std::nullopt;
}

}  // namespace

std::vector<IdaPoint> ida_points(const Results& t, const PlotOptions& o) {
  const Layout l = layout(t, o);
  const auto pga = find_column(t, o.pga_key);
  std::vector<IdaPoint> points;
  if (!pga || *pga >= l.end) return points;
  for (const auto& row : t.rows) {
    const auto x = t.number(row, *pga);
    const auto y = t.number(row, l.response);
    const bool lost_seat = unseated(row);
    if (!(completed(row) || lost_seat) || !x || !y) continue;
    std::string curve;
    for (std::size_t k = l.first; k < l.end; ++k) {
      if (k == *pga) continue;
      curve += (curve.empty() ? "" : "; ") + t.columns[k].name + "=" + t.cell(row, k);
    }
    points.push_back({curve.empty() ? "all" : curve, *x, *y, lost_seat});
  }
  std::stable_sort(points.begin(), points.end(), [](const IdaPoint& a, const IdaPoint& b) {
    return a.curve != b.curve ? a.curve < b.curve : a.pga < b.pga;
  });
  return points;
}

std::vector<ExceedancePoint> exceedance_points(const Results& t, const PlotOptions& o) {
  std::map<double, ExceedancePoint> by_pga;
  for (const auto& p : ida_points(t, o)) {
    auto& e = by_pga[p.pga];
    e.pga = p.pga;
    ++e.runs;
    if (p.unseated || p.response > o.limit) ++e.exceeding;
    if (p.unseated) ++e.unseated;
  }
  std::vector<ExceedancePoint> out;
  for (auto& [pga, e] : by_pga) {
    e.share = static_cast<double>(e.exceeding) / static_cast<double>(e.runs);
    out.push_back(e);
  }
  return out;
}

std::vector<TornadoBar> tornado_bars(const Results& t, const PlotOptions& o) {
  const Layout l = layout(t, o);
  std::optional<double> base;
  std::map<std::size_t, TornadoBar> bars;
  for (const auto& row : t.rows) {
    std::vector<std::size_t> set;
    for (std::size_t k = l.first; k < l.end; ++k) {
      if (!row.labels.at(t.columns[k].index).empty()) set.push_back(k);
    }
    const auto y = t.number(row, l.response);
    if (!completed(row) || !y) continue;
    if (set.empty()) {
      base = *y;
    } else if (set.size() == 1) {
      auto [it, fresh] = bars.try_emplace(set[0]);
      TornadoBar& b = it->second;
      const std::string level = t.cell(row, set[0]);
      if (fresh) {
        b = {t.columns[set[0]].name, *y, *y, level, level, 0.0};
      } else {
        if (*y < b.low) {
          b.low = *y;
          b.low_level = level;
        }
        if (*y > b.high) {
          b.high = *y;
          b.high_level = level;
        }
      }
    }
  }
  std::vector<TornadoBar> out;
  if (!base) return out;
  for (auto& [k, b] : bars) {
    b.base = *base;
    b.low = std::min(b.low, *base);
    b.high = std::max(b.high, *base);
    out.push_back(b);
  }
  std::stable_sort(out.begin(), out.end(), [](const TornadoBar& a, const TornadoBar& b) {
    return a.high - a.low > b.high - b.low;
  });
  return out;
}

namespace {

// Writes the script and runs options.gnuplot on it once per terminal: PNG, then SVG
// (io::render_gnuplot). The script sets everything but the terminal and the output.
void render(const PlotOptions& o, const fs::path& dir, const std::string& stem,
            const std::string& script, std::vector<fs::path>& files) {
  write_file_atomically(dir / (stem + ".gp"), script);
  files.push_back(dir / (stem + ".gp"));
  const std::string failure = io::render_gnuplot(o.gnuplot, dir, stem);
  if (!failure.empty()) throw std::runtime_error(dir.string() + ": " + failure);
  files.push_back(dir / (stem + ".png"));
  files.push_back(dir / (stem + ".svg"));
}

std::string axis_label(const std::string& column) {
  return column == "peak_theta" ? "peak deck rotation |theta| [rad]" : column;
}

}  // namespace

namespace {

// ida.{csv,gp,png,svg}: one line per curve through its completed runs; the unseated runs, when
// there are any, as points of their own from ida-unseated.csv (their response is that up to
// the loss of seat, so they are not joined to the curves).
void draw_ida(const std::vector<IdaPoint>& ida, const fs::path& dir, const PlotOptions& o,
              std::vector<fs::path>& files) {
  const std::string header = "curve," + csv_quote(o.pga_key) + "," + o.response + "\n";
  std::string csv = header, lost = header;
  std::vector<std::string> curves;
  for (const auto& p : ida) {
    (p.unseated ? lost : csv) +=
        csv_quote(p.curve) + "," + io::csv_number(p.pga) + "," + io::csv_number(p.response) + "\n";
    if (!p.unseated && (curves.empty() || curves.back() != p.curve)) curves.push_back(p.curve);
  }
  write_file_atomically(dir / "ida.csv", csv);
  files.push_back(dir / "ida.csv");
  std::string gp =
      "set datafile separator ','\nset termoption noenhanced\nset key top left\nset grid\n"
      "set xlabel 'target PGA [g] (" +
      o.pga_key + ")'\nset ylabel " + io::gnuplot_string(axis_label(o.response)) +
      "\nset title 'IDA curves'\nplot ";
  std::string sep;
  for (const auto& c : curves) {
    const std::string curve = io::gnuplot_string(c);
    gp += sep + "'ida.csv' skip 1 using 2:(strcol(1) eq " + curve +
          " ? $3 : NaN) with linespoints title " + curve;
    sep = ", \\\n     ";
  }
  if (lost != header) {
    write_file_atomically(dir / "ida-unseated.csv", lost);
    files.push_back(dir / "ida-unseated.csv");
    gp += sep + "'ida-unseated.csv' skip 1 using 2:3 with points pt 2 ps 2 lc rgb 'black' "
                "title 'unseated: response up to the loss of seat'";
  }
  render(o, dir, "ida", gp + "\n", files);
}

// exceedance.{csv,gp,png,svg}: the share of runs above the limit at each PGA; an unseated run
// counts as exceeding, and the CSV then has a column `unseated` with their number.
void draw_exceedance(const Results& t, const fs::path& dir, const PlotOptions& o,
                     std::vector<fs::path>& files) {
  const auto points = exceedance_points(t, o);
  const bool lost = std::any_of(points.begin(), points.end(),
                                [](const ExceedancePoint& e) { return e.unseated > 0; });
  std::string ex =
      csv_quote(o.pga_key) + ",runs,exceeding,share" + (lost ? ",unseated\n" : "\n");
  for (const auto& e : points) {
    ex += io::csv_number(e.pga) + "," + std::to_string(e.runs) + "," +
          std::to_string(e.exceeding) + "," + io::csv_number(e.share) +
          (lost ? "," + std::to_string(e.unseated) : std::string()) + "\n";
  }
  write_file_atomically(dir / "exceedance.csv", ex);
  files.push_back(dir / "exceedance.csv");
  const std::string title = "share of runs with " + o.response + " > " +
                            io::csv_number(o.limit) +
                            (lost ? " or unseated (unseated runs count as exceeding)" : "");
  render(o, dir, "exceedance",
         "set datafile separator ','\nset termoption noenhanced\nset grid\nset yrange [0:1]\nset "
         "xlabel 'target PGA [g] (" +
             o.pga_key + ")'\nset ylabel 'share of runs'\nset title " +
             io::gnuplot_string(title) +
             "\nplot 'exceedance.csv' skip 1 using 1:4 with linespoints notitle\n",
         files);
}

void draw_tornado(const std::vector<TornadoBar>& bars, const fs::path& dir, const PlotOptions& o,
                  std::vector<fs::path>& files) {
  std::string csv = "factor,low,high,base,low_level,high_level\n";
  for (const auto& b : bars) {
    csv += csv_quote(b.factor) + "," + io::csv_number(b.low) + "," + io::csv_number(b.high) + "," +
           io::csv_number(b.base) + "," + csv_quote(b.low_level) + "," + csv_quote(b.high_level) +
           "\n";
  }
  write_file_atomically(dir / "tornado.csv", csv);
  files.push_back(dir / "tornado.csv");
  // Largest swing on top: bar i sits at y = n - 1 - i.
  const std::string n = std::to_string(bars.size());
  render(o, dir, "tornado",
         "set datafile separator ','\nset termoption noenhanced\nset grid x\nset xlabel " +
             io::gnuplot_string(axis_label(o.response)) +
             "\nset title 'one factor at a time, about the base run'\nset yrange [-1:" + n +
             "]\nset style fill solid 0.5\nset arrow from " + io::csv_number(bars[0].base) +
             ", graph 0 to " + io::csv_number(bars[0].base) +
             ", graph 1 nohead dt 2\nplot 'tornado.csv' skip 1 using (($2+$3)/2):(" + n +
             "-1-$0):2:3:(" + n + "-1.4-$0):(" + n +
             "-0.6-$0):yticlabels(1) with boxxyerror notitle\n",
         files);
}

// The options with the default response resolved: a bridge in segments has one rotation per
// frame (peak_theta1, peak_theta2, ...) and no peak_theta; the default then plots frame 1's.
PlotOptions resolve_response(const Results& t, PlotOptions o) {
  const auto has = [&t](const std::string& c) { return find_column(t, c).has_value(); };
  if (o.response == "peak_theta" && !has("peak_theta") && has("peak_theta1")) {
    o.response = "peak_theta1";
  }
  return o;
}

}  // namespace

std::vector<fs::path> draw_plots(const Results& t, const fs::path& dir,
                                 const PlotOptions& options) {
  options.validate();
  const PlotOptions o = resolve_response(t, options);
  (void)layout(t, o);
  fs::create_directories(dir);
  std::vector<fs::path> files;
  const auto ida = ida_points(t, o);
  if (!ida.empty()) {
    draw_ida(ida, dir, o, files);
    draw_exceedance(t, dir, o, files);
  }
  const auto bars = tornado_bars(t, o);
  if (!bars.empty()) draw_tornado(bars, dir, o, files);
  return files;
}

}  // namespace nsb::sweep
