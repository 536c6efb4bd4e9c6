// fragility.png and the files of a sweep's fragility (sweep/fragility_sweep.hpp).
#include "io/gnuplot.hpp"
#include "io/csv.hpp"
#include "sweep/fragility_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace nsb::sweep {

namespace fs = std::filesystem;

namespace {

// P(x) = Phi(ln(x / theta) / beta) (Baker 2015, eq. 1), Phi from erfc.
double lognormal_cdf(double x, double theta, double beta) {
  return 0.5 * std::erfc(-std::log(x / theta) / (beta * std::sqrt(2.0)));
}

// A gnuplot string literal: '"' and '\' escaped.
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + '"';
}

// The curve on 200 points of (0, x_max] with its band: at each x, the least and largest P
// over the four corners of the theta and beta bands. P is monotone in theta, and in beta for a
// fixed theta, so the corners bound P over the rectangle of the two marginal 95 % bands (a
// band wider than a joint one would be).
std::string curve_block(const FragilityFit& f, double x_max, const std::string& name) {
  std::ostringstream s;
  s.precision(10);
  const bool bands = f.ci95_theta[1] > 0.0 && f.ci95_beta[1] > 0.0;
  s << '$' << name << " << EOD\n";
  for (int i = 1; i <= 200; ++i) {
    const double x = x_max * i / 200.0;
    const double p = lognormal_cdf(x, f.theta, f.beta);
    double lo = p, hi = p;
    if (bands) {
      for (const double th : f.ci95_theta) {
        for (const double be : f.ci95_beta) {
          lo = std::min(lo, lognormal_cdf(x, th, be));
          hi = std::max(hi, lognormal_cdf(x, th, be));
        }
      }
    }
    s << x << ' ' << p << ' ' << lo << ' ' << hi << '\n';
  }
  s << "EOD\n";
  return s.str();
}

std::string points_block(const LimitStateFit& f, const std::string& name) {
  std::ostringstream s;
  s.precision(10);
  s << '$' << name << " << EOD\n";
  for (const auto& st : f.stripes)
    if (st.n > 0) s << st.im << ' ' << static_cast<double>(st.exceeded) / st.n << '\n';
  s << "EOD\n";
  return s.str();
}

std::string curve_title(const LimitStateFit& f) {
  std::ostringstream s;
  s.precision(3);
  s << f.limit.name;
  if (has_estimate(f.mle.status)) {
    s << ": theta = " << f.mle.theta << ", beta = " << f.mle.beta;
  } else {
    s << ": " << to_string(f.mle.status);
  }
  return s.str();
}

}  // namespace

std::string fragility_script(const FragilityReport& report) {
  double x_max = 0.0;
  for (const auto& f : report.fits)
    for (const auto& s : f.stripes) x_max = std::max(x_max, s.im);
  x_max = x_max > 0.0 ? 1.1 * x_max : 1.0;
  std::string data, plot;
  for (std::size_t k = 0; k < report.fits.size(); ++k) {
    const LimitStateFit& f = report.fits[k];
    const std::string id = std::to_string(k), lc = " lc " + std::to_string(k + 1);
    const std::string title = " title " + quoted(curve_title(f)) + " noenhanced";
    data += points_block(f, "points" + id);
    if (has_estimate(f.mle.status)) {
      data += curve_block(f.mle, x_max, "curve" + id);
      plot += "$curve" + id + " using 1:3:4 with filledcurves fs transparent solid 0.2 noborder" +
              lc + " notitle, \\\n  ";
      plot += "$curve" + id + " using 1:2 with lines lw 2" + lc + title + ", \\\n  ";
      plot += "$points" + id + " using 1:2 with points pt 7 ps 1.2" + lc + " notitle, \\\n  ";
    } else {
      plot += "$points" + id + " using 1:2 with points pt 7 ps 1.2" + lc + title + ", \\\n  ";
    }
  }
  plot.resize(plot.size() - std::string(", \\\n  ").size());
  std::string script = data;
  script += "set xlabel " + quoted(report.im) + " noenhanced\n";
  script += "set ylabel \"P(limit state reached)\"\n";
  script += "set xrange [0:" + io::csv_number(x_max) + "]\nset yrange [0:1]\n";
  script += "set key left top\nset grid\n";
  script += "plot " + plot + "\n";
  return script;
}

std::vector<fs::path> write_fragility(const Design& d, const Results& results, const fs::path& out,
                                      const std::string& gnuplot) {
  if (!d.fragility) return {};
  const FragilityReport report =
      fit_fragility(*d.fragility, results, is_ida(d, d.fragility->im));
  std::vector<fs::path> files{out / "fragility.json"};
  write_file_atomically(files.back(), fragility_json(report));
  if (!gnuplot.empty()) {
    files.push_back(out / "fragility.png");
    const std::string failed = io::draw_gnuplot(gnuplot, fragility_script(report), files.back());
    if (!failed.empty()) throw std::runtime_error(failed);
  }
  return files;
}

}  // namespace nsb::sweep
