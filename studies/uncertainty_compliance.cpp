// The compliance claims of the uncertainty study: C4 (the compliance method against the
// nonsmooth run 5 over the whole record) and C5 (the first pounding of run 5), each under both
// compared damping laws of eq. (9) (C4', C5' for the law that is not Hertz-damp), judged with
// the functions of paper-figures/claims.hpp on the runs of every point.
#include "studies/uncertainty_steps.hpp"

#include <cmath>
#include <limits>

#include "paper-figures/figure.hpp"

namespace nsb::studies::uncertainty {

using namespace paper_figures;  // the claims and the claim runs the study judges

namespace fs = std::filesystem;
using integrators::DampingLaw;

namespace {

// Run 5 under Moreau-Jean: the nonsmooth reference of C4 and the first impact of C5.
const std::string kNonsmoothRun = "exc5";

// The law a claim id names: the primed ids are the second compared law (figure.hpp).
DampingLaw law_of(const std::string& id) {
  return id.ends_with("'") ? kComparedLaws[1] : kComparedLaws[0];
}

// "<run>: <status>" of every run of `names` that is missing or did not complete.
std::string missing_runs(const std::map<std::string, RunRow>& runs,
                         const std::vector<std::string>& names) {
  std::string failure;
  for (const auto& n : names) {
    const auto it = runs.find(n);
    if (it != runs.end() && it->second.ok()) continue;
    failure += (failure.empty() ? "" : "; ") + n + ": " +
               (it == runs.end() ? std::string("not run") : it->second.status);
  }
  return failure;
}

Claim judge_c4(const std::map<std::string, RunRow>& runs, DampingLaw law) {
  std::vector<std::string> names{kNonsmoothRun};
  for (double f : kStudyC4Factors) names.push_back(exc5_compliance_run(f, law));
  const std::string failure = missing_runs(runs, names);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  double ref = nan, t_end = nan;
  std::vector<CompliancePeak> k;
  if (failure.empty()) {
    const History mj = History::read(runs.at(kNonsmoothRun).dir);
    t_end = runs.at(kNonsmoothRun).end_time;
    ref = peak(mj, "theta", t_end);
    for (double f : kStudyC4Factors) {
      const History h = History::read(runs.at(exc5_compliance_run(f, law)).dir);
      k.push_back({f, peak(h, "theta", t_end), normalized_rms_difference(mj, h, "theta", t_end)});
    }
  } else {
    for (double f : kStudyC4Factors) k.push_back({f, nan, nan});
  }
  Claim c = claim_c4(ref, t_end, k);
  c.runs = names;
  c.failure = failure;
  return c;
}

Claim judge_c5(const std::map<std::string, RunRow>& runs, DampingLaw law) {
  std::vector<std::string> names{kNonsmoothRun};
  for (double f : kStudyC5Factors) names.push_back(exc5_window_run(f, law));
  std::string failure = missing_runs(runs, names);
  std::vector<FirstPounding> fps;
  if (failure.empty()) {
    const auto [t_first, contact] = first_impact(History::read(runs.at(kNonsmoothRun).dir));
    const std::string g = "gN" + std::to_string(contact);
    for (double f : kStudyC5Factors) {
      const History h = History::read(runs.at(exc5_window_run(f, law)).dir);
      fps.push_back(measure_first_pounding(f, h.series("t"), h.series(g),
                                           t_first - kFirstPoundingLead));
    }
  } else {
    for (double f : kStudyC5Factors) fps.push_back({f});
  }
  Claim c = claim_c5(fps);
  c.runs = names;
  c.failure = failure;
  return c;
}

}  // namespace

std::vector<ClaimRun> compliance_claim_runs() {
  std::vector<ClaimRun> v;
  for (const auto law : kComparedLaws) {
    for (double f : kStudyC4Factors) {
      const double tol = kStudyComplianceTolerance;
      v.push_back({exc5_compliance_run(f, law), kExampleRun, true, false, f, law, tol});
    }
  }
  return v;
}

bool has_claim_runs(const std::map<std::string, RunRow>& runs) {
  for (const auto& r : claim_runs()) {
    if (runs.find(r.name) == runs.end()) return false;
  }
  return true;
}

// As Fig. 8: from kFirstPoundingLead before run 5's first impact to kFirstPoundingWindow
// after it, every step recorded. A point whose run 5 failed or never pounds gets none (C5 is
// then not evaluated there: "not run").
void add_first_poundings(const std::string& name, const fs::path& base_scene,
                         const std::vector<Point>& points, const SceneTargets& targets,
                         const fs::path& dir, int workers, Rows& rows, UncertaintyResult& res) {
  std::map<std::string, double> ends;  // by point: the runs' end time [s]
  for (const auto& p : points) {
    const auto it = rows.find(p.name);
    if (it == rows.end() || !has_claim_runs(it->second)) continue;
    const RunRow& mj = it->second.at(kNonsmoothRun);
    if (!mj.ok()) continue;
    const auto [t_first, contact] = first_impact(History::read(mj.dir));
    if (contact > 0) ends[p.name] = t_first + kFirstPoundingWindow;
  }
  std::vector<ClaimRun> windows;
  for (const auto law : kComparedLaws) {
    for (double f : kStudyC5Factors) {
      windows.push_back({exc5_window_run(f, law), kExampleRun, true, false, f, law});
    }
  }
  sweep::Design d = make_design(
      name, base_scene, points, targets, 0.0, windows,
      [&](const Point& p, const ClaimRun&) { return ends.count(p.name) > 0; });
  if (d.runs.empty()) return;
  for (auto& run : d.runs) {
    run.overrides.push_back(
        scene::parse_override(override_text("solver.end_time", ends.at(run.labels[0]))));
    run.overrides.push_back(scene::parse_override("output.sample_dt=0"));
  }
  const Rows first = run_design(d, dir, workers, res.runs, res.failed);
  for (const auto& [point, runs] : first) {
    for (const auto& [run, row] : runs) rows[point][run] = row;
  }
}

Claim judge_compliance(const std::string& id, const std::map<std::string, RunRow>& runs) {
  const DampingLaw law = law_of(id);
  Claim c = id.starts_with("C4") ? judge_c4(runs, law) : judge_c5(runs, law);
  c.id = id;
  c.law.name = std::string(integrators::to_string(law));
  return c;
}

}  // namespace nsb::studies::uncertainty
