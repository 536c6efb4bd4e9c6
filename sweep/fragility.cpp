#include "sweep/fragility.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_multimin.h>
#include <gsl/gsl_sf_erf.h>
#include <gsl/gsl_statistics_double.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <stdexcept>

namespace nsb::sweep {

std::string_view to_string(FitStatus s) {
  return config::name_of(kFitStatusNames, s);
}

std::optional<FitStatus> parse_fit_status(std::string_view name) {
  return config::value_of(kFitStatusNames, name);
}

bool has_estimate(FitStatus s) { return s == FitStatus::kFitted || s == FitStatus::kNotConverged; }

void FitOptions::validate() const {
  if (!(tolerance > 0.0 && tolerance <= 0.1)) {
    throw std::invalid_argument("FitOptions.tolerance: must be in (0, 0.1] (got " +
                                config::format_value(tolerance) + ")");
  }
  if (max_iterations < 1) {
    throw std::invalid_argument("FitOptions.max_iterations: must be >= 1 (got " +
                                std::to_string(max_iterations) + ")");
  }
  if (resamples < 0) {
    throw std::invalid_argument("FitOptions.resamples: must be >= 0 (got " +
                                std::to_string(resamples) + ")");
  }
}

namespace {

std::string num(double x) { return config::format_value(x); }

[[noreturn]] void bad_stripe(std::size_t j, const Stripe& s, const std::string& what) {
  throw std::invalid_argument("stripe " + std::to_string(j) + " (im = " + num(s.im) +
                              ", n = " + std::to_string(s.n) + ", exceeded = " +
                              std::to_string(s.exceeded) + "): " + what);
}

// ln Phi(z) = ln(erfc(-z / sqrt 2) / 2). std::erfc keeps its relative accuracy until it
// underflows near 26.5 (erfc(26) = 5.7e-296); beyond, gsl_sf_log_erfc_e evaluates the
// logarithm directly (its asymptotic series), so the log-likelihood is finite for any finite
// z. The _e form reports through its return value instead of GSL's error handler.
double log_phi(double z) {
  constexpr double kErfcUnderflow = 26.0;
  const double x = -z / std::numbers::sqrt2;
  if (x < kErfcUnderflow) return std::log(0.5 * std::erfc(x));
  gsl_sf_result r;
  gsl_sf_log_erfc_e(x, &r);
  return r.val - std::numbers::ln2;
}

}  // namespace

void validate_stripes(const std::vector<Stripe>& stripes) {
  for (std::size_t j = 0; j < stripes.size(); ++j) {
    const Stripe& s = stripes[j];
    if (!std::isfinite(s.im) || !(s.im > 0.0)) bad_stripe(j, s, "im: must be finite and > 0");
    if (s.n <= 0) bad_stripe(j, s, "n: must be > 0");
    if (s.exceeded < 0 || s.exceeded > s.n) bad_stripe(j, s, "exceeded: must be in [0, n]");
  }
}

double log_likelihood(const std::vector<Stripe>& stripes, double theta, double beta) {
  double l = 0.0;
  for (const Stripe& s : stripes) {
    const double z = std::log(s.im / theta) / beta;
    // A term with zero count is 0 even where its logarithm is -inf (0 ln 0 = 0).
    if (s.exceeded > 0) l += s.exceeded * log_phi(z);
    if (s.n > s.exceeded) l += (s.n - s.exceeded) * log_phi(-z);
  }
  return l;
}

namespace {

struct NoEstimate {
  FitStatus status;
  std::string message;
};

// Whether the likelihood has a maximum with 0 < theta, beta < infinity, and if not why.
// In a = -ln(theta) / beta, b = 1 / beta the model is a probit regression on ln x, whose
// log-likelihood is concave in (a, b) (ln Phi is concave). Its maximum is finite iff the
// data are not (quasi-)separated (Albert & Anderson 1984, Biometrika 71(1):1-10): no IM c
// has only non-exceedances below it and only exceedances above it. Concavity also makes
// g(b) = max_a l(a, b) concave, with g'(0) proportional to sum_j (k_j - n_j p)(ln x_j - m)
// (p the overall fraction, m the mean ln x): the maximum has b > 0 iff that is > 0. (Data
// separated the other way, exceedances only below some IM, make that sum negative.)
std::optional<NoEstimate> why_no_estimate(const std::vector<Stripe>& stripes) {
  if (stripes.empty()) return NoEstimate{FitStatus::kNoData, "no stripes: nothing to fit"};
  long runs = 0, exceeded = 0;
  double first_exceeding = std::numeric_limits<double>::infinity();  // least im with k > 0
  double last_safe = -std::numeric_limits<double>::infinity();       // largest im with k < n
  double im_min = stripes[0].im, im_max = stripes[0].im, sum_ln = 0.0;
  for (const Stripe& s : stripes) {
    runs += s.n;
    exceeded += s.exceeded;
    if (s.exceeded > 0) first_exceeding = std::min(first_exceeding, s.im);
    if (s.exceeded < s.n) last_safe = std::max(last_safe, s.im);
    im_min = std::min(im_min, s.im);
    im_max = std::max(im_max, s.im);
    sum_ln += s.n * std::log(s.im);
  }
  const std::string counts = std::to_string(runs) + " runs in " +
                             std::to_string(stripes.size()) + " stripes";
  if (exceeded == 0) {
    return NoEstimate{FitStatus::kNoExceedances,
                      "no exceedance in " + counts +
                          ": the likelihood grows as theta -> infinity, no estimate"};
  }
  if (exceeded == runs) {
    return NoEstimate{FitStatus::kAllExceeded, "every one of " + counts +
                                                   " exceeded: the likelihood grows as "
                                                   "theta -> 0, no estimate"};
  }
  if (im_min == im_max) {
    return NoEstimate{FitStatus::kOneIntensity,
                      "every stripe is at im = " + num(im_min) +
                          ": any (theta, beta) with Phi(ln(im/theta)/beta) = " +
                          std::to_string(exceeded) + "/" + std::to_string(runs) +
                          " fits equally, theta and beta are not identifiable"};
  }
  if (last_safe <= first_exceeding) {
    return NoEstimate{FitStatus::kSeparated,
                      "no exceedance below im = " + num(first_exceeding) +
                          " and only exceedances above im = " + num(last_safe) +
                          ": a step (beta -> 0) at any theta in [" + num(last_safe) + ", " +
                          num(first_exceeding) + "] fits best, no estimate"};
  }
  const double p = static_cast<double>(exceeded) / static_cast<double>(runs);
  const double mean_ln = sum_ln / static_cast<double>(runs);
  double score = 0.0, scale = 0.0;
  for (const Stripe& s : stripes) {
    const double d = std::log(s.im) - mean_ln;
    score += (s.exceeded - s.n * p) * d;
    scale += s.n * std::abs(d);
  }
  // Relative round-off bound of the sum: fractions that are flat in ln IM give score = 0.
  constexpr double kRoundOff = 1e-12;
  if (score <= kRoundOff * scale) {
    return NoEstimate{FitStatus::kNotIncreasing,
                      "the exceedance fractions do not increase with im (" + counts +
                          "): the likelihood is largest as beta -> infinity, no estimate"};
  }
  return std::nullopt;
}

struct Problem {
  const std::vector<Stripe>* stripes;
  double ln_theta_min, ln_theta_max;  // bounds far beyond any estimate, so that the objective
                                      // stays finite wherever the simplex wanders
};

// Bounds of the box: theta within e^50 of the IMs, beta in [e^-50, e^50]. The MLE exists
// (why_no_estimate), so it lies well inside; outside, the objective is a finite wall.
constexpr double kLnBox = 50.0;

// -l(theta, beta) at x = (ln theta, ln beta), the function the simplex minimizes.
double negative_log_likelihood(const gsl_vector* x, void* params) {
  const auto* p = static_cast<const Problem*>(params);
  const double ln_theta = gsl_vector_get(x, 0), ln_beta = gsl_vector_get(x, 1);
  const bool inside = ln_theta >= p->ln_theta_min && ln_theta <= p->ln_theta_max &&
                      std::abs(ln_beta) <= kLnBox;
  if (!inside) return std::numeric_limits<double>::max();
  return -log_likelihood(*p->stripes, std::exp(ln_theta), std::exp(ln_beta));
}

struct Estimate {
  double theta = 0.0, beta = 0.0;
  int iterations = 0;
  bool converged = false;
};

// Nelder-Mead simplex (GSL nmsimplex2) on (ln theta, ln beta). Why this optimizer: the
// parameters are two, the log form keeps theta, beta > 0 without constraints and makes the
// tolerance relative, the likelihood is smooth with one maximum once why_no_estimate has
// passed (a smooth reparametrization of a concave function), and no derivative is needed. A
// fit to 1e-6 costs about 50 iterations (~100 likelihood evaluations, ~50 us for 10 stripes),
// cheap enough for a bootstrap of 1000 refits.
// The cold start: theta0 = sqrt(x_first_exceeding * x_last_safe), the middle of the IMs where
// exceedance and non-exceedance overlap, and beta0 = half the ln-width of that overlap, with
// simplex edges of 0.5 (a factor e^0.5 = 1.6 either way). A bootstrap refit starts warm from
// the estimate of the data it resamples, with edges of 0.1 (a few standard errors).
struct Start {
  double ln_theta, ln_beta, step;
};
Estimate maximize(const std::vector<Stripe>& stripes, const FitOptions& options,
                  std::optional<Start> warm) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  double im_min = lo, im_max = hi;
  for (const Stripe& s : stripes) {
    if (s.exceeded > 0) lo = std::min(lo, s.im);
    if (s.exceeded < s.n) hi = std::max(hi, s.im);
    im_min = std::min(im_min, s.im);
    im_max = std::max(im_max, s.im);
  }
  Problem problem{&stripes, std::log(im_min) - kLnBox, std::log(im_max) + kLnBox};
  gsl_multimin_function f{&negative_log_likelihood, 2, &problem};

  using Vector = std::unique_ptr<gsl_vector, decltype(&gsl_vector_free)>;
  Vector x(gsl_vector_alloc(2), &gsl_vector_free), step(gsl_vector_alloc(2), &gsl_vector_free);
  const Start start = warm ? *warm
                           : Start{0.5 * (std::log(lo) + std::log(hi)),
                                   std::log(0.5 * std::log(hi / lo)), 0.5};
  gsl_vector_set(x.get(), 0, start.ln_theta);
  gsl_vector_set(x.get(), 1, start.ln_beta);
  gsl_vector_set_all(step.get(), start.step);
  std::unique_ptr<gsl_multimin_fminimizer, decltype(&gsl_multimin_fminimizer_free)> s(
      gsl_multimin_fminimizer_alloc(gsl_multimin_fminimizer_nmsimplex2, 2),
      &gsl_multimin_fminimizer_free);
  gsl_multimin_fminimizer_set(s.get(), &f, x.get(), step.get());

  Estimate e;
  while (e.iterations < options.max_iterations) {
    ++e.iterations;
    if (gsl_multimin_fminimizer_iterate(s.get()) != GSL_SUCCESS) break;
    if (gsl_multimin_test_size(gsl_multimin_fminimizer_size(s.get()), options.tolerance) ==
        GSL_SUCCESS) {
      e.converged = true;
      break;
    }
  }
  const gsl_vector* best = gsl_multimin_fminimizer_x(s.get());
  e.theta = std::exp(gsl_vector_get(best, 0));
  e.beta = std::exp(gsl_vector_get(best, 1));
  return e;
}

// The maximum likelihood point estimate of valid stripes, without bands.
FragilityFit fit_point(const std::vector<Stripe>& stripes, const FitOptions& options,
                       std::optional<Start> warm = std::nullopt) {
  FragilityFit fit;
  if (const auto no = why_no_estimate(stripes)) {
    fit.status = no->status;
    fit.message = no->message;
    return fit;
  }
  const Estimate e = maximize(stripes, options, warm);
  fit.theta = e.theta;
  fit.beta = e.beta;
  fit.iterations = e.iterations;
  fit.log_likelihood = log_likelihood(stripes, e.theta, e.beta);
  fit.status = e.converged ? FitStatus::kFitted : FitStatus::kNotConverged;
  if (!e.converged) {
    fit.message = "the simplex did not reach the tolerance " + num(options.tolerance) + " in " +
                  std::to_string(e.iterations) + " iterations: best point reported";
  }
  return fit;
}

// The number of successes in n Bernoulli(p) trials, each a uniform double in [0, 1) made from
// the top 53 bits of one mt19937_64 output. The engine's sequence is fixed by the C++
// standard, and so is this draw: the bands are the same with every standard library (the
// std:: distributions are implementation-defined).
int draw_binomial(std::mt19937_64& rng, int n, double p) {
  constexpr double kTwoToMinus53 = 0x1.0p-53;
  int k = 0;
  for (int i = 0; i < n; ++i) {
    if (static_cast<double>(rng() >> 11) * kTwoToMinus53 < p) ++k;
  }
  return k;
}

// The 2.5 and 97.5 percentiles, interpolated between order statistics at (N - 1) q
// (gsl_stats_quantile_from_sorted_data).
Band percentiles_95(std::vector<double>& values) {
  std::sort(values.begin(), values.end());
  return {gsl_stats_quantile_from_sorted_data(values.data(), 1, values.size(), 0.025),
          gsl_stats_quantile_from_sorted_data(values.data(), 1, values.size(), 0.975)};
}

// The bands around the estimate `fit` of the stripes (has_estimate(fit.status)).
BootstrapBands bands_of(const std::vector<Stripe>& stripes, const FragilityFit& fit,
                        const FitOptions& options) {
  BootstrapBands bands;
  const Start warm{std::log(fit.theta), std::log(fit.beta), 0.1};
  std::mt19937_64 rng(options.seed);
  std::vector<Stripe> resample = stripes;
  std::vector<double> thetas, betas;
  thetas.reserve(static_cast<std::size_t>(options.resamples));
  betas.reserve(static_cast<std::size_t>(options.resamples));
  for (int r = 0; r < options.resamples; ++r) {
    for (std::size_t j = 0; j < stripes.size(); ++j) {
      const double fraction = static_cast<double>(stripes[j].exceeded) / stripes[j].n;
      resample[j].exceeded = draw_binomial(rng, stripes[j].n, fraction);
    }
    const FragilityFit refit = fit_point(resample, options, warm);
    if (!has_estimate(refit.status)) continue;
    thetas.push_back(refit.theta);
    betas.push_back(refit.beta);
  }
  bands.resamples = options.resamples;
  bands.fitted = static_cast<int>(thetas.size());
  const int left_out = bands.resamples - bands.fitted;
  if (bands.fitted < kMinBootstrapFits) {
    bands.message = "no bands: " + std::to_string(bands.fitted) + " of " +
                    std::to_string(bands.resamples) + " bootstrap resamples had an estimate, " +
                    "fewer than " + std::to_string(kMinBootstrapFits);
    return bands;
  }
  bands.theta = percentiles_95(thetas);
  bands.beta = percentiles_95(betas);
  bands.computed = true;
  if (left_out > 0) {
    bands.message = std::to_string(left_out) + " of " + std::to_string(bands.resamples) +
                    " bootstrap resamples had no estimate (no exceedance, separated, ...) and "
                    "are left out of the bands";
  }
  return bands;
}

}  // namespace

FragilityFit fit_mle(const std::vector<Stripe>& stripes, const FitOptions& options) {
  options.validate();
  validate_stripes(stripes);
  FragilityFit fit = fit_point(stripes, options);
  fit.stripes = stripes;
  if (!has_estimate(fit.status) || options.resamples == 0) return fit;
  const BootstrapBands bands = bands_of(stripes, fit, options);
  if (bands.computed) {
    fit.ci95_theta = bands.theta;
    fit.ci95_beta = bands.beta;
  }
  if (!bands.message.empty()) fit.message += (fit.message.empty() ? "" : "; ") + bands.message;
  return fit;
}

BootstrapBands bootstrap_ci(const std::vector<Stripe>& stripes, const FitOptions& options) {
  options.validate();
  validate_stripes(stripes);
  const FragilityFit fit = fit_point(stripes, options);
  if (!has_estimate(fit.status)) {
    BootstrapBands none;
    none.message = "no bands: the data have no estimate (" + std::string(to_string(fit.status)) +
                   ")";
    return none;
  }
  return bands_of(stripes, fit, options);
}

FragilityFit fit_moments(const std::vector<double>& capacities) {
  for (std::size_t i = 0; i < capacities.size(); ++i) {
    if (!std::isfinite(capacities[i]) || !(capacities[i] > 0.0)) {
      throw std::invalid_argument("capacity " + std::to_string(i) + " (" + num(capacities[i]) +
                                  "): must be finite and > 0");
    }
  }
  FragilityFit fit;
  if (capacities.empty()) {
    fit.status = FitStatus::kNoData;
    fit.message = "no capacities: nothing to fit";
    return fit;
  }
  if (capacities.size() == 1) {
    fit.status = FitStatus::kOneIntensity;
    fit.message = "one capacity (" + num(capacities[0]) +
                  "): the standard deviation of ln c needs at least two";
    return fit;
  }
  if (std::all_of(capacities.begin(), capacities.end(),
                  [&](double c) { return c == capacities[0]; })) {
    fit.status = FitStatus::kSeparated;
    fit.message = "all " + std::to_string(capacities.size()) + " capacities equal " +
                  num(capacities[0]) + ": a step there (beta = 0), no lognormal estimate";
    return fit;
  }
  std::vector<double> ln_c(capacities.size());
  std::transform(capacities.begin(), capacities.end(), ln_c.begin(),
                 [](double c) { return std::log(c); });
  // Baker 2015 eqs. 2-3; gsl_stats_sd divides by N - 1 (the sample standard deviation).
  const double mean = gsl_stats_mean(ln_c.data(), 1, ln_c.size());
  fit.theta = std::exp(mean);
  fit.beta = gsl_stats_sd_m(ln_c.data(), 1, ln_c.size(), mean);
  fit.status = FitStatus::kFitted;
  return fit;
}

}  // namespace nsb::sweep
