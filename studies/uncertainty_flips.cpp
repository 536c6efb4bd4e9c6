// The flips step of the uncertainty study: the claims' verdicts at the one-at-a-time points,
// and the verdicts that differ from the base point's.
#include "studies/uncertainty_steps.hpp"

#include <cmath>
#include <stdexcept>

namespace nsb::studies {

using namespace paper_figures;  // the claims and the claim runs the study judges

std::vector<Flip> find_flips(const std::vector<OatPoint>& points) {
  const OatPoint* base = nullptr;
  for (const auto& p : points) {
    if (!p.assumption.empty()) continue;
    if (base != nullptr) throw std::invalid_argument("find_flips: more than one base point");
    base = &p;
  }
  if (base == nullptr) throw std::invalid_argument("find_flips: no base point");
  std::vector<Flip> flips;
  for (const auto& p : points) {
    if (&p == base) continue;
    for (const auto& [claim, v] : p.verdicts) {
      const auto b = base->verdicts.find(claim);
      if (b == base->verdicts.end() || b->second == Verdict::kNotEvaluated ||
          v == Verdict::kNotEvaluated || v == b->second) {
        continue;
      }
      flips.push_back({p.assumption, p.end, p.value, claim, b->second, v});
    }
  }
  return flips;
}

namespace uncertainty {

std::string judge_oat(const std::vector<Point>& oat, const Rows& oat_rows, const InputPga& pga,
                      std::vector<std::pair<std::string, std::string>>& cols,
                      UncertaintyResult& res) {
  std::string oat_csv;
  for (const auto& p : oat) {
    const auto it = oat_rows.find(p.name);
    if (it == oat_rows.end()) continue;
    // A point with the tornado's run only: --quick, or an end at the nominal value.
    if (!has_claim_runs(it->second)) continue;
    const double mu = p.values[assumption_index("friction")];
    const auto claims = judge(it->second, mu, pga);
    if (cols.empty()) cols = check_columns(claims);
    const double value = p.assumption.empty() ? 0.0 : p.values[assumption_index(p.assumption)];
    OatPoint op{p.assumption, p.end, value, {}};
    for (const auto& c : claims) op.verdicts[c.id] = verdict_of(c);
    if (p.assumption.empty()) res.nominal = op.verdicts;
    res.oat.push_back(op);
    const auto r7 = it->second.find(kTornadoRun);
    oat_csv += csv_row({p.name, p.assumption, p.end}, p.values, claims, cols,
                       r7 == it->second.end() ? std::nan("") : r7->second.peak_theta);
  }
  if (!res.oat.empty()) res.flips = find_flips(res.oat);
  return oat_csv;
}

}  // namespace uncertainty

}  // namespace nsb::studies
