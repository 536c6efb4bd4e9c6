// Response spectra: the interval coefficients against Chopra's Table 5.2.1, hand-solved
// responses, the period grid, scaling properties and the rejection of bad input. The g of a
// .AT2 file read by the scene's record reader: scene/test/recorded_motions_test.cpp.
#include "models/response_spectrum.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

using nsb::models::Record;
using nsb::models::SdofStep;
using nsb::models::SpectrumOptions;

namespace {

constexpr double kPi = std::numbers::pi;
// Two algebraic forms of the same coefficients agree to round-off amplified by the
// cancellation in C and D, which grows like 1 / (w h)^2 (w h >= 0.01 here: 1e-16 / 1e-4).
constexpr double kFormTolerance = 1e-10;
// A recurrence that is exact for the load reproduces closed forms to round-off.
constexpr double kExactTolerance = 1e-11;

// Chopra, Dynamics of Structures, Table 5.2.1, written out as printed (unit mass, k = w^2).
SdofStep chopra_table_5_2_1(double w, double zeta, double dt) {
  SdofStep r(1.0, 0.0, 1.0);
  const double k = w * w, s1 = std::sqrt(1.0 - zeta * zeta), wd = w * s1;
  const double e = std::exp(-zeta * w * dt), s = std::sin(wd * dt), c = std::cos(wd * dt);
  r.A = e * (zeta / s1 * s + c);
  r.B = e * (s / wd);
  r.C = (2.0 * zeta / (w * dt) + e * (((1.0 - 2.0 * zeta * zeta) / (wd * dt) - zeta / s1) * s -
                                      (1.0 + 2.0 * zeta / (w * dt)) * c)) / k;
  r.D = (1.0 - 2.0 * zeta / (w * dt) +
         e * ((2.0 * zeta * zeta - 1.0) / (wd * dt) * s + 2.0 * zeta / (w * dt) * c)) / k;
  r.Ap = -e * (w / s1 * s);
  r.Bp = e * (c - zeta / s1 * s);
  r.Cp = (-1.0 / dt + e * ((w / s1 + zeta / (dt * s1)) * s + c / dt)) / k;
  r.Dp = (1.0 - e * (zeta / s1 * s + c)) / (k * dt);
  return r;
}

// Uniform record a(t_i) = f(t_i), t_i = i dt, i = 0..n-1.
template <class F>
Record sampled(F f, double dt, int n) {
  Record r;
  r.source = "sampled";
  for (int i = 0; i < n; ++i) {
    r.t.push_back(i * dt);
    r.a.push_back(f(i * dt));
  }
  return r;
}

std::string message_of(auto&& call) {
  try {
    call();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no exception";
}

}  // namespace

TEST_CASE("response_spectrum: the interval coefficients equal Chopra's Table 5.2.1") {
  for (const double period : {0.01, 0.1, 1.0, 10.0}) {
    for (const double zeta : {0.0, 0.02, 0.05, 0.3, 0.9}) {
      for (const double h : {0.001, 0.005, 0.02}) {
        const double w = 2.0 * kPi / period;
        if (w * h < 0.01) continue;  // outside kFormTolerance's bound on the cancellation
        const SdofStep s(w, zeta, h);
        const SdofStep c = chopra_table_5_2_1(w, zeta, h);
        INFO("T = " << period << ", zeta = " << zeta << ", h = " << h);
        const double ku = 1.0 / (w * w), kv = 1.0 / w;  // scales of C, D and of Cp, Dp
        CHECK(s.A == doctest::Approx(c.A).epsilon(kFormTolerance).scale(1.0));
        CHECK(s.B == doctest::Approx(c.B).epsilon(kFormTolerance).scale(kv));
        CHECK(s.C == doctest::Approx(c.C).epsilon(kFormTolerance).scale(ku));
        CHECK(s.D == doctest::Approx(c.D).epsilon(kFormTolerance).scale(ku));
        CHECK(s.Ap == doctest::Approx(c.Ap).epsilon(kFormTolerance).scale(w));
        CHECK(s.Bp == doctest::Approx(c.Bp).epsilon(kFormTolerance).scale(1.0));
        CHECK(s.Cp == doctest::Approx(c.Cp).epsilon(kFormTolerance).scale(kv));
        CHECK(s.Dp == doctest::Approx(c.Dp).epsilon(kFormTolerance).scale(kv));
      }
    }
  }
}

TEST_CASE("response_spectrum: the recurrence is exact for a ramp load (by hand)") {
  // u'' + w^2 u = t from rest: u = (t - sin(w t) / w) / w^2, v = (1 - cos(w t)) / w^2.
  const double w = 3.0, h = 0.41;
  const SdofStep s(w, 0.0, h);
  double u = 0.0, v = 0.0;
  for (int i = 0; i < 30; ++i) {
    const double t0 = i * h, t1 = t0 + h;
    const double un = s.A * u + s.B * v + s.C * t0 + s.D * t1;
    v = s.Ap * u + s.Bp * v + s.Cp * t0 + s.Dp * t1;
    u = un;
    CHECK(u == doctest::Approx((t1 - std::sin(w * t1) / w) / (w * w)).epsilon(kExactTolerance));
    CHECK(v == doctest::Approx((1.0 - std::cos(w * t1)) / (w * w)).epsilon(kExactTolerance));
  }
}

TEST_CASE("response_spectrum: step record, uniform and non-uniform samples, gives the closed form") {
  // a_g = a0 for t >= 0 (from rest): u = -(a0/w^2) [1 - e^{-z w t}(cos wd t + z/sqrt(1-z^2)
  // sin wd t)], whose largest |u| is at the first peak t* = pi / wd:
  // Sd = (a0 / w^2) (1 + exp(-z pi / sqrt(1 - z^2))). t* is a sample time in both records.
  const double a0 = 2.0, period = 0.8, zeta = 0.05;
  const double w = 2.0 * kPi / period, wd = w * std::sqrt(1.0 - zeta * zeta);
  const double t_peak = kPi / wd;
  const double expected = a0 / (w * w) * (1.0 + std::exp(-zeta * kPi / std::sqrt(1.0 - zeta * zeta)));
  const Record uniform = sampled([&](double) { return a0; }, t_peak / 40.0, 200);
  CHECK(nsb::models::spectral_displacement(uniform, period, zeta) ==
        doctest::Approx(expected).epsilon(kExactTolerance));
  Record irregular;  // steps alternating 1 and 3 units of t_peak / 40: t* is still a sample
  irregular.source = "irregular";
  for (double t = 0.0, k = 0; t < 3.0 * t_peak; t += t_peak / 40.0 * (int(k++) % 2 ? 3 : 1)) {
    irregular.t.push_back(t);
    irregular.a.push_back(a0);
  }
  CHECK(nsb::models::spectral_displacement(irregular, period, zeta) ==
        doctest::Approx(expected).epsilon(kExactTolerance));
}

TEST_CASE("response_spectrum: PSV, PSA and Sd are linked by w and scale with the record") {
  const Record r = sampled([](double t) { return std::sin(7.0 * t) * std::exp(-0.3 * t); }, 0.01, 1000);
  Record doubled = r;
  for (double& a : doubled.a) a *= 2.0;
  SpectrumOptions o;
  o.periods = {0.0, 0.05, 0.5, 2.0};
  const auto s = nsb::models::response_spectrum(r, o);
  const auto s2 = nsb::models::response_spectrum(doubled, o);
  REQUIRE(s.periods.size() == 4);
  // T = 0: PGA in g, no displacement.
  double pga = 0.0;
  for (double a : r.a) pga = std::max(pga, std::abs(a));
  CHECK(s.psa_g[0] == doctest::Approx(pga / nsb::models::kSpectrumGravity));
  CHECK(s.sd_m[0] == 0.0);
  for (std::size_t i = 1; i < 4; ++i) {
    const double w = 2.0 * kPi / s.periods[i];
    CHECK(s.sd_m[i] > 0.0);
    CHECK(s.psv_m_s[i] == doctest::Approx(w * s.sd_m[i]));
    CHECK(s.psa_g[i] == doctest::Approx(w * w * s.sd_m[i] / nsb::models::kSpectrumGravity));
    CHECK(s2.sd_m[i] == doctest::Approx(2.0 * s.sd_m[i]).epsilon(kExactTolerance));
  }
  // A stiff oscillator follows the ground: PSA(T -> 0) -> PGA.
  CHECK(s.psa_g[1] == doctest::Approx(s.psa_g[0]).epsilon(0.05));
}

TEST_CASE("response_spectrum: the NGA-West2 grid and log-spaced periods") {
  const auto p = nsb::models::nga_west2_periods();
  REQUIRE(p.size() == 105);
  CHECK(p.front() == 0.01);
  CHECK(p.back() == 10.0);
  for (std::size_t i = 1; i < p.size(); ++i) CHECK(p[i] > p[i - 1]);
  CHECK(SpectrumOptions{}.periods.size() == 105);
  const auto l = nsb::models::log_spaced_periods(0.1, 10.0, 5);
  REQUIRE(l.size() == 5);
  CHECK(l[0] == 0.1);
  CHECK(l[2] == doctest::Approx(1.0));
  CHECK(l[4] == 10.0);
  CHECK(message_of([] { nsb::models::log_spaced_periods(1.0, 0.5, 5); }).find("periods") == 0);
  CHECK(message_of([] { nsb::models::log_spaced_periods(0.1, 1.0, 1); }).find("count") !=
        std::string::npos);
}

TEST_CASE("response_spectrum: bad periods and damping are refused by name") {
  const Record r = sampled([](double t) { return std::sin(t); }, 0.01, 100);
  SpectrumOptions o;
  o.periods = {0.5, -1.0};
  const std::string neg = message_of([&] { nsb::models::response_spectrum(r, o); });
  CHECK(neg.find("periods[1]") != std::string::npos);
  CHECK(neg.find("-1") != std::string::npos);
  o.periods = {double(NAN)};
  CHECK(message_of([&] { o.validate(); }).find("periods[0]: period T = nan") == 0);
  o.periods = {};
  CHECK(message_of([&] { o.validate(); }).find("periods") == 0);
  o.periods = {1.0};
  for (const double zeta : {-0.01, 1.0, double(INFINITY), double(NAN)}) {
    o.damping = zeta;
    CHECK(message_of([&] { o.validate(); }).find("damping: zeta") == 0);
  }
  CHECK(message_of([&] { nsb::models::spectral_displacement(r, INFINITY, 0.05); })
            .find("period: period T = inf") == 0);
  CHECK(nsb::models::spectral_displacement(r, 0.0, 0.05) == 0.0);
  Record two = r;
  two.t.resize(2);
  two.a.resize(2);
  CHECK(message_of([&] { nsb::models::response_spectrum(two, SpectrumOptions{}); })
            .find("sampled") != std::string::npos);
}

TEST_CASE("asce7_design_spectrum: the four branches of ASCE 7-16 Fig. 11.4-1 by hand") {
  // S_DS = 1.0 g, S_D1 = 0.6 g, T_L = 8 s: T0 = 0.2 * 0.6 / 1.0 = 0.12 s, Ts = 0.6 s.
  const double sds = 1.0, sd1 = 0.6, tl = 8.0;
  using nsb::models::asce7_design_spectrum;
  CHECK(asce7_design_spectrum(sds, sd1, tl, 0.0) == doctest::Approx(0.4));           // 0.4 S_DS
  CHECK(asce7_design_spectrum(sds, sd1, tl, 0.06) == doctest::Approx(0.7));          // 0.4 + 0.6/2
  CHECK(asce7_design_spectrum(sds, sd1, tl, 0.12) == doctest::Approx(1.0));          // T0: plateau
  CHECK(asce7_design_spectrum(sds, sd1, tl, 0.6) == doctest::Approx(1.0));           // Ts
  CHECK(asce7_design_spectrum(sds, sd1, tl, 1.2) == doctest::Approx(0.5));           // 0.6 / 1.2
  CHECK(asce7_design_spectrum(sds, sd1, tl, 8.0) == doctest::Approx(0.075));         // 0.6 / 8
  CHECK(asce7_design_spectrum(sds, sd1, tl, 10.0) == doctest::Approx(0.048));        // 0.6*8/100
  // Continuous at T0, Ts and T_L.
  for (const double t : {0.12, 0.6, 8.0}) {
    CHECK(asce7_design_spectrum(sds, sd1, tl, t * (1 - 1e-12)) ==
          doctest::Approx(asce7_design_spectrum(sds, sd1, tl, t * (1 + 1e-12))));
  }
  CHECK_THROWS_WITH_AS(asce7_design_spectrum(0.0, sd1, tl, 1.0),
                       doctest::Contains("sds"), std::invalid_argument);
  CHECK_THROWS_WITH_AS(asce7_design_spectrum(sds, sd1, 0.3, 1.0),
                       doctest::Contains("tl"), std::invalid_argument);
  CHECK_THROWS_WITH_AS(asce7_design_spectrum(sds, sd1, tl, -1.0),
                       doctest::Contains("period"), std::invalid_argument);
}
