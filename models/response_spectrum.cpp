// Elastic response spectra by the exact piecewise-linear recurrence (Nigam & Jennings 1969;
// Chopra §5.2). Derivation of the coefficients: docs/spectra.md.
#include "models/response_spectrum.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace nsb::models {
namespace {

// NGA-West2 flatfile periods [s] (Ancheta et al. 2014; PEER 2013/03): columns T0.010S to
// T10.000S of the PSA tables.
constexpr std::array<double, 105> kNgaWest2Periods{
    0.01,  0.02,  0.022, 0.025, 0.029, 0.03, 0.032, 0.035, 0.036, 0.04, 0.042, 0.044, 0.045,
    0.046, 0.048, 0.05,  0.055, 0.06,  0.065, 0.067, 0.07, 0.075, 0.08, 0.085, 0.09, 0.095,
    0.1,   0.11,  0.12,  0.13,  0.133, 0.14, 0.15,  0.16, 0.17,  0.18, 0.19,  0.2,  0.22,
    0.24,  0.25,  0.26,  0.28,  0.29,  0.3,  0.32,  0.34, 0.35,  0.36, 0.38,  0.4,  0.42,
    0.44,  0.45,  0.46,  0.48,  0.5,   0.55, 0.6,   0.65, 0.667, 0.7,  0.75,  0.8,  0.85,
    0.9,   0.95,  1.0,   1.1,   1.2,   1.3,  1.4,   1.5,  1.6,   1.7,  1.8,   1.9,  2.0,
    2.2,   2.4,   2.5,   2.6,   2.8,   3.0,  3.2,   3.4,  3.5,   3.6,  3.8,   4.0,  4.2,
    4.4,   4.6,   4.8,   5.0,   5.5,   6.0,  6.5,   7.0,  7.5,   8.0,  8.5,   9.0,  9.5,
    10.0};

// Steps within this fraction of the mean step count as one uniform step (AT2 times are
// i * DT, whose differences vary by round-off only); the mean step is then used for all.
constexpr double kUniformStepSlack = 1e-9;

std::string text(double x) {
  std::ostringstream os;
  os.precision(17);
  os << x;
  return os.str();
}

// where: "period", or "periods[i]" for entry i of a list; the text is built only on failure.
void check_period(double period, std::size_t index = std::string::npos) {
  if (!std::isfinite(period) || period < 0.0) {
    const std::string where =
        index == std::string::npos ? "period" : "periods[" + std::to_string(index) + "]";
    throw std::invalid_argument(where + ": period T = " + text(period) +
                                " s; expected a finite period >= 0 (0 stands for PGA)");
  }
}

void check_damping(double zeta) {
  if (!(zeta >= 0.0 && zeta < 1.0)) {
    throw std::invalid_argument("damping: zeta = " + text(zeta) +
                                "; expected a fraction of critical damping in [0, 1)");
  }
}

// The record's uniform step [s], or 0 when its steps differ beyond kUniformStepSlack.
double uniform_step(const Record& r) {
  const double mean = (r.t.back() - r.t.front()) / static_cast<double>(r.t.size() - 1);
  for (std::size_t i = 0; i + 1 < r.t.size(); ++i) {
    if (std::abs((r.t[i + 1] - r.t[i]) - mean) > kUniformStepSlack * mean) return 0.0;
  }
  return mean;
}

// Sub-steps of a record interval h for outputs at most period / kOutputsPerPeriod apart. The
// ratio is lowered by kRatioSlack before rounding up so that a ratio that is an integer but
// for round-off (0.02 * 20 / 0.4 = 1.0000000000000002) gives that integer.
constexpr double kRatioSlack = 1e-12;
int substeps(double h, double period) {
  return std::max(1, static_cast<int>(std::ceil(h * kOutputsPerPeriod / period - kRatioSlack)));
}

// Advances (u, v) over one record interval of m equal sub-steps with the load linear from p0
// to p1, and returns the largest |u| at the sub-step ends.
double advance(const SdofStep& s, int m, double p0, double p1, double& u, double& v) {
  double peak = 0.0;
  const double dp = (p1 - p0) / m;
  for (int k = 0; k < m; ++k) {
    const double q0 = p0 + k * dp, q1 = k + 1 == m ? p1 : p0 + (k + 1) * dp;
    const double un = s.A * u + s.B * v + s.C * q0 + s.D * q1;
    v = s.Ap * u + s.Bp * v + s.Cp * q0 + s.Dp * q1;
    u = un;
    peak = std::max(peak, std::abs(u));
  }
  return peak;
}

}  // namespace

// Free vibration about the particular solution of the linear load (docs/spectra.md):
// u_p(tau) = (p0 + s tau) / w^2 - 2 zeta s / w^3 with s = (p1 - p0) / h, and the homogeneous
// part y = u - u_p carried over h by the free-vibration matrix F.
SdofStep::SdofStep(double omega, double zeta, double h) {
  const double root = std::sqrt(1.0 - zeta * zeta);
  const double wd = omega * root;
  const double e = std::exp(-zeta * omega * h);
  const double c = std::cos(wd * h), s = std::sin(wd * h);
  // F: y(h) = F11 y0 + F12 y0',  y'(h) = F21 y0 + F22 y0'.
  const double f11 = e * (c + zeta / root * s);
  const double f12 = e * s / wd;
  const double f21 = -e * omega / root * s;
  const double f22 = e * (c - zeta / root * s);
  const double k = 1.0 / (omega * omega);             // static flexibility per unit mass
  const double g = 2.0 * zeta / (omega * omega * omega * h);  // the 2 zeta s / w^3 term per unit dp
  const double r = k / h;                               // u_p' = (p1 - p0) / (w^2 h)
  A = f11;
  B = f12;
  Ap = f21;
  Bp = f22;
  // u1 = F11 (u0 - u_p(0)) + F12 (v0 - u_p') + u_p(h), with u_p(0) = (k + g) p0 - g p1,
  // u_p(h) = g p0 + (k - g) p1, u_p' = r (p1 - p0); the same for v1 with F21, F22 and + u_p'.
  C = -f11 * (k + g) + f12 * r + g;
  D = f11 * g - f12 * r + k - g;
  Cp = -f21 * (k + g) + f22 * r - r;
  Dp = f21 * g - f22 * r + r;
}

std::span<const double> nga_west2_periods() { return kNgaWest2Periods; }

std::vector<double> log_spaced_periods(double first, double last, int count) {
  if (!(std::isfinite(first) && std::isfinite(last) && first > 0.0 && last > first)) {
    throw std::invalid_argument("periods: " + text(first) + ":" + text(last) +
                                "; expected 0 < first < last, finite [s]");
  }
  if (count < 2) {
    throw std::invalid_argument("periods: count " + std::to_string(count) +
                                "; expected at least 2 periods from first to last");
  }
  std::vector<double> out(static_cast<std::size_t>(count));
  const double step = std::log(last / first) / (count - 1);
  for (int i = 0; i < count; ++i) out[static_cast<std::size_t>(i)] = first * std::exp(step * i);
  out.back() = last;
  return out;
}

void SpectrumOptions::validate() const {
  check_damping(damping);
  if (periods.empty()) throw std::invalid_argument("periods: expected at least one period");
  for (std::size_t i = 0; i < periods.size(); ++i) {
    check_period(periods[i], i);
  }
}

double spectral_displacement(const Record& r, double period, double zeta) {
  check_period(period);
  check_damping(zeta);
  if (period == 0.0) return 0.0;
  if (r.t.size() < 2 || r.t.size() != r.a.size()) {  // what the loop below reads; validate_record
    throw std::invalid_argument("record '" + r.source + "': needs at least 2 samples of (t, a)");
  }
  const double omega = 2.0 * std::numbers::pi / period;
  const double h_uniform = uniform_step(r);
  double h = h_uniform > 0.0 ? h_uniform : r.t[1] - r.t[0];
  int m = substeps(h, period);
  SdofStep step(omega, zeta, h / m);
  double u = 0.0, v = 0.0, peak = 0.0;
  for (std::size_t i = 0; i + 1 < r.t.size(); ++i) {
    if (h_uniform == 0.0 && r.t[i + 1] - r.t[i] != h) {
      h = r.t[i + 1] - r.t[i];
      m = substeps(h, period);
      step = SdofStep(omega, zeta, h / m);
    }
    peak = std::max(peak, advance(step, m, -r.a[i], -r.a[i + 1], u, v));
  }
  return peak;
}

Spectrum response_spectrum(const Record& record, const SpectrumOptions& options) {
  options.validate();
  validate_record(record);
  Spectrum out;
  out.record = record.source;
  out.damping = options.damping;
  out.periods = options.periods;
  const std::size_t n = options.periods.size();
  out.sd_m.resize(n);
  out.psv_m_s.resize(n);
  out.psa_g.resize(n);
  double pga = 0.0;
  for (const double a : record.a) pga = std::max(pga, std::abs(a));
  for (std::size_t i = 0; i < n; ++i) {
    const double period = options.periods[i];
    if (period == 0.0) {
      out.psa_g[i] = pga / kSpectrumGravity;
      continue;
    }
    const double omega = 2.0 * std::numbers::pi / period;
    const double sd = spectral_displacement(record, period, options.damping);
    out.sd_m[i] = sd;
    out.psv_m_s[i] = omega * sd;
    out.psa_g[i] = omega * omega * sd / kSpectrumGravity;
  }
  return out;
}

double asce7_design_spectrum(double sds, double sd1, double tl, double period) {
  const auto bad = [](const char* name, double v, const char* what) {
    throw std::invalid_argument(std::string("asce7_design_spectrum: ") + name + " = " +
                                text(v) + ": " + what);
  };
  if (!(std::isfinite(sds) && sds > 0)) bad("sds", sds, "S_DS must be finite and > 0 [g]");
  if (!(std::isfinite(sd1) && sd1 > 0)) bad("sd1", sd1, "S_D1 must be finite and > 0 [g]");
  const double t0 = 0.2 * sd1 / sds, ts = sd1 / sds;
  if (!(std::isfinite(tl) && tl >= ts)) bad("tl", tl, "T_L must be finite and >= S_D1 / S_DS [s]");
  if (!(std::isfinite(period) && period >= 0)) bad("period", period, "must be finite and >= 0 [s]");
  if (period < t0) return sds * (0.4 + 0.6 * period / t0);
  if (period <= ts) return sds;
  if (period <= tl) return sd1 / period;
  return sd1 * tl / (period * period);
}

}  // namespace nsb::models
