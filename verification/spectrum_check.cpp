// Response spectra (models/response_spectrum.hpp) against references from outside the code:
// (a) closed forms: the step response's first peak and the steady-state amplitude of a
//     harmonic record at and off resonance;
// (b) Chopra, Dynamics of Structures, §6.4: peak deformations of SDF systems under the 1940
//     El Centro N-S record (the record and numbers of verification/chopra_sdof_check.cpp);
// (c) Newmark's average-acceleration method on the record refined linearly (m sub-steps per
//     record step) converges to the exact-interval response at second order.
// Tolerances and measured figures: docs/spectra.md, "Checks".
#include "models/response_spectrum.hpp"
#include "scene/records.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <vector>

namespace {

namespace fs = std::filesystem;
using nsb::models::Record;
using nsb::models::SdofStep;

constexpr double kPi = std::numbers::pi;

// (a) The step response is reproduced to round-off: measured worst 2.7e-14; 1e-11 leaves
// room for other compilers and platforms (the recurrence is exact for a constant load).
constexpr double kClosedFormTolerance = 1e-11;
// (a) Harmonic records: the linear interpolant of the sampled sine differs from the sine; its
// fundamental has amplitude A sinc^2(W h / 2) (derivation below), which the expected values
// include. What remains: the aliased harmonics near 2 pi k / h (relative amplitude
// sin^2(W h/2)/(pi k)^2 = 2.5e-5, filtered by (w h / 2 pi k)^2 ~ 1e-4 at W h = 2 pi / 200)
// and the transient: below 1e-8 at the end, but at resonance Sd is the largest peak over the
// whole record, and for zeta = 0.2 a late peak of the decaying transient (frequency wd, out
// of phase with the steady state by (w - wd) t) adds to it. Measured: 5.7e-9 (zeta = 0.05)
// and 4.9e-8 (zeta = 0.2) at resonance, 6.5e-9 and 8.7e-9 off resonance; 5e-7 is 10x the worst.
constexpr double kHarmonicTolerance = 5e-7;
// (b) Chopra quotes peaks to 3 significant figures: agreement within 1 %, as chopra_sdof_check.
constexpr double kChopraTolerance = 0.01;
constexpr double kMetresPerInch = 0.0254;
constexpr double kChopraG = 386.0;  // [in/s^2], Chopra's g
// (c) Measured orders of the history error between successive refinements m -> 2m:
// 1.996 to 2.000 from m = 2 on (T = 0.5, 1, 2 s); asserted from m = 4 within kOrderMargin
// of 2, 12x the largest measured deviation (0.004).
constexpr double kExpectedOrder = 2.0;
constexpr double kOrderMargin = 0.05;

const fs::path kElCentro = fs::path(NSB_DATA_DIR) / "ground-motions/elCentro_NS_1940_Peknold.AT2";

struct ChopraCase {
  double period, zeta, peak_in;
};
// Chopra §6.4: peak deformations D [in] for (T_n, zeta) under El Centro 1940 N-S.
constexpr std::array<ChopraCase, 5> kChopra{{{0.5, 0.02, 2.67},
                                             {1.0, 0.02, 5.97},
                                             {2.0, 0.02, 7.47},
                                             {2.0, 0.00, 9.91},
                                             {2.0, 0.05, 5.37}}};

Record uniform_record(double dt, int n, auto f) {
  Record r;
  r.source = "closed form";
  for (int i = 0; i < n; ++i) {
    r.t.push_back(i * dt);
    r.a.push_back(f(i * dt));
  }
  return r;
}

double relative(double x, double ref) { return std::abs(x / ref - 1.0); }

// The linear interpolant of sin(W t) sampled at h has the Fourier component at W of amplitude
// sinc^2(W h / 2): linear interpolation is the convolution of the samples with the hat
// function of width 2h, whose transform is h sinc^2(W h / 2), and the samples' spectrum at
// |W| < pi / h is the sine's own divided by h.
double interpolation_gain(double W, double h) {
  const double x = W * h / 2.0;
  return std::pow(std::sin(x) / x, 2);
}

// Exact-interval history u(t_i) at the record samples (library coefficients, one step per
// sample interval, uniform record).
std::vector<double> exact_history(const Record& r, double w, double zeta) {
  const SdofStep s(w, zeta, r.t[1] - r.t[0]);
  std::vector<double> u_out{0.0};
  double u = 0.0, v = 0.0;
  for (std::size_t i = 0; i + 1 < r.a.size(); ++i) {
    const double un = s.A * u + s.B * v - s.C * r.a[i] - s.D * r.a[i + 1];
    v = s.Ap * u + s.Bp * v - s.Cp * r.a[i] - s.Dp * r.a[i + 1];
    u = un;
    u_out.push_back(u);
  }
  return u_out;
}

// Newmark, gamma = 1/2, beta = 1/4 (Chopra §5.4), for u'' + 2 zeta w u' + w^2 u = -a_g with
// a_g linear between the record samples, m steps per record step; u at the record samples.
std::vector<double> newmark_history(const Record& r, double w, double zeta, int m) {
  const double h = (r.t[1] - r.t[0]) / m, c = 2.0 * zeta * w, k = w * w;
  const double beta = 0.25, gamma = 0.5;
  const double lhs = 1.0 + gamma * h * c + beta * h * h * k;
  double u = 0.0, v = 0.0, a = -r.a[0];
  std::vector<double> u_out{0.0};
  for (std::size_t i = 0; i + 1 < r.a.size(); ++i) {
    for (int j = 1; j <= m; ++j) {
      const double p = -(r.a[i] + (r.a[i + 1] - r.a[i]) * j / m);
      const double us = u + h * v + h * h * (0.5 - beta) * a;
      const double vs = v + h * (1.0 - gamma) * a;
      a = (p - c * vs - k * us) / lhs;
      u = us + beta * h * h * a;
      v = vs + gamma * h * a;
    }
    u_out.push_back(u);
  }
  return u_out;
}

double max_abs(const std::vector<double>& x) {
  double m = 0.0;
  for (double y : x) m = std::max(m, std::abs(y));
  return m;
}

}  // namespace

TEST_CASE("spectrum: a step record gives the closed-form first peak") {
  // a_g = a0 from rest: u = -(a0/w^2)[1 - e^{-z w t}(cos wd t + z/sqrt(1-z^2) sin wd t)].
  // u' = 0 at wd t = k pi; the first (largest) extremum, t* = pi / wd, gives
  // Sd = (a0/w^2)(1 + exp(-z pi / sqrt(1-z^2))): 2 a0 / w^2 without damping.
  // dt = t* / 50, so t* is a sample.
  for (const double period : {0.2, 1.0, 3.0}) {
    for (const double zeta : {0.0, 0.05, 0.2}) {
      const double a0 = 1.7, w = 2.0 * kPi / period, root = std::sqrt(1.0 - zeta * zeta);
      const double t_peak = kPi / (w * root);
      const Record r = uniform_record(t_peak / 50.0, 151, [&](double) { return a0; });
      const double expected = a0 / (w * w) * (1.0 + std::exp(-zeta * kPi / root));
      const double sd = nsb::models::spectral_displacement(r, period, zeta);
      INFO("T = " << period << " s, zeta = " << zeta);
      std::printf("step: T = %.1f s, zeta = %.2f: Sd %.12e m, closed form %.12e m (%.1e)\n",
                  period, zeta, sd, expected, relative(sd, expected));
      CHECK(relative(sd, expected) <= kClosedFormTolerance);
    }
  }
}

TEST_CASE("spectrum: a harmonic record at resonance gives the steady-state amplitude") {
  // a_g = A sin(w t) with w = 2 pi / T: the steady state is u = (A_e / (2 zeta w^2)) cos(w t)
  // (phase lag pi/2, dynamic amplification 1 / (2 zeta)), A_e = A sinc^2(w h / 2) for the
  // interpolated record. From rest the envelope grows like 1 - e^{-zeta w t} and beats at
  // the frequency w (1 - sqrt(1 - zeta^2)), slower than the decay, so the response approaches
  // the steady state from below up to what is left of the transient (kHarmonicTolerance):
  // Sd is the steady-state amplitude. T / h = 200 is even, so the
  // extrema t = k T / 2 are samples. 60 cycles: e^{-zeta w t} = e^{-0.05 2 pi 60} < 1e-8.
  const double A = 2.5, period = 1.0, h = period / 200.0;
  for (const double zeta : {0.05, 0.2}) {
    const double w = 2.0 * kPi / period;
    const Record r = uniform_record(h, 60 * 200 + 1, [&](double t) { return A * std::sin(w * t); });
    const double expected = A * interpolation_gain(w, h) / (2.0 * zeta * w * w);
    const double sd = nsb::models::spectral_displacement(r, period, zeta);
    std::printf("harmonic at resonance, zeta = %.2f: Sd %.10e m, closed form %.10e m (%.1e)\n",
                zeta, sd, expected, relative(sd, expected));
    CHECK(relative(sd, expected) <= kHarmonicTolerance);
  }
}

TEST_CASE("spectrum: harmonic records off resonance give the steady-state amplitude") {
  // a_g = A sin(W t), r = W / w: the steady state u = U sin(W t - phi) has
  // U = (A_e / w^2) / sqrt((1 - r^2)^2 + (2 zeta r)^2) (Chopra §3.2), and at any instant
  // U^2 = u^2 + (u' / W)^2. It is read at the record's end, after 60 s of T = 1 s: the
  // transient is below e^{-0.05 2 pi 60} < 1e-8.
  const double A = 2.5, period = 1.0, zeta = 0.05, w = 2.0 * kPi / period;
  for (const double ratio : {0.5, 2.0}) {
    const double W = ratio * w, h = 2.0 * kPi / W / 200.0;
    const auto n = static_cast<int>(std::lround(60.0 / h));
    const Record r = uniform_record(h, n + 1, [&](double t) { return A * std::sin(W * t); });
    const SdofStep s(w, zeta, h);
    double u = 0.0, v = 0.0;
    for (int i = 0; i < n; ++i) {
      const double un = s.A * u + s.B * v - s.C * r.a[i] - s.D * r.a[i + 1];
      v = s.Ap * u + s.Bp * v - s.Cp * r.a[i] - s.Dp * r.a[i + 1];
      u = un;
    }
    const double amplitude = std::hypot(u, v / W);
    const double expected = A * interpolation_gain(W, h) / (w * w) /
                            std::hypot(1.0 - ratio * ratio, 2.0 * zeta * ratio);
    std::printf("harmonic, W/w = %.1f: amplitude %.10e m, closed form %.10e m (%.1e)\n", ratio,
                amplitude, expected, relative(amplitude, expected));
    CHECK(relative(amplitude, expected) <= kHarmonicTolerance);
  }
}

TEST_CASE("spectrum: El Centro 1940 N-S against Chopra section 6.4 within 1 %") {
  // PSV = w D and PSA = w^2 D are Chopra's own definitions (§6.6); his A in g uses g = 386
  // in/s^2, ours 9.81 m/s^2 (0.06 % apart), so PSA is compared through w^2 D / g of his D.
  const Record rec = nsb::scene::read_at2(kElCentro);
  for (const auto& c : kChopra) {
    nsb::models::SpectrumOptions o;
    o.damping = c.zeta;
    o.periods = {c.period};
    const auto s = nsb::models::response_spectrum(rec, o);
    const double w = 2.0 * kPi / c.period;
    const double d_in = s.sd_m[0] / kMetresPerInch;
    const double v_in = s.psv_m_s[0] / kMetresPerInch;
    const double a_chopra = w * w * c.peak_in / kChopraG;
    std::printf("El Centro T = %.1f s, zeta = %.2f: D %.3f in (Chopra %.2f, %+.2f %%), "
                "V %.2f in/s (%.2f), A %.4f g (%.4f g, %+.2f %%)\n",
                c.period, c.zeta, d_in, c.peak_in, 100.0 * (d_in / c.peak_in - 1.0), v_in,
                w * c.peak_in, s.psa_g[0], a_chopra, 100.0 * (s.psa_g[0] / a_chopra - 1.0));
    INFO("T = " << c.period << " s, zeta = " << c.zeta);
    CHECK(relative(d_in, c.peak_in) <= kChopraTolerance);
    CHECK(relative(v_in, w * c.peak_in) <= kChopraTolerance);
    CHECK(relative(s.psa_g[0], a_chopra) <= kChopraTolerance);
  }
}

TEST_CASE("spectrum: Newmark average acceleration converges to the exact recurrence at order 2") {
  // Error of the history at the record samples, e(m) = max_i |u_N(t_i) - u_ex(t_i)| /
  // max |u_ex|, for m = 1, 2, ..., 32 Newmark steps per record step; the order between m and
  // 2m is log2(e(m) / e(2m)). Newmark's trapezoidal rule is second order and the refined
  // record is the same piecewise-linear excitation, so e -> 0 like (dt / m)^2. The peak error
  // |Sd_N - Sd| is at most e(m) max |u_ex| (peaks of two histories differ by at most their
  // largest difference) and is checked below that bound.
  const Record rec = nsb::scene::read_at2(kElCentro);
  for (const double period : {0.5, 1.0, 2.0}) {
    const double zeta = 0.05, w = 2.0 * kPi / period;
    const auto exact = exact_history(rec, w, zeta);
    const double scale = max_abs(exact);
    const double sd = nsb::models::spectral_displacement(rec, period, zeta);
    CHECK(relative(sd, scale) <= kClosedFormTolerance);  // T >= 20 dt: peaks at the samples
    double previous = 0.0;
    for (int m = 1; m <= 32; m *= 2) {
      const auto nm = newmark_history(rec, w, zeta, m);
      double e = 0.0;
      for (std::size_t i = 0; i < nm.size(); ++i) e = std::max(e, std::abs(nm[i] - exact[i]));
      e /= scale;
      const double peak_error = relative(max_abs(nm), sd);
      const double order = m > 1 ? std::log2(previous / e) : 0.0;
      std::printf("Newmark T = %.1f s, m = %2d: history error %.3e, peak error %.3e, order %.3f\n",
                  period, m, e, peak_error, order);
      INFO("T = " << period << " s, m = " << m);
      CHECK(peak_error <= e * (1.0 + 1e-12));
      if (m >= 4) CHECK(std::abs(order - kExpectedOrder) <= kOrderMargin);
      previous = e;
    }
  }
}
