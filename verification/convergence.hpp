// Measures shared by the convergence checks: the difference of two recorded histories, a
// column's peak, and the least-squares power law e = C x^p through measured errors.
#pragma once

#include "integrators/recorder.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace nsb::verification {

// max |a(t) - b(t)| over the sample times of a, with b interpolated linearly between its
// samples; samples of a past the end of b are not compared.
inline double history_error(const integrators::Recorder& a, const integrators::Recorder& b,
                            const char* column) {
  const auto ta = a.series("t"), xa = a.series(column);
  const auto tb = b.series("t"), xb = b.series(column);
  double err = 0.0;
  std::size_t j = 0;
  for (std::size_t i = 0; i < ta.size(); ++i) {
    while (j + 2 < tb.size() && tb[j + 1] < ta[i]) ++j;
    if (j + 1 >= tb.size() || ta[i] > tb.back()) break;
    const double w = (tb[j + 1] > tb[j]) ? (ta[i] - tb[j]) / (tb[j + 1] - tb[j]) : 0.0;
    err = std::max(err, std::abs(xa[i] - ((1.0 - w) * xb[j] + w * xb[j + 1])));
  }
  return err;
}

// max |column| over the recorded samples.
inline double peak_abs(const integrators::Recorder& r, const char* column) {
  double p = 0.0;
  for (double v : r.series(column)) p = std::max(p, std::abs(v));
  return p;
}

// The least-squares line through (log x_i, log e_i): e = constant x^slope.
struct PowerFit {
  double slope = 0.0;     // p, the measured order
  double constant = 0.0;  // C, the error constant
};
inline PowerFit fit_power_law(const std::vector<double>& x, const std::vector<double>& e) {
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double lx = std::log(x[i]), ly = std::log(e[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  PowerFit f;
  f.slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  f.constant = std::exp((sy - f.slope * sx) / n);
  return f;
}

}  // namespace nsb::verification
