#include "benchmarks/performance_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace nsb::benchmarks {

PerformanceProfile::PerformanceProfile(const std::vector<std::vector<double>>& cost) {
  const std::size_t np = cost.empty() ? 0 : cost[0].size();
  for (std::size_t s = 0; s < cost.size(); ++s) {
    if (cost[s].size() != np)
      throw std::invalid_argument("PerformanceProfile: solver " + std::to_string(s) + " has " +
                                  std::to_string(cost[s].size()) + " costs; expected " +
                                  std::to_string(np) + ", one per problem");
    for (std::size_t p = 0; p < np; ++p) {
      if (!(cost[s][p] > 0.0))
        throw std::invalid_argument("PerformanceProfile: cost[" + std::to_string(s) + "][" +
                                    std::to_string(p) + "] = " + std::to_string(cost[s][p]) +
                                    "; expected a cost > 0, or +inf for a failure");
    }
  }
  constexpr double kInf = std::numeric_limits<double>::infinity();
  ratio_.assign(cost.size(), std::vector<double>(np, kInf));
  for (std::size_t p = 0; p < np; ++p) {
    double best = kInf;
    for (const auto& c : cost) best = std::min(best, c[p]);
    if (std::isinf(best)) continue;  // every solver failed: +inf for all
    for (std::size_t s = 0; s < cost.size(); ++s) ratio_[s][p] = cost[s][p] / best;
  }
  sorted_ = ratio_;
  for (auto& r : sorted_) std::sort(r.begin(), r.end());
}

double PerformanceProfile::ratio(int s, int p) const {
  return ratio_.at(static_cast<std::size_t>(s)).at(static_cast<std::size_t>(p));
}

double PerformanceProfile::rho(int s, double tau) const {
  const auto& r = sorted_.at(static_cast<std::size_t>(s));
  if (r.empty()) return 0.0;
  // A failure (+inf) is within no factor, not even tau = +inf.
  if (std::isinf(tau)) tau = std::numeric_limits<double>::max();
  const auto within = std::upper_bound(r.begin(), r.end(), tau) - r.begin();
  return static_cast<double>(within) / static_cast<double>(r.size());
}

int PerformanceProfile::failures(int s) const {
  const auto& r = ratio_.at(static_cast<std::size_t>(s));
  return static_cast<int>(std::count_if(r.begin(), r.end(), [](double x) { return std::isinf(x); }));
}

double PerformanceProfile::max_ratio() const {
  double m = 1.0;
  for (const auto& r : ratio_) {
    for (double x : r) {
      if (std::isfinite(x)) m = std::max(m, x);
    }
  }
  return m;
}

}  // namespace nsb::benchmarks
