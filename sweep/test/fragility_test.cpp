// Tests of the lognormal fragility fits against values computed outside the code under test:
// synthetic stripes from a known curve (recovery within the Fisher-information error, and the
// coverage of the bootstrap bands), the log-likelihood evaluated directly on a grid, the
// method of moments by hand, and every case without an estimate.
#include "sweep/fragility.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using nsb::sweep::FitOptions;
using nsb::sweep::FitStatus;
using nsb::sweep::FragilityFit;
using nsb::sweep::Stripe;

// The test's own normal CDF and log-likelihood (std::erfc, not the library's log_erfc path),
// so that a wrong term in the library's likelihood shows as a disagreement.
double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }
double normal_pdf(double z) { return std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi); }

double direct_log_likelihood(const std::vector<Stripe>& stripes, double theta, double beta) {
  double l = 0.0;
  for (const Stripe& s : stripes) {
    const double p = normal_cdf(std::log(s.im / theta) / beta);
    if (s.exceeded > 0) l += s.exceeded * std::log(p);
    if (s.exceeded < s.n) l += (s.n - s.exceeded) * std::log(1.0 - p);
  }
  return l;
}

// The synthetic design of test (a): 10 stripes at 0.1, 0.2, ..., 1.0 g, 40 runs each, drawn
// from the curve theta = 0.5 g, beta = 0.4.
constexpr double kTheta = 0.5;
constexpr double kBeta = 0.4;
constexpr int kRuns = 40;
std::vector<double> design_ims() {
  std::vector<double> ims;
  for (int j = 1; j <= 10; ++j) ims.push_back(0.1 * j);
  return ims;
}

std::vector<Stripe> draw_stripes(std::mt19937_64& rng, const std::vector<double>& ims) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Stripe> stripes;
  for (double im : ims) {
    const double p = normal_cdf(std::log(im / kTheta) / kBeta);
    int k = 0;
    for (int i = 0; i < kRuns; ++i) k += u(rng) < p ? 1 : 0;
    stripes.push_back({im, kRuns, k});
  }
  return stripes;
}

// Asymptotic standard errors of ln theta and ln beta for the design at the true curve: the
// inverse of the expected Fisher information. For a stripe, with z = (ln x - ln theta)/beta,
// P = Phi(z), the binomial information about P is n / (P (1 - P)), and
// dP/d(ln theta, ln beta) = phi(z) (-1/beta, -z); so
//   I = sum_j n_j phi(z_j)^2 / (P_j (1 - P_j)) [1/beta^2, z_j/beta; z_j/beta, z_j^2].
struct StandardErrors {
  double ln_theta, ln_beta;
};
StandardErrors fisher_standard_errors(const std::vector<double>& ims) {
  double a = 0.0, b = 0.0, c = 0.0;  // I = [a b; b c]
  for (double im : ims) {
    const double z = std::log(im / kTheta) / kBeta;
    const double p = normal_cdf(z);
    const double w = kRuns * normal_pdf(z) * normal_pdf(z) / (p * (1.0 - p));
    a += w / (kBeta * kBeta);
    b += w * z / kBeta;
    c += w * z * z;
  }
  const double det = a * c - b * b;
  return {std::sqrt(c / det), std::sqrt(a / det)};
}

FitOptions no_bands() {
  FitOptions o;
  o.resamples = 0;
  return o;
}

bool finite_fields(const FragilityFit& f) {
  return std::isfinite(f.theta) && std::isfinite(f.beta) && std::isfinite(f.ci95_theta[0]) &&
         std::isfinite(f.ci95_theta[1]) && std::isfinite(f.ci95_beta[0]) &&
         std::isfinite(f.ci95_beta[1]) && std::isfinite(f.log_likelihood);
}

}  // namespace

// (a) One data set: the estimate lies within 3 standard errors of the true curve (a random
// data set fails this with probability 0.27 % per parameter), and the bands enclose the
// estimate.
TEST_CASE("synthetic stripes: theta and beta recovered within the Fisher-information error") {
  const auto ims = design_ims();
  const StandardErrors se = fisher_standard_errors(ims);
  std::mt19937_64 rng(20150101);
  const auto stripes = draw_stripes(rng, ims);
  const FragilityFit fit = nsb::sweep::fit_mle(stripes);
  REQUIRE(fit.status == FitStatus::kFitted);
  MESSAGE("Fisher standard errors: ln theta " << se.ln_theta << ", ln beta " << se.ln_beta
                                              << "; fit: theta " << fit.theta << " ["
                                              << fit.ci95_theta[0] << ", " << fit.ci95_theta[1]
                                              << "], beta " << fit.beta << " ["
                                              << fit.ci95_beta[0] << ", " << fit.ci95_beta[1]
                                              << "]");
  CHECK(std::abs(std::log(fit.theta / kTheta)) < 3.0 * se.ln_theta);
  CHECK(std::abs(std::log(fit.beta / kBeta)) < 3.0 * se.ln_beta);
  CHECK(fit.ci95_theta[0] < fit.theta);
  CHECK(fit.theta < fit.ci95_theta[1]);
  CHECK(fit.ci95_beta[0] < fit.beta);
  CHECK(fit.beta < fit.ci95_beta[1]);
  CHECK(fit.message.empty());
  CHECK(fit.stripes.size() == stripes.size());
  CHECK(fit.log_likelihood == doctest::Approx(direct_log_likelihood(stripes, fit.theta, fit.beta))
                                  .epsilon(1e-12));
}

// (a) 200 data sets from the same curve. Bounds, each at 3 standard deviations of what is
// measured:
// - the mean error of ln theta and ln beta is within 3 SE / sqrt(200) of 0 (this also bounds
//   the MLE's O(1/N) bias);
// - the spread of the estimates matches the Fisher standard error: a standard deviation from
//   200 samples has relative standard error 1/sqrt(2 * 199) = 5 %, so the ratio lies in
//   [0.85, 1.15];
// - the 95 % bands (bootstrap, 1000 resamples each, and the Wald interval +-1.96 SE) cover
//   the truth in a fraction within 3 binomial standard deviations of 0.95:
//   0.95 +- 3 sqrt(0.95 * 0.05 / 200) = [0.904, 0.996].
TEST_CASE("200 synthetic data sets: spread, bias and coverage of the 95 % bands") {
  const auto ims = design_ims();
  const StandardErrors se = fisher_standard_errors(ims);
  constexpr int kSets = 200;
  FitOptions options;
  std::mt19937_64 rng(7);
  double sum_t = 0.0, sum_b = 0.0, sq_t = 0.0, sq_b = 0.0;
  int boot_t = 0, boot_b = 0, wald_t = 0, wald_b = 0;
  for (int d = 0; d < kSets; ++d) {
    options.seed = 1000 + static_cast<std::uint64_t>(d);
    const FragilityFit fit = nsb::sweep::fit_mle(draw_stripes(rng, ims), options);
    REQUIRE(fit.status == FitStatus::kFitted);
    const double et = std::log(fit.theta / kTheta), eb = std::log(fit.beta / kBeta);
    sum_t += et;
    sum_b += eb;
    sq_t += et * et;
    sq_b += eb * eb;
    boot_t += fit.ci95_theta[0] <= kTheta && kTheta <= fit.ci95_theta[1] ? 1 : 0;
    boot_b += fit.ci95_beta[0] <= kBeta && kBeta <= fit.ci95_beta[1] ? 1 : 0;
    wald_t += std::abs(et) <= 1.96 * se.ln_theta ? 1 : 0;
    wald_b += std::abs(eb) <= 1.96 * se.ln_beta ? 1 : 0;
  }
  const double mean_t = sum_t / kSets, mean_b = sum_b / kSets;
  const double sd_t = std::sqrt((sq_t - kSets * mean_t * mean_t) / (kSets - 1));
  const double sd_b = std::sqrt((sq_b - kSets * mean_b * mean_b) / (kSets - 1));
  MESSAGE("mean error: ln theta " << mean_t << ", ln beta " << mean_b << "; spread / Fisher SE: "
                                  << sd_t / se.ln_theta << ", " << sd_b / se.ln_beta
                                  << "; coverage: bootstrap " << boot_t << ", " << boot_b
                                  << ", Wald " << wald_t << ", " << wald_b << " of " << kSets);
  CHECK(std::abs(mean_t) < 3.0 * se.ln_theta / std::sqrt(kSets));
  CHECK(std::abs(mean_b) < 3.0 * se.ln_beta / std::sqrt(kSets));
  const double spread_margin = 3.0 / std::sqrt(2.0 * (kSets - 1));
  CHECK(std::abs(sd_t / se.ln_theta - 1.0) < spread_margin);
  CHECK(std::abs(sd_b / se.ln_beta - 1.0) < spread_margin);
  const double coverage_margin = 3.0 * std::sqrt(0.95 * 0.05 / kSets);
  for (int covered : {boot_t, boot_b, wald_t, wald_b}) {
    CHECK(std::abs(static_cast<double>(covered) / kSets - 0.95) < coverage_margin);
  }
}

// (b) The optimum against the log-likelihood evaluated directly (the test's own formula) on a
// grid of 801 x 801 points, uniform in ln theta over [0.3, 0.8] g and in ln beta over
// [0.15, 1.0]: no grid point beats the optimum by more than round-off, and the best grid point
// lies within one cell of it.
namespace {
void check_against_grid(const std::vector<Stripe>& stripes) {
  const FragilityFit fit = nsb::sweep::fit_mle(stripes, no_bands());
  REQUIRE(fit.status == FitStatus::kFitted);
  constexpr int kCells = 800;
  const double t0 = std::log(0.3), t1 = std::log(0.8), b0 = std::log(0.15), b1 = std::log(1.0);
  const double ht = (t1 - t0) / kCells, hb = (b1 - b0) / kCells;
  double best = -std::numeric_limits<double>::infinity(), best_t = 0.0, best_b = 0.0;
  for (int i = 0; i <= kCells; ++i) {
    for (int j = 0; j <= kCells; ++j) {
      const double lt = t0 + i * ht, lb = b0 + j * hb;
      const double l = direct_log_likelihood(stripes, std::exp(lt), std::exp(lb));
      if (l > best) {
        best = l;
        best_t = lt;
        best_b = lb;
      }
    }
  }
  const double at_optimum = direct_log_likelihood(stripes, fit.theta, fit.beta);
  // Round-off of a sum of ~10 terms of size |l|; a grid cell away from the optimum costs
  // ~1e-4 here, so a misplaced optimum cannot hide below this.
  const double round_off = 1e-12 * std::abs(at_optimum);
  MESSAGE("optimum theta " << fit.theta << " beta " << fit.beta << " l " << at_optimum
                           << "; grid best theta " << std::exp(best_t) << " beta "
                           << std::exp(best_b) << " l " << best);
  CHECK(best <= at_optimum + round_off);
  CHECK(std::abs(best_t - std::log(fit.theta)) <= ht);
  CHECK(std::abs(best_b - std::log(fit.beta)) <= hb);
  // The library's likelihood is the same function as the direct one.
  for (double theta : {0.35, 0.5, 0.7}) {
    for (double beta : {0.2, 0.4, 0.9}) {
      CHECK(nsb::sweep::log_likelihood(stripes, theta, beta) ==
            doctest::Approx(direct_log_likelihood(stripes, theta, beta)).epsilon(1e-12));
    }
  }
}
}  // namespace

TEST_CASE("the optimum is the maximum of the log-likelihood on a fine grid") {
  SUBCASE("synthetic stripes") {
    std::mt19937_64 rng(20150101);
    check_against_grid(draw_stripes(rng, design_ims()));
  }
  SUBCASE("non-monotone fractions are fitted like any others") {
    check_against_grid({{0.2, 10, 1}, {0.3, 10, 5}, {0.4, 10, 3}, {0.5, 10, 6}, {0.7, 10, 9}});
  }
  SUBCASE("unequal runs per stripe, stripes in any order, two at one IM") {
    check_against_grid({{0.6, 25, 17}, {0.25, 8, 1}, {0.45, 40, 18}, {0.45, 12, 7}, {0.9, 5, 5}});
  }
}

// (c) Method of moments by hand.
// Constants: round-off of a few logarithms and an exponential.
constexpr double kMomentsRoundOff = 1e-14;

TEST_CASE("method of moments on five IDA capacities, computed by hand") {
  SUBCASE("symmetric in ln c") {
    // c_i = 0.5 exp(0.4 d_i), d = -2, -1, 0, 1, 2: ln c_i = ln 0.5 + 0.4 d_i.
    // mean ln c = ln 0.5 (sum d = 0), so theta = 0.5.
    // sum (ln c_i - ln theta)^2 = 0.16 (4 + 1 + 0 + 1 + 4) = 1.6; / (5 - 1) = 0.4;
    // beta = sqrt(0.4) = 0.632455532 (dividing by 5 would give sqrt(0.32) = 0.565685425).
    const std::vector<double> c{0.5 * std::exp(-0.8), 0.5 * std::exp(-0.4), 0.5,
                                0.5 * std::exp(0.4), 0.5 * std::exp(0.8)};
    const FragilityFit fit = nsb::sweep::fit_moments(c);
    REQUIRE(fit.status == FitStatus::kFitted);
    CHECK(fit.theta == doctest::Approx(0.5).epsilon(kMomentsRoundOff));
    CHECK(fit.beta == doctest::Approx(0.632455532033676).epsilon(kMomentsRoundOff));
  }
  SUBCASE("skewed in ln c, in any order") {
    // c = 0.8 exp(0.3 d), d = 1, -2, 0, 1, 0: sum d = 0, so theta = 0.8;
    // sum (0.3 d)^2 = 0.09 (1 + 4 + 0 + 1 + 0) = 0.54; / 4 = 0.135; beta = sqrt(0.135)
    // = 0.367423461.
    const std::vector<double> c{0.8 * std::exp(0.3), 0.8 * std::exp(-0.6), 0.8,
                                0.8 * std::exp(0.3), 0.8};
    const FragilityFit fit = nsb::sweep::fit_moments(c);
    REQUIRE(fit.status == FitStatus::kFitted);
    CHECK(fit.theta == doctest::Approx(0.8).epsilon(kMomentsRoundOff));
    CHECK(fit.beta == doctest::Approx(0.367423461417477).epsilon(kMomentsRoundOff));
    CHECK(fit.stripes.empty());
    CHECK(fit.message.empty());
  }
}

// (d) Every case without an estimate: a status, theta and beta "not fitted" (0), no NaN, and
// a message that says why.
namespace {
void check_no_estimate(const FragilityFit& fit, FitStatus expected, const std::string& says) {
  CHECK(fit.status == expected);
  CHECK_FALSE(nsb::sweep::has_estimate(fit.status));
  CHECK(fit.theta == 0.0);
  CHECK(fit.beta == 0.0);
  CHECK(fit.ci95_theta == nsb::sweep::Band{0.0, 0.0});
  CHECK(fit.ci95_beta == nsb::sweep::Band{0.0, 0.0});
  CHECK(finite_fields(fit));
  CHECK_MESSAGE(fit.message.find(says) != std::string::npos, fit.message);
}
}  // namespace

TEST_CASE("data without a maximum-likelihood estimate give a status, never NaN") {
  using nsb::sweep::fit_mle;
  check_no_estimate(fit_mle({}), FitStatus::kNoData, "no stripes");
  check_no_estimate(fit_mle({{0.2, 10, 0}, {0.5, 10, 0}, {0.9, 10, 0}}), FitStatus::kNoExceedances,
                    "no exceedance in 30 runs in 3 stripes");
  check_no_estimate(fit_mle({{0.2, 10, 10}, {0.5, 10, 10}}), FitStatus::kAllExceeded,
                    "every one of 20 runs");
  check_no_estimate(fit_mle({{0.4, 20, 7}}), FitStatus::kOneIntensity, "im = 0.4");
  check_no_estimate(fit_mle({{0.4, 20, 7}, {0.4, 10, 0}}), FitStatus::kOneIntensity,
                    "7/30");
  // Complete separation: nothing below 0.4 exceeds, everything from 0.4 up does.
  check_no_estimate(fit_mle({{0.2, 10, 0}, {0.3, 10, 0}, {0.4, 10, 10}, {0.8, 10, 10}}),
                    FitStatus::kSeparated, "theta in [0.3, 0.4]");
  // Quasi-complete separation: the stripe at the step is mixed, the others pure.
  check_no_estimate(fit_mle({{0.2, 10, 0}, {0.4, 10, 5}}), FitStatus::kSeparated,
                    "theta in [0.4, 0.4]");
  check_no_estimate(fit_mle({{0.2, 10, 9}, {0.4, 10, 5}, {0.6, 10, 1}}),
                    FitStatus::kNotIncreasing, "do not increase");
  check_no_estimate(fit_mle({{0.2, 10, 5}, {0.4, 10, 5}, {0.8, 10, 5}}),
                    FitStatus::kNotIncreasing, "do not increase");
}

TEST_CASE("moments without an estimate give a status, never NaN") {
  using nsb::sweep::fit_moments;
  check_no_estimate(fit_moments({}), FitStatus::kNoData, "no capacities");
  check_no_estimate(fit_moments({0.7}), FitStatus::kOneIntensity, "one capacity");
  check_no_estimate(fit_moments({0.7, 0.7, 0.7}), FitStatus::kSeparated, "all 3 capacities");
}

namespace {
// The message of the std::invalid_argument that f throws ("" when none).
template <class F>
std::string thrown(F f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("bad stripes, capacities and options throw, naming what is wrong") {
  using nsb::sweep::fit_mle;
  const std::vector<Stripe> good{{0.2, 10, 1}, {0.4, 10, 6}};
  const auto bad = [&](Stripe s) {
    auto stripes = good;
    stripes.push_back(s);
    return thrown([&] { fit_mle(stripes, no_bands()); });
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double im : {0.0, -0.1, nan, inf}) {
    const std::string what = bad({im, 10, 1});
    CHECK_MESSAGE(what.find("stripe 2 (im = ") == 0, what);
    CHECK_MESSAGE(what.find("im: must be finite and > 0") != std::string::npos, what);
  }
  for (int n : {0, -3}) CHECK(bad({0.5, n, 0}).find("n: must be > 0") != std::string::npos);
  for (int k : {-1, 11}) {
    CHECK(bad({0.5, 10, k}).find("exceeded: must be in [0, n]") != std::string::npos);
  }
  CHECK(thrown([&] { nsb::sweep::bootstrap_ci({{-1.0, 10, 1}}); }).find("stripe 0") == 0);
  for (double c : {0.0, -1.0, nan, inf}) {
    const std::string what = thrown([&] { nsb::sweep::fit_moments({0.3, c}); });
    CHECK_MESSAGE(what.find("capacity 1 (") == 0, what);
  }
  FitOptions o;
  o.tolerance = 0.0;
  CHECK(thrown([&] { fit_mle(good, o); }).find("FitOptions.tolerance") == 0);
  o = {};
  o.tolerance = nan;
  CHECK(thrown([&] { fit_mle(good, o); }).find("FitOptions.tolerance") == 0);
  o = {};
  o.max_iterations = 0;
  CHECK(thrown([&] { fit_mle(good, o); }).find("FitOptions.max_iterations") == 0);
  o = {};
  o.resamples = -1;
  CHECK(thrown([&] { nsb::sweep::bootstrap_ci(good, o); }).find("FitOptions.resamples") == 0);
}

TEST_CASE("a simplex stopped by max_iterations reports its best point as kNotConverged") {
  FitOptions o = no_bands();
  o.max_iterations = 1;
  const FragilityFit fit = nsb::sweep::fit_mle({{0.2, 10, 1}, {0.4, 10, 6}, {0.7, 10, 9}}, o);
  CHECK(fit.status == FitStatus::kNotConverged);
  CHECK(nsb::sweep::has_estimate(fit.status));
  CHECK(fit.theta > 0.0);
  CHECK(fit.beta > 0.0);
  CHECK(finite_fields(fit));
  CHECK(fit.iterations == 1);
  CHECK(fit.message.find("did not reach the tolerance") != std::string::npos);
}

TEST_CASE("bootstrap bands: reproducible for a seed, and resamples without an estimate") {
  std::mt19937_64 rng(20150101);
  const auto stripes = draw_stripes(rng, design_ims());
  FitOptions o;
  o.resamples = 200;
  const auto a = nsb::sweep::bootstrap_ci(stripes, o);
  const auto b = nsb::sweep::bootstrap_ci(stripes, o);
  REQUIRE(a.computed);
  CHECK(a.theta == b.theta);
  CHECK(a.beta == b.beta);
  CHECK(a.resamples == 200);
  CHECK(a.fitted == 200);
  CHECK(a.message.empty());
  const FragilityFit fit = nsb::sweep::fit_mle(stripes, o);
  CHECK(fit.ci95_theta == a.theta);
  CHECK(fit.ci95_beta == a.beta);
  o.seed += 1;
  CHECK(nsb::sweep::bootstrap_ci(stripes, o).theta != a.theta);
  o.resamples = 0;
  const FragilityFit bare = nsb::sweep::fit_mle(stripes, o);
  CHECK(bare.ci95_theta == nsb::sweep::Band{0.0, 0.0});
  CHECK(bare.theta == fit.theta);

  // One exceedance in 10 at 0.4 g: a resample draws none there with probability 0.9^10 = 35 %
  // and is then separated; those resamples are left out and counted.
  const std::vector<Stripe> thin{{0.2, 10, 0}, {0.4, 10, 1}, {0.5, 10, 2}, {0.6, 10, 10}};
  o.resamples = 400;
  const auto some = nsb::sweep::bootstrap_ci(thin, o);
  CHECK(some.computed);
  CHECK(some.fitted < some.resamples);
  CHECK(some.fitted >= nsb::sweep::kMinBootstrapFits);
  CHECK(some.message.find("left out") != std::string::npos);
  CHECK(std::isfinite(some.theta[0]));
  CHECK(some.theta[0] < some.theta[1]);
  o.resamples = 50;
  const auto few = nsb::sweep::bootstrap_ci(thin, o);
  CHECK(few.computed == (few.fitted >= nsb::sweep::kMinBootstrapFits));
  if (!few.computed) {
    CHECK(few.theta == nsb::sweep::Band{0.0, 0.0});
    CHECK(few.message.find("no bands") == 0);
  }
  const auto none = nsb::sweep::bootstrap_ci({{0.2, 10, 0}, {0.4, 10, 0}});
  CHECK_FALSE(none.computed);
  CHECK(none.message.find("no_exceedances") != std::string::npos);
}

TEST_CASE("status names: one list, each name parses back to its status") {
  for (const auto& n : nsb::sweep::kFitStatusNames) {
    CHECK(nsb::sweep::to_string(n.value) == n.name);
    CHECK(nsb::sweep::parse_fit_status(n.name) == n.value);
  }
  CHECK_FALSE(nsb::sweep::parse_fit_status("converged").has_value());
}

// ln Phi(z) far in the lower tail, where erfc underflows, against the asymptotic series of
// the Mills ratio (Abramowitz & Stegun 26.2.12):
//   ln Phi(z) = -z^2/2 - ln(|z| sqrt(2 pi)) + ln(1 - 1/z^2 + 3/z^4 - 15/z^6 + 105/z^8),
// whose truncation error is below 945/z^10 (< 1e-12 relative for |z| >= 20). A stripe with
// k = n at im = theta e^(beta z) contributes n ln Phi(z); one with k = 0 at im = theta e^(-beta
// z) contributes n ln Phi(z) as well.
TEST_CASE("the log-likelihood stays finite and accurate far in the tails") {
  for (double z : {-20.0, -36.7, -36.8, -50.0, -1000.0}) {
    const double z2 = z * z;
    const double series = 1.0 - 1.0 / z2 + 3.0 / (z2 * z2) - 15.0 / (z2 * z2 * z2) +
                          105.0 / (z2 * z2 * z2 * z2);
    const double expected =
        -0.5 * z2 - std::log(-z * std::sqrt(2.0 * std::numbers::pi)) + std::log(series);
    const double theta = 0.5, beta = 0.3;
    const std::vector<Stripe> low{{theta * std::exp(beta * z), 3, 3}};
    const std::vector<Stripe> high{{theta * std::exp(-beta * z), 3, 0}};
    CHECK(nsb::sweep::log_likelihood(low, theta, beta) ==
          doctest::Approx(3.0 * expected).epsilon(1e-12));
    CHECK(nsb::sweep::log_likelihood(high, theta, beta) ==
          doctest::Approx(3.0 * expected).epsilon(1e-12));
  }
}
