// The tornado step of the uncertainty study: run 7's peak rotation at the two ends of each
// assumption's range, from the one-at-a-time sweep, drawn by the sweep module's tornado plot.
#include "studies/uncertainty_steps.hpp"

#include <cmath>

#include "sweep/csv.hpp"
#include "sweep/plots.hpp"

namespace nsb::studies::uncertainty {

using namespace paper_figures;  // the claims and the claim runs the study judges

namespace fs = std::filesystem;

namespace {

// The rows of run 7 in the one-at-a-time results.csv, without the point and claim_run
// columns: a results table of one run per point, as the sweep's plots read it. Written to
// `file` and returned.
sweep::Table tornado_runs(const fs::path& results, const fs::path& file) {
  const sweep::Table all = sweep::read_csv(results);
  const std::size_t point = all.column("point"), run = all.column("claim_run");
  sweep::Table t;
  for (std::size_t k = 0; k < all.header.size(); ++k) {
    if (k != point && k != run) t.header.push_back(all.header[k]);
  }
  std::string csv;
  for (std::size_t k = 0; k < t.header.size(); ++k) {
    if (k > 0) csv += ',';
    csv += t.header[k];
  }
  csv += "\n";
  for (const auto& row : all.rows) {
    if (row[run] != kTornadoRun) continue;
    std::vector<std::string> kept;
    for (std::size_t k = 0; k < row.size(); ++k) {
      if (k != point && k != run) kept.push_back(row[k]);
    }
    for (std::size_t k = 0; k < kept.size(); ++k) {
      if (k > 0) csv += ',';
      csv += sweep::csv_quote(kept[k]);
    }
    csv += "\n";
    t.rows.push_back(std::move(kept));
  }
  sweep::write_file_atomically(file, csv);
  return t;
}

}  // namespace

void tornado(const Rows& oat_rows, const fs::path& work, const fs::path& out,
             UncertaintyResult& res) {
  const sweep::Results t =
      sweep::results_of(tornado_runs(work / "oat" / "results.csv", work / "tornado-runs.csv"));
  sweep::PlotOptions po;
  po.response = kTornadoResponse;
  res.tornado_base = tornado_peak(oat_rows, "nominal");
  for (const auto& b : sweep::tornado_bars(t, po)) {
    res.tornado.push_back({b.factor, tornado_peak(oat_rows, b.factor + "-low"),
                           tornado_peak(oat_rows, b.factor + "-high")});
  }
  try {
    sweep::draw_plots(t, work / "plots", po);
    for (const char* ext : {".png", ".svg", ".csv"}) {
      fs::copy_file(work / "plots" / (std::string("tornado") + ext),
                    out / (std::string("uncertainty-tornado") + ext),
                    fs::copy_options::overwrite_existing);
    }
  } catch (const std::exception& e) {
    res.plot_errors.push_back(std::string("uncertainty-tornado: ") + e.what());
  }
}

}  // namespace nsb::studies::uncertainty
