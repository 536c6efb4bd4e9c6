// Elastic response spectra of a ground-acceleration record, as PEER computes them: the linear
// SDOF oscillator u'' + 2 zeta w u' + w^2 u = -a_g(t) is solved exactly over each interval
// with a_g linear between samples (Nigam & Jennings 1969, BSSA 59(2):909-922; Chopra,
// Dynamics of Structures, §5.2), from rest. Sd = max |u|, PSV = w Sd, PSA = w^2 Sd.
// Method, coefficients, period grid and checks: docs/spectra.md.
//
// Units: m, s, m/s^2; PSA is reported in units of g = kSpectrumGravity.
#pragma once

#include "models/ground_motion.hpp"

#include <span>
#include <string>
#include <vector>

namespace nsb::models {

// g [m/s^2] for PSA in g: the value read_at2 and the scenes use (scene/records.hpp).
inline constexpr double kSpectrumGravity = 9.81;

// Peaks are taken at the record's samples and, where a period is shorter than
// kOutputsPerPeriod record steps, at kOutputsPerPeriod equally spaced instants per period
// (each record interval split into exact sub-steps): a sampled sinusoid of period T then
// misses its peak by at most 1 - cos(pi / kOutputsPerPeriod) = 1.2 %.
inline constexpr int kOutputsPerPeriod = 20;

// Exact update of (u, v) over a step h for u'' + 2 zeta w u' + w^2 u = p(tau), with p linear
// from p0 to p1 within the step (per unit mass; p = -a_g for a ground acceleration):
//   u1 = A u0 + B v0 + C p0 + D p1,   v1 = Ap u0 + Bp v0 + Cp p0 + Dp p1.
// The formulas and their derivation: docs/spectra.md, "Interval coefficients".
struct SdofStep {
  SdofStep(double omega, double zeta, double h);  // omega > 0 [rad/s], zeta in [0, 1), h > 0 [s]
  double A = 0, B = 0, C = 0, D = 0;
  double Ap = 0, Bp = 0, Cp = 0, Dp = 0;
};

// The 105 periods [s], 0.01 to 10 s, at which the NGA-West2 flatfile tabulates PSA (Ancheta
// et al. 2014, Earthquake Spectra 30(3):989-1005; PEER report 2013/03). Listed in docs/spectra.md.
std::span<const double> nga_west2_periods();

// count periods from first to last [s], equally spaced in log T (first and last included).
// Throws std::invalid_argument unless 0 < first < last (finite) and count >= 2.
std::vector<double> log_spaced_periods(double first, double last, int count);

struct SpectrumOptions {
  double damping = 0.05;  // zeta, fraction of critical damping, in [0, 1)
  // Oscillator periods [s], each finite and >= 0; T = 0 stands for PGA (PSA = PGA / g,
  // Sd = PSV = 0, the limit T -> 0). Default: nga_west2_periods().
  std::vector<double> periods{nga_west2_periods().begin(), nga_west2_periods().end()};
  // Throws std::invalid_argument naming the field and, for a period, its value and position.
  void validate() const;
};

struct Spectrum {
  std::string record;          // the record's source
  double damping = 0.0;        // zeta
  std::vector<double> periods;  // [s]
  std::vector<double> sd_m;     // peak relative displacement [m]
  std::vector<double> psv_m_s;  // pseudo-velocity w Sd [m/s]
  std::vector<double> psa_g;    // pseudo-acceleration w^2 Sd [g]
};

// Sd [m] of one period [s] (> 0 finite; 0 gives 0) at damping zeta in [0, 1), from rest at the
// record's first sample. No heap allocation: the interval coefficients are computed once per
// step length (once per period for a uniformly sampled record). The record must be valid
// (validate_record); throws std::invalid_argument for a bad period or zeta.
double spectral_displacement(const Record& record, double period, double zeta);

// Sd, PSV and PSA of the record at every period of the options (validated first), and the
// record (validate_record).
Spectrum response_spectrum(const Record& record, const SpectrumOptions& options = {});

// The design response spectrum of ASCE/SEI 7-16 §11.4.6 (Fig. 11.4-1), Sa [g] at period T [s]:
//   T < T0:        Sa = S_DS (0.4 + 0.6 T / T0)        (eq. 11.4-5)
//   T0 <= T <= Ts: Sa = S_DS
//   Ts < T <= T_L: Sa = S_D1 / T                        (eq. 11.4-6)
//   T > T_L:       Sa = S_D1 T_L / T^2                  (eq. 11.4-7)
// with T0 = 0.2 S_D1 / S_DS and Ts = S_D1 / S_DS. sds = S_DS [g] > 0, sd1 = S_D1 [g] > 0,
// tl = T_L [s] >= Ts, period >= 0, all finite; throws std::invalid_argument naming the
// argument otherwise.
double asce7_design_spectrum(double sds, double sd1, double tl, double period);

}  // namespace nsb::models
