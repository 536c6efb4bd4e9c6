// The shares step of the uncertainty study: the claims' verdicts over the Latin hypercube,
// and the share of the samples in which each holds with its binomial standard error.
#include "studies/uncertainty_steps.hpp"

#include <cmath>

namespace nsb::studies {

using namespace paper_figures;  // the claims and the claim runs the study judges

Verdict verdict_of(const Claim& c) {
  if (!c.failure.empty()) return Verdict::kNotEvaluated;
  return c.holds() ? Verdict::kHolds : Verdict::kFails;
}

std::string to_string(Verdict v) {
  switch (v) {
    case Verdict::kHolds:
      return "holds";
    case Verdict::kFails:
      return "fails";
    case Verdict::kNotEvaluated:
      break;
  }
  return "not evaluated";
}

Share share_of(const std::vector<Verdict>& verdicts) {
  Share s;
  for (const Verdict v : verdicts) {
    if (v == Verdict::kNotEvaluated) {
      ++s.not_evaluated;
      continue;
    }
    ++s.evaluated;
    if (v == Verdict::kHolds) ++s.holds;
  }
  if (s.evaluated == 0) {
    s.share = s.standard_error = std::numeric_limits<double>::quiet_NaN();
    return s;
  }
  const double n = static_cast<double>(s.evaluated);
  s.share = static_cast<double>(s.holds) / n;
  s.standard_error = std::sqrt(s.share * (1.0 - s.share) / n);
  return s;
}

namespace uncertainty {

std::string judge_latin(const std::vector<Point>& lhs, const Rows& lhs_rows, const InputPga& pga,
                        std::vector<std::pair<std::string, std::string>>& cols,
                        UncertaintyResult& res) {
  std::map<std::string, std::vector<Verdict>> verdicts;
  std::string lhs_csv;
  for (const auto& p : lhs) {
    const auto& runs = lhs_rows.at(p.name);
    const auto claims = judge(runs, p.values[assumption_index("friction")], pga);
    if (cols.empty()) cols = check_columns(claims);
    if (lhs_csv.empty()) lhs_csv = csv_header({"sample"}, cols);
    for (const auto& c : claims) verdicts[c.id].push_back(verdict_of(c));
    const auto r7 = runs.find(kTornadoRun);
    lhs_csv += csv_row({p.name}, p.values, claims, cols,
                       r7 == runs.end() ? std::nan("") : r7->second.peak_theta);
  }
  for (const auto& id : kStudyClaims) res.shares[id] = share_of(verdicts[id]);
  return lhs_csv;
}

}  // namespace uncertainty

}  // namespace nsb::studies
