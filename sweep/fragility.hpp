// Lognormal fragility curves fitted to the results of many runs (docs/fragility.md).
//
// The model (Baker 2015, "Efficient analytical fragility function fitting using dynamic
// structural analysis", Earthquake Spectra 31(1):579-599, eq. 1): the probability that a
// limit state is reached in a run scaled to intensity measure IM = x is
//
//   P(x) = Phi(ln(x / theta) / beta),   theta > 0 the median capacity [unit of IM],
//                                       beta > 0 the dispersion of ln capacity [-].
//
// Two estimators, as Baker 2015 gives them:
// - multiple stripe analysis (MSA): stripe j runs n_j records at x_j, of which k_j exceed the
//   limit state. fit_mle maximizes the binomial log-likelihood of all stripes
//     l(theta, beta) = sum_j [ k_j ln P(x_j) + (n_j - k_j) ln(1 - P(x_j)) ]   (+ const);
// - incremental dynamic analysis (IDA): each record's capacity c_i (the IM at which it first
//   exceeds the limit state). fit_moments takes the moments of ln c (Baker 2015, eqs. 2-3).
//
// Two error channels (STYLE.md): malformed input (im <= 0 or non-finite, n <= 0, k outside
// [0, n], capacities <= 0, bad options) throws std::invalid_argument naming the stripe or
// field; data from which no curve can be estimated (no exceedance at all, every run exceeded,
// one intensity level, ...) give a FitStatus with a message, never NaN.
#pragma once

#include "config/schema.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace nsb::sweep {

// One intensity level of a multiple-stripe analysis.
struct Stripe {
  double im = 0.0;   // intensity measure of the stripe's runs [unit of the IM, e.g. g]; > 0
  int n = 0;         // runs at this level; > 0
  int exceeded = 0;  // runs whose response reached the limit state; in [0, n]
};

// Whether a fit has an estimate, and if not why not. theta and beta hold an estimate only for
// kFitted and kNotConverged (has_estimate); otherwise both are 0, the value "not fitted" (a
// fitted theta and beta are > 0), and a JSON writer prints null for them.
enum class FitStatus {
  kNotRun,         // nothing was fitted (a default FragilityFit).
  kFitted,         // the estimate: the likelihood's maximum to FitOptions::tolerance, or the
                   //   moments of ln c. Usable.
  kNotConverged,   // the simplex stopped at max_iterations before reaching the tolerance: the
                   //   best point found is reported. Usable with care.
  kNoData,         // no stripes (MLE) or no capacities (moments).
  kNoExceedances,  // no run exceeded the limit state: the likelihood grows without bound as
                   //   theta -> infinity, no maximum exists.
  kAllExceeded,    // every run exceeded: the likelihood grows as theta -> 0, no maximum.
  kOneIntensity,   // every stripe at one IM (or one capacity): theta and beta cannot both be
                   //   identified (a ridge of equal maxima; a sample deviation of one value).
  kSeparated,      // a step explains the data (beta -> 0): every run below some IM stayed
                   //   below the limit state and every run above it exceeded (or all
                   //   capacities are equal). The message gives the range of the step.
  kNotIncreasing,  // the exceedance fractions do not grow with IM as a whole (ln IM and the
                   //   outcomes are not positively correlated): the likelihood's supremum over
                   //   beta > 0 lies at beta -> infinity.
};
inline constexpr std::array<config::Name<FitStatus>, 9> kFitStatusNames{
    {{"not_run", FitStatus::kNotRun},
     {"fitted", FitStatus::kFitted},
     {"not_converged", FitStatus::kNotConverged},
     {"no_data", FitStatus::kNoData},
     {"no_exceedances", FitStatus::kNoExceedances},
     {"all_exceeded", FitStatus::kAllExceeded},
     {"one_intensity", FitStatus::kOneIntensity},
     {"separated", FitStatus::kSeparated},
     {"not_increasing", FitStatus::kNotIncreasing}}};
std::string_view to_string(FitStatus s);
// The status of a name of kFitStatusNames; std::nullopt for anything else.
std::optional<FitStatus> parse_fit_status(std::string_view name);
// True for kFitted and kNotConverged: theta and beta hold an estimate.
bool has_estimate(FitStatus s);

struct FitOptions {
  double tolerance = 1e-6;  // the simplex stops when its size in (ln theta, ln beta) is below
                            //   this: about the relative error of theta and beta; in (0, 0.1].
                            //   Below ~1e-8 the likelihood's round-off (relative 1e-16 of
                            //   |l|) hides the curvature and the simplex cannot shrink.
  int max_iterations = 2000;  // simplex iterations per fit; >= 1
  int resamples = 1000;       // bootstrap resamples for the 95 % bands; 0 = no bands; >= 0
  std::uint64_t seed = 5489;  // std::mt19937_64 seed of the bootstrap: same seed, same bands
  void validate() const;      // throws std::invalid_argument naming the field
};

// Lower and upper end of a 95 % band; {0, 0} when not computed.
using Band = std::array<double, 2>;

struct FragilityFit {
  double theta = 0.0;  // median capacity [unit of IM]; 0 = not fitted (see FitStatus)
  double beta = 0.0;   // dispersion of ln capacity [-]; 0 = not fitted
  Band ci95_theta{0.0, 0.0};  // 2.5 and 97.5 percentiles of theta over the bootstrap
  Band ci95_beta{0.0, 0.0};   //   resamples; {0, 0} when not computed (see bootstrap_ci)
  std::vector<Stripe> stripes;  // the data fitted, as given (empty for fit_moments)
  FitStatus status = FitStatus::kNotRun;
  std::string message;     // why there is no estimate, or what to know about the bands
  int iterations = 0;      // simplex iterations of the point fit (0 for fit_moments)
  double log_likelihood = 0.0;  // log_likelihood(stripes, theta, beta) at the estimate; 0
                                //   without an estimate and for fit_moments
};

struct BootstrapBands {
  Band theta{0.0, 0.0};  // 95 % band of theta; {0, 0} when not computed
  Band beta{0.0, 0.0};   // 95 % band of beta; {0, 0} when not computed
  int resamples = 0;     // data sets drawn
  int fitted = 0;        // of which had an estimate (has_estimate); only these make the bands
  bool computed = false;  // false when the data have no estimate or fewer than
                          //   kMinBootstrapFits resamples had one
  std::string message;   // why not computed, or how many resamples were left out
};
// The fewest fitted resamples from which 2.5 and 97.5 percentiles are taken: 40 = 1/0.025,
// the fewest for which one refit is expected beyond each percentile.
inline constexpr int kMinBootstrapFits = 40;

// The binomial log-likelihood of the stripes for a curve (theta, beta), without the constant
// sum_j ln C(n_j, k_j):
//   l = sum_j [ k_j ln Phi(z_j) + (n_j - k_j) ln Phi(-z_j) ],   z_j = ln(im_j / theta) / beta.
// Evaluated with ln Phi(z) = ln(erfc(-z / sqrt 2) / 2), from std::erfc and, where erfc
// underflows (-z / sqrt 2 > 26), from gsl_sf_log_erfc: finite for any finite z (no ln 0 in
// the tails). Requires theta > 0, beta > 0.
double log_likelihood(const std::vector<Stripe>& stripes, double theta, double beta);

// Throws std::invalid_argument naming the first bad stripe: "stripe 3 (im = -0.1): im: must be
// finite and > 0", likewise n > 0 and exceeded in [0, n].
void validate_stripes(const std::vector<Stripe>& stripes);

// Maximum likelihood fit of (theta, beta) to the stripes. When the data have an estimate and
// options.resamples > 0, ci95_theta and ci95_beta are bootstrap_ci's bands (the message then
// says how many resamples had no estimate, if any). Throws std::invalid_argument for bad
// stripes or options; every other outcome is a status.
FragilityFit fit_mle(const std::vector<Stripe>& stripes, const FitOptions& options = {});

// 95 % bands of theta and beta by the nonparametric bootstrap: each of options.resamples
// data sets draws every stripe's exceedances from Binomial(n_j, k_j / n_j) (the stripe's runs
// resampled with replacement), is refitted by maximum likelihood, and the bands are the 2.5
// and 97.5 percentiles over the resamples that have an estimate. Reproducible for a seed.
BootstrapBands bootstrap_ci(const std::vector<Stripe>& stripes, const FitOptions& options = {});

// Method of moments on IDA capacities c_i [unit of IM] (Baker 2015, eqs. 2-3):
//   theta = exp(mean ln c),   beta = sqrt( sum_i (ln c_i - ln theta)^2 / (N - 1) ),
// the sample standard deviation with N - 1. No bands. Throws std::invalid_argument naming the
// first capacity that is not finite and > 0.
FragilityFit fit_moments(const std::vector<double>& capacities);

}  // namespace nsb::sweep
