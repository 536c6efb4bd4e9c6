// The design step of the uncertainty study: the study's claim runs and the points of its
// one-at-a-time and hypercube designs.
#include "studies/uncertainty_steps.hpp"

#include <iomanip>
#include <sstream>

#include "io/csv.hpp"

namespace nsb::studies {

using namespace paper_figures;  // the claims and the claim runs the study judges

const std::vector<ClaimRun>& claim_runs() {
  static const std::vector<ClaimRun> r = [] {
    std::vector<ClaimRun> v = fig6_runs(uncertainty::kStudyPgaRuns, uncertainty::kStudyMu0Runs);
    for (auto& c : uncertainty::compliance_claim_runs()) v.push_back(std::move(c));
    return v;
  }();
  return r;
}

namespace uncertainty {

std::vector<Point> oat_points() {
  const auto& as = assumptions();
  std::vector<Point> oat{{"nominal", nominal_point(), std::vector<std::string>(as.size()), "", ""}};
  for (std::size_t k = 0; k < as.size(); ++k) {
    for (const char* end : {"low", "high"}) {
      Point p{as[k].key + "-" + end, nominal_point(), std::vector<std::string>(as.size()),
              as[k].key, end};
      p.values[k] = std::string(end) == "low" ? as[k].low : as[k].high;
      p.labels[k] = io::csv_number(p.values[k]);
      oat.push_back(std::move(p));
    }
  }
  return oat;
}

std::vector<Point> latin_points(std::size_t samples, std::uint64_t seed) {
  const auto& as = assumptions();
  const auto draw = sweep::latin_hypercube(samples, as.size(), seed);
  std::vector<Point> lhs;
  for (std::size_t i = 0; i < samples; ++i) {
    std::ostringstream name;
    name << "s" << std::setw(4) << std::setfill('0') << i;
    Point p{name.str(), {}, {}, "", ""};
    for (std::size_t k = 0; k < as.size(); ++k) {
      const double u = draw[k][i];
      // A two-valued assumption takes the end whose half of [0, 1) holds the draw, as the
      // sweep's latin mode does for a factor of two levels.
      const double v = as[k].two_values ? (u < 0.5 ? as[k].low : as[k].high)
                                        : as[k].low + u * (as[k].high - as[k].low);
      p.values.push_back(v);
      p.labels.push_back(io::csv_number(v));
    }
    lhs.push_back(std::move(p));
  }
  return lhs;
}

}  // namespace uncertainty

}  // namespace nsb::studies
