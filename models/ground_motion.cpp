// Ground-motion records: readers, scaling, baseline correction and the spline motion.
// Method and formats: docs/ground-motions.md.
#include "models/ground_motion.hpp"

#include <gsl/gsl_spline.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <istream>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace nsb::models {
namespace {

// Baseline correction polynomial: powers kFirstPower..kLastPower of the normalized time.
// Starting at power 2 keeps the motion at rest at its start (d = v = 0); the highest power
// fixes how slow the removed drift is (docs/ground-motions.md).
constexpr int kFirstPower = 2;
constexpr int kLastPower = 5;
constexpr int kPowers = kLastPower - kFirstPower + 1;
// A cubic spline needs three samples (GSL's cspline minimum size).
constexpr std::size_t kMinSamples = 3;
// Knots within this fraction of a sampling step of the uniform grid count as uniformly
// sampled: the direct interval guess is then off by at most one knot (GroundMotion::Data).
constexpr double kUniformSlack = 0.1;
// Longest AT2 line 4 read ('NPTS= n, DT= dt SEC' and the filter data some files append).
constexpr std::size_t kMaxHeaderLine = 512;

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw std::invalid_argument(where + ": " + what);
}

std::string at(const std::string& file, std::size_t line) {
  return file + ":" + std::to_string(line);
}

// Strict conversion of a whole token to double: no trailing characters, finite.
// Subnormal values are read as they are; a value beyond the range of a double (1e400, or
// 1e-400, which would silently become 0) is refused by name.
double parse_number(std::string_view tok, const std::string& file, std::size_t line) {
  std::string_view s = tok;
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec == std::errc::result_out_of_range && ptr == s.data() + s.size()) {
    fail(at(file, line), "value '" + std::string(tok) + "' is outside the range of a double");
  }
  if (ec != std::errc() || ptr != s.data() + s.size() || s.empty()) {
    fail(at(file, line), "non-numeric token '" + std::string(tok) + "'");
  }
  if (!std::isfinite(v)) fail(at(file, line), "value '" + std::string(tok) + "' is not finite");
  return v;
}

std::vector<std::string_view> split_ws(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    std::size_t j = i;
    while (j < s.size() && !std::isspace(static_cast<unsigned char>(s[j]))) ++j;
    if (j > i) out.push_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// Only regular files are read: a FIFO or a device could block or never end.
std::ifstream open_or_throw(const std::filesystem::path& file) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (ec || !std::filesystem::exists(status)) fail(file.string(), "record file does not exist");
  if (!std::filesystem::is_regular_file(status)) {
    fail(file.string(), "not a regular file; expected a record file");
  }
  std::ifstream in(file);
  if (!in) fail(file.string(), "cannot open the record file for reading");
  return in;
}

void check_unit(double unit, const std::string& file, const char* name) {
  if (!(unit > 0.0) || !std::isfinite(unit)) {
    fail(file, std::string(name) + " must be finite and > 0");
  }
}

// Appends one sample, checking that time increases strictly.
void push_sample(Record& r, double t, double a, const std::string& file,
                 std::size_t line) {
  if (!r.t.empty() && !(t > r.t.back())) {
    std::ostringstream os;
    os.precision(10);
    os << "time " << t << " is not greater than the previous time " << r.t.back()
       << " (time must increase strictly)";
    fail(at(file, line), os.str());
  }
  r.t.push_back(t);
  r.a.push_back(a);
}

void check_size(const Record& r, const std::string& file) {
  if (r.t.size() < kMinSamples) {
    fail(file, "a record needs at least " + std::to_string(kMinSamples) +
                            " samples, found " + std::to_string(r.t.size()));
  }
}

struct SplineDeleter {
  void operator()(gsl_spline* s) const { gsl_spline_free(s); }
};

}  // namespace

Record read_at2(const std::filesystem::path& file, double g) {
  check_unit(g, file.string(), "g");
  std::ifstream in = open_or_throw(file);
  return read_at2(in, file.string(), g);
}

Record read_at2(std::istream& in, const std::string& file, double g) {
  check_unit(g, file, "g");
  std::string line;
  std::size_t line_no = 0;
  // Lines 1-3: free text (database, event and station, units).
  for (int i = 0; i < 3; ++i) {
    if (!std::getline(in, line)) fail(at(file, line_no + 1), "missing AT2 header line");
    ++line_no;
  }
  if (!std::getline(in, line)) fail(at(file, 4), "missing the 'NPTS= n, DT= dt SEC' line");
  ++line_no;
  // Line 4 in both PEER forms: "NPTS=  1559, DT= .02000 SEC" and
  // "NPTS=   8773, DT=   .0050 SEC,   4 POLE @ ..." (filter data may follow).
  // PEER header lines are about 80 characters; a longer line is not one, and std::regex's
  // recursive matcher is kept away from unbounded input.
  if (line.size() > kMaxHeaderLine) {
    fail(at(file, 4), "line 4 has " + std::to_string(line.size()) + " characters; expected "
                      "'NPTS= <count>, DT= <step> SEC' (at most " +
                      std::to_string(kMaxHeaderLine) + ")");
  }
  static const std::regex header(R"(NPTS\s*=\s*([0-9]+)\s*,\s*DT\s*=\s*([-+0-9.eE]+))",
                                 std::regex::icase);
  std::smatch m;
  if (!std::regex_search(line, m, header)) {
    fail(at(file, 4), "expected 'NPTS= <count>, DT= <step> SEC', found '" +
                          std::string(trim(line)) + "'");
  }
  const std::string npts_s = m[1].str();
  const std::string dt_s = m[2].str();
  // At most 9 digits: far more samples than any record, and no overflow in the conversion.
  if (npts_s.size() > 9) fail(at(file, 4), "NPTS = " + npts_s + " is too large");
  const long npts = std::stol(npts_s);
  const double dt = parse_number(dt_s, file, 4);
  if (npts < static_cast<long>(kMinSamples)) {
    fail(at(file, 4), "NPTS must be >= " + std::to_string(kMinSamples));
  }
  if (!(dt > 0.0)) fail(at(file, 4), "DT must be > 0");
  Record r;
  r.source = file;
  std::size_t last_data_line = 4;
  while (std::getline(in, line)) {
    ++line_no;
    for (auto tok : split_ws(line)) {
      const double v = parse_number(tok, file, line_no);
      if (static_cast<long>(r.a.size()) >= npts) {
        fail(at(file, line_no), "more values than NPTS = " + npts_s + " (line 4)");
      }
      r.a.push_back(v * g);
      last_data_line = line_no;
    }
  }
  if (static_cast<long>(r.a.size()) != npts) {
    fail(at(file, last_data_line), "NPTS = " + npts_s + " (line 4) but " +
                                       std::to_string(r.a.size()) + " values found");
  }
  r.t.resize(r.a.size());
  for (std::size_t i = 0; i < r.t.size(); ++i) r.t[i] = static_cast<double>(i) * dt;
  return r;
}

Record read_two_column(const std::filesystem::path& file, double unit) {
  check_unit(unit, file.string(), "unit");
  std::ifstream in = open_or_throw(file);
  return read_two_column(in, file.string(), unit);
}

Record read_two_column(std::istream& in, const std::string& file, double unit) {
  check_unit(unit, file, "unit");
  Record r;
  r.source = file;
  std::string line;
  std::size_t line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const auto s = trim(line);
    if (s.empty() || s.front() == '#') continue;
    const auto toks = split_ws(s);
    if (toks.size() != 2) {
      fail(at(file, line_no), "expected two numbers 't a', found " +
                                  std::to_string(toks.size()) + " fields");
    }
    const double t = parse_number(toks[0], file, line_no);
    const double a = parse_number(toks[1], file, line_no);
    push_sample(r, t, a * unit, file, line_no);
  }
  check_size(r, file);
  return r;
}

Record read_csv(const std::filesystem::path& file, double unit) {
  check_unit(unit, file.string(), "unit");
  std::ifstream in = open_or_throw(file);
  return read_csv(in, file.string(), unit);
}

Record read_csv(std::istream& in, const std::string& file, double unit) {
  check_unit(unit, file, "unit");
  Record r;
  r.source = file;
  std::string line;
  std::size_t line_no = 0;
  auto split_csv = [](std::string_view s) {
    std::vector<std::string_view> out;
    std::size_t start = 0;
    for (;;) {
      const std::size_t comma = s.find(',', start);
      out.push_back(trim(s.substr(start, comma == std::string_view::npos ? comma : comma - start)));
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    return out;
  };
  std::size_t n_fields = 0, col_t = 0, col_a = 1;
  bool have_header = false;
  while (std::getline(in, line)) {
    ++line_no;
    const auto s = trim(line);
    if (s.empty() || s.front() == '#') continue;
    const auto fields = split_csv(s);
    if (!have_header) {
      // Header: columns named t (or time) and a (or acceleration); with exactly two columns
      // of other names, the first is time and the second acceleration.
      n_fields = fields.size();
      bool found_t = false, found_a = false;
      for (std::size_t i = 0; i < fields.size(); ++i) {
        std::string name(fields[i]);
        std::transform(name.begin(), name.end(), name.begin(),
                       [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        if (name == "t" || name == "time") { col_t = i; found_t = true; }
        if (name == "a" || name == "acceleration") { col_a = i; found_a = true; }
      }
      if (!(found_t && found_a) && n_fields != 2) {
        fail(at(file, line_no), "header must name the columns 't' and 'a', found '" +
                                    std::string(s) + "'");
      }
      if (!(found_t && found_a)) { col_t = 0; col_a = 1; }
      have_header = true;
      continue;
    }
    if (fields.size() != n_fields) {
      fail(at(file, line_no), "expected " + std::to_string(n_fields) + " comma-separated fields, found " +
                                  std::to_string(fields.size()));
    }
    const double t = parse_number(fields[col_t], file, line_no);
    const double a = parse_number(fields[col_a], file, line_no);
    push_sample(r, t, a * unit, file, line_no);
  }
  if (!have_header) fail(file, "empty CSV file: expected a header line 't,a'");
  check_size(r, file);
  return r;
}

void validate_record(const Record& r) {
  const std::string who = "record '" + r.source + "'";
  if (r.t.size() != r.a.size()) {
    throw std::invalid_argument(who + ": t and a differ in size (" + std::to_string(r.t.size()) +
                                " vs " + std::to_string(r.a.size()) + ")");
  }
  if (r.t.size() < kMinSamples) {
    throw std::invalid_argument(who + ": needs at least " + std::to_string(kMinSamples) +
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

GroundMotion::GroundMotion(const Record& r, const GroundMotionOptions& o) {
  validate_record(r);
  o.validate();
  auto d = std::make_shared<Data>();
  d->source = r.source;
  d->delay = o.delay;
  const std::size_t n = r.t.size();
  d->t.resize(n);
  // Similitude: t -> time_scale * t with the acceleration unchanged (docs/ground-motions.md).
  for (std::size_t i = 0; i < n; ++i) d->t[i] = o.time_scale * r.t[i];
  for (std::size_t i = 1; i < n; ++i) {
    if (!(d->t[i] > d->t[i - 1])) {
      throw std::invalid_argument("record '" + r.source +
                                  "': time_scale makes the sample times coincide");
    }
  }
  d->t0 = d->t.front();
  d->t1 = d->t.back();
  {
    const double step = (d->t1 - d->t0) / static_cast<double>(n - 1);
    bool uniform = step > 0.0;
    for (std::size_t i = 0; uniform && i < n; ++i) {
      uniform = std::abs(d->t[i] - (d->t0 + static_cast<double>(i) * step)) <= kUniformSlack * step;
    }
    if (uniform) d->uniform_rate = 1.0 / step;
  }

  // Natural cubic spline of the acceleration samples (GSL), then its exact integrals.
  d->spline = std::shared_ptr<gsl_spline>(gsl_spline_alloc(gsl_interp_cspline, n), SplineDeleter{});
  if (!d->spline) throw std::runtime_error("GroundMotion: gsl_spline_alloc failed");
  gsl_spline_init(d->spline.get(), d->t.data(), r.a.data(), n);
  std::vector<double> m2(n);  // second derivatives at the knots
  for (std::size_t i = 0; i < n; ++i) {
    m2[i] = gsl_spline_eval_deriv2(d->spline.get(), d->t[i], nullptr);
  }
  m2.front() = 0.0;  // natural end conditions, exactly
  m2.back() = 0.0;
  d->c0.resize(n - 1);
  d->c1.resize(n - 1);
  d->c2.resize(n - 1);
  d->c3.resize(n - 1);
  d->v_knot.assign(n, 0.0);
  d->d_knot.assign(n, 0.0);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double h = d->t[i + 1] - d->t[i];
    // The cubic on [t_i, t_i+1] from its end values and end second derivatives.
    d->c0[i] = r.a[i];
    d->c1[i] = (r.a[i + 1] - r.a[i]) / h - h * (2.0 * m2[i] + m2[i + 1]) / 6.0;
    d->c2[i] = 0.5 * m2[i];
    d->c3[i] = (m2[i + 1] - m2[i]) / (6.0 * h);
    const double h2 = h * h, h3 = h2 * h, h4 = h3 * h, h5 = h4 * h;
    d->v_knot[i + 1] = d->v_knot[i] + d->c0[i] * h + d->c1[i] * h2 / 2.0 + d->c2[i] * h3 / 3.0 +
                       d->c3[i] * h4 / 4.0;
    d->d_knot[i + 1] = d->d_knot[i] + d->v_knot[i] * h + d->c0[i] * h2 / 2.0 +
                       d->c1[i] * h3 / 6.0 + d->c2[i] * h4 / 12.0 + d->c3[i] * h5 / 20.0;
  }

  if (o.baseline_correction) {
    // Least-squares fit of p(tau) = sum_{k=2..5} b_k tau^k to the displacement at the knots,
    // subject to p(1) = d(t1) and p'(1)/T = v(t1), so that the corrected motion ends at rest
    // where it started; subtracting p, p', p'' keeps d, v, a exactly consistent.
    const double T = d->t1 - d->t0;
    Eigen::Matrix<double, kPowers, kPowers> ata = Eigen::Matrix<double, kPowers, kPowers>::Zero();
    Eigen::Matrix<double, kPowers, 1> atb = Eigen::Matrix<double, kPowers, 1>::Zero();
    for (std::size_t i = 0; i < n; ++i) {
      const double tau = (d->t[i] - d->t0) / T;
      Eigen::Matrix<double, kPowers, 1> row;
      for (int k = 0; k < kPowers; ++k) row(k) = std::pow(tau, k + kFirstPower);
      ata += row * row.transpose();
      atb += row * d->d_knot[i];
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
    rhs(kPowers) = d->d_knot.back();
    rhs(kPowers + 1) = d->v_knot.back() * T;
    const Eigen::Matrix<double, kKkt, 1> sol = kkt.fullPivLu().solve(rhs);
    for (int k = 0; k < kPowers; ++k) d->baseline[k] = sol(k);
  }

  // Amplitude: the PGA of the (corrected) samples, then target_pga and scale.
  double pga_raw = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    double p, dp, ddp;
    d->poly(d->t[i], p, dp, ddp);
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
  d->factor = factor;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    d->c0[i] *= factor;
    d->c1[i] *= factor;
    d->c2[i] *= factor;
    d->c3[i] *= factor;
  }
  for (std::size_t i = 0; i < n; ++i) {
    d->v_knot[i] *= factor;
    d->d_knot[i] *= factor;
  }
  for (double& b : d->baseline) b *= factor;
  d->pga = std::abs(factor) * pga_raw;
  // Finite samples can still overflow the exact integrals (a time span of 1e124 s makes
  // h^5 infinite): such a record is bad input, never a motion that is silently NaN.
  const auto finite = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
  };
  const bool baseline_finite = std::all_of(std::begin(d->baseline), std::end(d->baseline),
                                           [](double x) { return std::isfinite(x); });
  if (!(finite(d->c0) && finite(d->c1) && finite(d->c2) && finite(d->c3) &&
        finite(d->v_knot) && finite(d->d_knot) && baseline_finite && std::isfinite(d->pga))) {
    throw std::invalid_argument("record '" + r.source + "': its velocity or displacement "
                                "overflows (time span " + std::to_string(d->t1 - d->t0) +
                                " s); expected times and accelerations of a ground motion");
  }
  data_ = std::move(d);
}

double GroundMotion::acceleration(double t) const {
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

double GroundMotion::duration() const { return data_ ? data_->t1 - data_->t0 : 0.0; }
double GroundMotion::pga() const { return data_ ? data_->pga : 0.0; }
double GroundMotion::start_time() const { return data_ ? data_->t0 + data_->delay : 0.0; }
double GroundMotion::end_time() const { return data_ ? data_->t1 + data_->delay : 0.0; }

const std::string& GroundMotion::source() const {
  static const std::string kNone;
  return data_ ? data_->source : kNone;
}

}  // namespace nsb::models
