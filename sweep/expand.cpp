#include "io/csv.hpp"
#include "sweep/expand.hpp"

#include <algorithm>
#include <random>
#include <utility>

namespace nsb::sweep {

namespace {

// A uniform double in [0, 1) from the top 53 bits: the same on every platform, unlike
// std::uniform_real_distribution, whose algorithm the standard leaves open.
double unit(std::mt19937_64& g) { return static_cast<double>(g() >> 11) * 0x1.0p-53; }

}  // namespace

void expand_grid(Design& d) {
  std::vector<std::size_t> at(d.factors.size(), 0);
  for (;;) {
    Run run;
    run.overrides = d.set;
    for (std::size_t k = 0; k < d.factors.size(); ++k) {
      const Level& l = d.factors[k].levels[at[k]];
      run.labels.push_back(l.label);
      run.overrides.insert(run.overrides.end(), l.overrides.begin(), l.overrides.end());
    }
    d.runs.push_back(std::move(run));
    // Odometer with the last factor fastest.
    std::size_t k = d.factors.size();
    while (k > 0) {
      --k;
      if (++at[k] < d.factors[k].levels.size()) break;
      at[k] = 0;
      if (k == 0) return;
    }
    if (d.factors.empty()) return;
  }
}

void expand_oat(Design& d) {
  Run base;
  base.labels.assign(d.factors.size(), std::string());
  base.overrides = d.set;
  d.runs.push_back(base);
  for (std::size_t k = 0; k < d.factors.size(); ++k) {
    for (const Level& l : d.factors[k].levels) {
      Run run = base;
      run.labels[k] = l.label;
      run.overrides.insert(run.overrides.end(), l.overrides.begin(), l.overrides.end());
      d.runs.push_back(std::move(run));
    }
  }
}

std::vector<std::vector<double>> latin_hypercube(std::size_t samples, std::size_t factors,
                                                 std::uint64_t seed) {
  std::mt19937_64 g(seed);
  std::vector<std::vector<double>> draw(factors, std::vector<double>(samples));
  for (std::size_t k = 0; k < factors; ++k) {
    std::vector<std::size_t> perm(samples);
    for (std::size_t i = 0; i < samples; ++i) perm[i] = i;
    for (std::size_t i = samples; i > 1; --i) {  // Fisher–Yates
      const auto j = static_cast<std::size_t>(unit(g) * static_cast<double>(i));
      std::swap(perm[i - 1], perm[std::min(j, i - 1)]);
    }
    for (std::size_t i = 0; i < samples; ++i) {
      draw[k][i] = (static_cast<double>(perm[i]) + unit(g)) / static_cast<double>(samples);
    }
  }
  return draw;
}

// Latin hypercube (McKay, Beckman & Conover 1979), drawn by latin_hypercube; continuous factors
// map the draw linearly onto their range, discrete factors take the level whose share of
// [0, 1) holds the draw.
void expand_latin(Design& d) {
  const auto n = static_cast<std::size_t>(d.samples);
  const auto draw = latin_hypercube(n, d.factors.size(), d.seed);
  for (std::size_t i = 0; i < n; ++i) {
    Run run;
    run.overrides = d.set;
    for (std::size_t k = 0; k < d.factors.size(); ++k) {
      const Factor& f = d.factors[k];
      if (f.range) {
        const double v = (*f.range)[0] + draw[k][i] * ((*f.range)[1] - (*f.range)[0]);
        run.labels.push_back(io::csv_number(v));
        run.overrides.push_back({f.key, v});
      } else {
        const auto m = f.levels.size();
        const Level& l = f.levels[std::min(
            m - 1, static_cast<std::size_t>(draw[k][i] * static_cast<double>(m)))];
        run.labels.push_back(l.label);
        run.overrides.insert(run.overrides.end(), l.overrides.begin(), l.overrides.end());
      }
    }
    d.runs.push_back(std::move(run));
  }
}

}  // namespace nsb::sweep
