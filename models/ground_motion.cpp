// The spline motion of a ground-motion record: time scaling, baseline correction and
// amplitude scaling (the record readers are records.cpp). Method: docs/ground-motions.md.
#include "models/ground_motion.hpp"

#include "io/csv.hpp"

#include <gsl/gsl_spline.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace nsb::models {
namespace {

// Baseline correction polynomial: powers kFirstPower..kLastPower of the normalized time.
// Starting at power 2 keeps the motion at rest at its start (d = v = 0); the highest power
// fixes how slow the removed drift is (docs/ground-motions.md).
constexpr int kFirstPower = 2;
constexpr int kLastPower = 5;
constexpr int kPowers = kLastPower - kFirstPower + 1;
// Knots within this fraction of a sampling step of the uniform grid count as uniformly
// sampled: the direct interval guess is then off by at most one knot (GroundMotion::Data).
constexpr double kUniformSlack = 0.1;
// Relative round-off by which a part of a sequence may start before the end of the one before
// it (GroundMotion::sequence): a few ulps of the sums that place them.
constexpr double kSequenceSlack = 1e-12;

struct SplineDeleter {
  void operator()(gsl_spline* s) const { gsl_spline_free(s); }
};

}  // namespace

void GroundMotionOptions::validate() const {
  auto bad = [](const char* field, const char* what) {
    throw std::invalid_argument(std::string("GroundMotionOptions: ") + field + " " + what);
  };
  if (!(target_pga >= 0.0) || !std::isfinite(target_pga)) bad("target_pga", "must be finite and >= 0");
  if (!std::isfinite(scale)) bad("scale", "must be finite");
  if (!(time_scale > 0.0) || !std::isfinite(time_scale)) bad("time_scale", "must be finite and > 0");
  if (!(delay >= 0.0) || !std::isfinite(delay)) bad("delay", "must be finite and >= 0");
}

// Everything a GroundMotion evaluates, computed once and shared (read-only) by copies.
struct GroundMotion::Data {
  std::string source;
  std::vector<double> t;  // knot times after time scaling (without the delay) [s]
  // Per interval i (local time s = t - t_i): a(s) = c0 + c1 s + c2 s^2 + c3 s^3, and the
  // exact integrals v_knot[i], d_knot[i] of the spline at the knots. All already multiplied
  // by the amplitude factor; the baseline polynomial is subtracted at evaluation.
  std::vector<double> c0, c1, c2, c3, v_knot, d_knot;
  std::shared_ptr<gsl_spline> spline;  // the natural cubic spline of the unscaled samples
  double factor = 1.0;                 // amplitude factor applied to the spline values
  double baseline[kPowers] = {};       // p(tau) = sum baseline[k] tau^(k + kFirstPower)
  double delay = 0.0, t0 = 0.0, t1 = 0.0, pga = 0.0;

  // Baseline polynomial and its first two time derivatives at time t in [t0, t1].
  void poly(double t_rel, double& p, double& dp, double& ddp) const {
    const double T = t1 - t0;
    const double tau = (t_rel - t0) / T;
    p = dp = ddp = 0.0;
    double pw = 1.0;  // tau^(n - 2)
    for (int k = 0; k < kPowers; ++k) {
      const int n = k + kFirstPower;
      const double c = baseline[k];
      ddp += c * n * (n - 1) * pw;
      dp += c * n * pw * tau;
      p += c * pw * tau * tau;
      pw *= tau;
    }
    dp /= T;
    ddp /= T * T;
  }
  // Index i in [0, n-2] of the interval holding t_rel: the last knot with t[i] <= t_rel
  // (0 before the first). Records are almost always sampled uniformly: then the interval
  // follows from the sampling step, corrected by at most a knot or two for round-off in the
  // knot times, with the same result as the binary search used otherwise.
  std::size_t interval(double t_rel) const {
    const std::size_t last = t.size() - 2;
    if (uniform_rate > 0.0) {
      const double guess = (t_rel - t0) * uniform_rate;
      std::size_t i = !(guess > 0.0) ? 0  // also NaN, which must not reach the cast
                      : guess >= static_cast<double>(last) ? last
                                                           : static_cast<std::size_t>(guess);
      while (i > 0 && t[i] > t_rel) --i;
      while (i < last && t[i + 1] <= t_rel) ++i;
      return i;
    }
    const auto it = std::upper_bound(t.begin(), t.end(), t_rel);
    const std::size_t i = it == t.begin() ? 0 : static_cast<std::size_t>(it - t.begin()) - 1;
    return std::min(i, last);
  }
  // 1 / sampling step when every knot lies within a tenth of a step of the uniform grid
  // t0 + i (t1 - t0) / (n - 1); 0 otherwise (interval() then searches).
  double uniform_rate = 0.0;
};

namespace {

// The knot times: the record's times scaled by time_scale (similitude, the acceleration
// unchanged; docs/ground-motions.md), and whether they are uniformly spaced.
void scale_times(GroundMotion::Data& d, const Record& r, const GroundMotionOptions& o) {
  const std::size_t n = r.t.size();
  d.t.resize(n);
  // Similitude: t -> time_scale * t with the acceleration unchanged (docs/ground-motions.md).
  for (std::size_t i = 0; i < n; ++i) d.t[i] = o.time_scale * r.t[i];
  for (std::size_t i = 1; i < n; ++i) {
    if (!(d.t[i] > d.t[i - 1])) {
      throw std::invalid_argument("record '" + r.source +
                                  "': time_scale makes the sample times coincide");
    }
  }
  d.t0 = d.t.front();
  d.t1 = d.t.back();
  const double step = (d.t1 - d.t0) / static_cast<double>(n - 1);
  bool uniform = step > 0.0;
  for (std::size_t i = 0; uniform && i < n; ++i) {
    uniform = std::abs(d.t[i] - (d.t0 + static_cast<double>(i) * step)) <= kUniformSlack * step;
  }
  if (uniform) d.uniform_rate = 1.0 / step;
}

// The natural cubic spline of the acceleration samples (GSL), its coefficients per interval
// and its exact integrals at the knots (velocity and displacement).
void fit_spline(GroundMotion::Data& d, const Record& r) {
  const std::size_t n = r.t.size();
  d.spline = std::shared_ptr<gsl_spline>(gsl_spline_alloc(gsl_interp_cspline, n), SplineDeleter{});
  if (!d.spline) throw std::runtime_error("GroundMotion: gsl_spline_alloc failed");
  gsl_spline_init(d.spline.get(), d.t.data(), r.a.data(), n);
  std::vector<double> m2(n);  // second derivatives at the knots
  for (std::size_t i = 0; i < n; ++i) {
    m2[i] = gsl_spline_eval_deriv2(d.spline.get(), d.t[i], nullptr);
  }
  m2.front() = 0.0;  // natural end conditions, exactly
  m2.back() = 0.0;
  d.c0.resize(n - 1);
  d.c1.resize(n - 1);
  d.c2.resize(n - 1);
  d.c3.resize(n - 1);
  d.v_knot.assign(n, 0.0);
  d.d_knot.assign(n, 0.0);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double h = d.t[i + 1] - d.t[i];
    // The cubic on [t_i, t_i+1] from its end values and end second derivatives.
    d.c0[i] = r.a[i];
    d.c1[i] = (r.a[i + 1] - r.a[i]) / h - h * (2.0 * m2[i] + m2[i + 1]) / 6.0;
    d.c2[i] = 0.5 * m2[i];
    d.c3[i] = (m2[i + 1] - m2[i]) / (6.0 * h);
    const double h2 = h * h, h3 = h2 * h, h4 = h3 * h, h5 = h4 * h;
    d.v_knot[i + 1] = d.v_knot[i] + d.c0[i] * h + d.c1[i] * h2 / 2.0 + d.c2[i] * h3 / 3.0 +
                       d.c3[i] * h4 / 4.0;
    d.d_knot[i + 1] = d.d_knot[i] + d.v_knot[i] * h + d.c0[i] * h2 / 2.0 +
                       d.c1[i] * h3 / 6.0 + d.c2[i] * h4 / 12.0 + d.c3[i] * h5 / 20.0;
  }
}

// Baseline correction: the polynomial subtracted from the displacement.
void fit_baseline(GroundMotion::Data& d) {
  const std::size_t n = d.t.size();
  // Least-squares fit of p(tau) = sum_{k=2..5} b_k tau^k to the displacement at the knots,
  // subject to p(1) = d(t1) and p'(1)/T = v(t1), so that the corrected motion ends at rest
  // where it started; subtracting p, p', p'' keeps d, v, a exactly consistent.
  const double T = d.t1 - d.t0;
  Eigen::Matrix<double, kPowers, kPowers> ata = Eigen::Matrix<double, kPowers, kPowers>::Zero();
  Eigen::Matrix<double, kPowers, 1> atb = Eigen::Matrix<double, kPowers, 1>::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const double tau = (d.t[i] - d.t0) / T;
    Eigen::Matrix<double, kPowers, 1> row;
    for (int k = 0; k < kPowers; ++k) row(k) = std::pow(tau, k + kFirstPower);
    ata += row * row.transpose();
    atb += row * d.d_knot[i];
  }
  constexpr int kKkt = kPowers + 2;
  Eigen::Matrix<double, kKkt, kKkt> kkt = Eigen::Matrix<double, kKkt, kKkt>::Zero();
  Eigen::Matrix<double, kKkt, 1> rhs = Eigen::Matrix<double, kKkt, 1>::Zero();
  kkt.topLeftCorner<kPowers, kPowers>() = ata;
  rhs.head<kPowers>() = atb;
  for (int k = 0; k < kPowers; ++k) {
    const int pw = k + kFirstPower;
    kkt(kPowers, k) = kkt(k, kPowers) = 1.0;           // p(1)
    kkt(kPowers + 1, k) = kkt(k, kPowers + 1) = pw;    // p'(1) in tau
  }
  rhs(kPowers) = d.d_knot.back();
  rhs(kPowers + 1) = d.v_knot.back() * T;
  const Eigen::Matrix<double, kKkt, 1> sol = kkt.fullPivLu().solve(rhs);
  for (int k = 0; k < kPowers; ++k) d.baseline[k] = sol(k);
}

// The amplitude factor (target_pga, scale) applied to the spline and the baseline.
void scale_amplitude(GroundMotion::Data& d, const Record& r, const GroundMotionOptions& o) {
  const std::size_t n = r.t.size();
  // The PGA of the (corrected) samples, then target_pga and scale.
  double pga_raw = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    double p, dp, ddp;
    d.poly(d.t[i], p, dp, ddp);
    pga_raw = std::max(pga_raw, std::abs(r.a[i] - ddp));
  }
  double factor = o.scale;
  if (o.target_pga > 0.0) {
    if (!(pga_raw > 0.0)) {
      throw std::invalid_argument("record '" + r.source +
                                  "': target_pga needs a record with non-zero acceleration");
    }
    factor *= o.target_pga / pga_raw;
  }
  d.factor = factor;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    d.c0[i] *= factor;
    d.c1[i] *= factor;
    d.c2[i] *= factor;
    d.c3[i] *= factor;
  }
  for (std::size_t i = 0; i < n; ++i) {
    d.v_knot[i] *= factor;
    d.d_knot[i] *= factor;
  }
  for (double& b : d.baseline) b *= factor;
  d.pga = std::abs(factor) * pga_raw;
}

// Finite samples can still overflow the exact integrals (a time span of 1e124 s makes h^5
// infinite): such a record is bad input, never a motion that is silently NaN.
void check_finite(const GroundMotion::Data& d, const Record& r) {
  const auto finite = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
  };
  const bool baseline_finite = std::all_of(std::begin(d.baseline), std::end(d.baseline),
                                           [](double x) { return std::isfinite(x); });
  if (!(finite(d.c0) && finite(d.c1) && finite(d.c2) && finite(d.c3) &&
        finite(d.v_knot) && finite(d.d_knot) && baseline_finite && std::isfinite(d.pga))) {
    throw std::invalid_argument("record '" + r.source + "': its velocity or displacement "
                                "overflows (time span " + io::three_digits(d.t1 - d.t0) +
                                " s); expected times and accelerations of a ground motion");
  }
}

}  // namespace

struct GroundMotion::Parts {
  std::vector<GroundMotion> motions;  // >= 2, each a record's, in order of start time
  std::vector<double> start;          // start_time() of each [s]
  std::vector<double> carried;        // displacement each starts from [m]
  double pga = 0.0;                   // [m/s^2]
  std::string source;
};

GroundMotion::GroundMotion(const Record& r, const GroundMotionOptions& o) {
  validate_record(r);
  o.validate();
  auto d = std::make_shared<Data>();
  d->source = r.source;
  d->delay = o.delay;
  scale_times(*d, r, o);
  fit_spline(*d, r);
  if (o.baseline_correction) fit_baseline(*d);
  scale_amplitude(*d, r, o);
  check_finite(*d, r);
  data_ = std::move(d);
}

double GroundMotion::acceleration(double t) const {
  if (parts_) return sequence_values(t).acceleration;
  if (!data_) return 0.0;
  const Data& d = *data_;
  const double tr = t - d.delay;
  if (tr < d.t0 || tr > d.t1) return 0.0;
  const std::size_t i = d.interval(tr);
  const double s = tr - d.t[i];
  double p, dp, ddp;
  d.poly(tr, p, dp, ddp);
  return d.c0[i] + s * (d.c1[i] + s * (d.c2[i] + s * d.c3[i])) - ddp;
}

double GroundMotion::velocity(double t) const {
  if (parts_) return sequence_values(t).velocity;
  if (!data_) return 0.0;
  const Data& d = *data_;
  const double tr = t - d.delay;
  if (tr < d.t0 || tr > d.t1) return 0.0;
  const std::size_t i = d.interval(tr);
  const double s = tr - d.t[i];
  double p, dp, ddp;
  d.poly(tr, p, dp, ddp);
  return d.v_knot[i] + s * (d.c0[i] + s * (d.c1[i] / 2.0 + s * (d.c2[i] / 3.0 + s * d.c3[i] / 4.0))) -
         dp;
}

double GroundMotion::displacement(double t) const {
  if (parts_) return sequence_values(t).displacement;
  if (!data_) return 0.0;
  const Data& d = *data_;
  double tr = t - d.delay;
  if (tr < d.t0) return 0.0;
  if (tr > d.t1) tr = d.t1;  // held after the end
  const std::size_t i = d.interval(tr);
  const double s = tr - d.t[i];
  double p, dp, ddp;
  d.poly(tr, p, dp, ddp);
  return d.d_knot[i] + s * (d.v_knot[i] + s * (d.c0[i] / 2.0 + s * (d.c1[i] / 6.0 +
                                                                  s * (d.c2[i] / 12.0 + s * d.c3[i] / 20.0)))) -
         p;
}

GroundMotion::Values GroundMotion::values(double t) const {
  if (parts_) return sequence_values(t);
  Values v;
  if (!data_) return v;
  const Data& d = *data_;
  double tr = t - d.delay;
  if (tr < d.t0) return v;
  const bool after_end = tr > d.t1;
  if (after_end) tr = d.t1;  // the displacement is held; velocity and acceleration are 0
  const std::size_t i = d.interval(tr);
  const double s = tr - d.t[i];
  double p, dp, ddp;
  d.poly(tr, p, dp, ddp);
  // The expressions of displacement(), velocity() and acceleration().
  v.displacement =
      d.d_knot[i] +
      s * (d.v_knot[i] +
           s * (d.c0[i] / 2.0 + s * (d.c1[i] / 6.0 + s * (d.c2[i] / 12.0 + s * d.c3[i] / 20.0)))) -
      p;
  if (after_end) return v;
  v.velocity =
      d.v_knot[i] + s * (d.c0[i] + s * (d.c1[i] / 2.0 + s * (d.c2[i] / 3.0 + s * d.c3[i] / 4.0))) -
      dp;
  v.acceleration = d.c0[i] + s * (d.c1[i] + s * (d.c2[i] + s * d.c3[i])) - ddp;
  return v;
}

double GroundMotion::duration() const {
  if (parts_) return end_time() - start_time();
  return data_ ? data_->t1 - data_->t0 : 0.0;
}
double GroundMotion::pga() const {
  if (parts_) return parts_->pga;
  return data_ ? data_->pga : 0.0;
}
double GroundMotion::start_time() const {
  if (parts_) return parts_->motions.front().start_time();
  return data_ ? data_->t0 + data_->delay : 0.0;
}
double GroundMotion::end_time() const {
  if (parts_) return parts_->motions.back().end_time();
  return data_ ? data_->t1 + data_->delay : 0.0;
}

const std::string& GroundMotion::source() const {
  static const std::string kNone;
  if (parts_) return parts_->source;
  return data_ ? data_->source : kNone;
}

GroundMotion GroundMotion::sequence(const std::vector<GroundMotion>& parts, bool ends_at_rest) {
  auto p = std::make_shared<Parts>();
  for (const GroundMotion& m : parts) {
    if (m.empty()) continue;
    if (m.parts_) throw std::invalid_argument("GroundMotion::sequence: a part is a sequence");
    // A part placed at the end of the one before it may start a round-off earlier (its start
    // and the end before it are sums of different terms).
    const double end = p->motions.empty() ? 0.0 : p->motions.back().end_time();
    if (!p->motions.empty() && !(m.start_time() >= end - kSequenceSlack * std::max(1.0, std::abs(end)))) {
      throw std::invalid_argument("GroundMotion::sequence: part '" + m.source() + "' starts at " +
                                  io::three_digits(m.start_time()) + " s, before the end of '" +
                                  p->motions.back().source() + "' at " +
                                  io::three_digits(p->motions.back().end_time()) + " s");
    }
    p->motions.push_back(m);
  }
  if (p->motions.empty()) throw std::invalid_argument("GroundMotion::sequence: no part");
  if (p->motions.size() == 1) return p->motions.front();
  double carried = 0.0;
  for (std::size_t k = 0; k < p->motions.size(); ++k) {
    const GroundMotion& m = p->motions[k];
    p->start.push_back(m.start_time());
    p->carried.push_back(carried);
    // The displacement at which this part leaves the ground, held after its end.
    if (!ends_at_rest) carried += m.displacement(m.end_time());
    p->pga = std::max(p->pga, m.pga());
    p->source += (k == 0 ? "" : " then ") + m.source();
  }
  GroundMotion out;
  out.data_ = p->motions.front().data_;
  out.parts_ = std::move(p);
  return out;
}

// The last part started before t (the first before any): its values, from the displacement
// the parts before it left. At the start time of a part the part before it still holds, so
// that the motion up to and including that time is the earlier records' alone (a run that
// ends there and one that goes on agree to that time, bit for bit). Adding a carried 0 is
// skipped so that the values of a part are its own, bit for bit (x + 0.0 would turn a -0.0
// into +0.0).
GroundMotion::Values GroundMotion::sequence_values(double t) const {
  const Parts& p = *parts_;
  std::size_t k = p.start.size() - 1;
  while (k > 0 && !(p.start[k] < t)) --k;
  Values v = p.motions[k].values(t);
  if (p.carried[k] != 0.0) v.displacement += p.carried[k];
  return v;
}

void validate_record(const Record& r) {
  const std::string who = "record '" + r.source + "'";
  if (r.t.size() != r.a.size()) {
    throw std::invalid_argument(who + ": t and a differ in size (" + std::to_string(r.t.size()) +
                                " vs " + std::to_string(r.a.size()) + ")");
  }
  if (r.t.size() < kMinRecordSamples) {
    throw std::invalid_argument(who + ": needs at least " + std::to_string(kMinRecordSamples) +
                                " samples, has " + std::to_string(r.t.size()));
  }
  for (std::size_t i = 0; i < r.t.size(); ++i) {
    if (!std::isfinite(r.t[i]) || !std::isfinite(r.a[i])) {
      throw std::invalid_argument(who + ": sample " + std::to_string(i) + " is not finite");
    }
    if (i > 0 && !(r.t[i] > r.t[i - 1])) {
      throw std::invalid_argument(who + ": time of sample " + std::to_string(i) +
                                  " does not increase strictly");
    }
  }
}

}  // namespace nsb::models
