#include "studies/uncertainty.hpp"

#include <chrono>
#include <stdexcept>

#include "studies/uncertainty_steps.hpp"
#include "sweep/csv.hpp"

namespace nsb::studies {

using namespace paper_figures;  // the claims and the claim runs the study judges

namespace fs = std::filesystem;

void UncertaintyOptions::validate() const {
  if (out.empty()) throw std::invalid_argument("out: an output folder is required");
  if (scenes.empty()) throw std::invalid_argument("scenes: the scenes folder is required");
  if (workers < 1) throw std::invalid_argument("workers: must be >= 1");
  if (samples > 100000) throw std::invalid_argument("samples: must be <= 100000");
}

namespace {

// The hypercube's size: 24 samples give each share a standard error of at most 0.10
// (sqrt(0.25 / 24)) and keep the full set under 10 minutes on 2 shared cores; --quick draws 2,
// enough to exercise the path and the checker, not to estimate a share.
constexpr std::size_t kSamplesFull = 24, kSamplesQuick = 2;
// --quick integrates the study's runs over the first 20 s of the 40 s record, which hold its
// strong phase (4.1-12.4 s), at half the cost.
constexpr double kQuickEndTime = 20.0;  // [s]

}  // namespace

UncertaintyResult run_uncertainty(const UncertaintyOptions& options) {
  using namespace uncertainty;
  options.validate();
  const auto t0 = std::chrono::steady_clock::now();
  UncertaintyResult res;
  res.claims = kStudyClaims;
  SceneTargets targets = scene_targets(options.scenes, claim_runs());
  const fs::path base_scene =
      options.scenes / ("bridge-exc" + std::to_string(kBaseExcitation) + ".toml");
  const InputPga pga = input_pgas(options.scenes, kStudyPgaRuns);
  const fs::path work = options.out / "uncertainty";
  fs::create_directories(work);
  targets.rotation_record = write_rotation_record(targets, work);
  const auto& as = assumptions();

  // One factor at a time. The tornado's run at every point; the claims' other runs: not in
  // --quick, and not at an end that is the nominal value (the seat lag's low end, the time
  // scale's high end), where they would repeat the base point's.
  const bool quick = options.quick;
  const double end_time = quick ? kQuickEndTime : 0.0;
  const std::vector<Point> oat = oat_points();
  const sweep::Design oat_design =
      make_design("oat", base_scene, oat, targets, end_time, claim_runs(),
                  [&](const Point& p, const ClaimRun& r) {
                    if (r.name == kTornadoRun) return true;
                    if (quick) return false;
                    if (p.assumption.empty()) return true;
                    const std::size_t k = assumption_index(p.assumption);
                    return p.values[k] != as[k].nominal;
                  });
  Rows oat_rows = run_design(oat_design, work / "oat", options.workers, res.runs, res.failed);
  add_first_poundings("oat-first", base_scene, oat, targets, work / "oat-first", options.workers,
                      oat_rows, res);
  tornado(oat_rows, work, options.out, res);
  std::vector<std::pair<std::string, std::string>> cols;
  const std::string oat_csv = judge_oat(oat, oat_rows, pga, cols, res);
  fs::remove_all(work / "oat" / "runs");
  fs::remove_all(work / "oat-first" / "runs");

  // The Latin hypercube over every assumption at once.
  res.samples = options.samples > 0 ? options.samples : (quick ? kSamplesQuick : kSamplesFull);
  const std::vector<Point> lhs = latin_points(res.samples, options.seed);
  const sweep::Design lhs_design =
      make_design("latin", base_scene, lhs, targets, end_time, claim_runs(),
                  [](const Point&, const ClaimRun&) { return true; });
  Rows lhs_rows = run_design(lhs_design, work / "latin", options.workers, res.runs, res.failed);
  add_first_poundings("latin-first", base_scene, lhs, targets, work / "latin-first",
                      options.workers, lhs_rows, res);
  const std::string lhs_csv = judge_latin(lhs, lhs_rows, pga, cols, res);
  sweep::write_file_atomically(options.out / "uncertainty.csv", lhs_csv);
  sweep::write_file_atomically(options.out / "uncertainty-oat.csv",
                               csv_header({"point", "assumption", "end"}, cols) + oat_csv);
  fs::remove_all(work / "latin" / "runs");
  fs::remove_all(work / "latin-first" / "runs");

  res.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  sweep::write_file_atomically(options.out / "uncertainty.json", uncertainty_json(res));
  sweep::write_file_atomically(options.out / "uncertainty.md", uncertainty_markdown(res, quick));
  return res;
}

}  // namespace nsb::studies
