// Takeda hysteresis; the numbered rules below are those of docs/takeda.md.
#include "models/takeda.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace nsb::models::takeda {
namespace {

// The bilinear variant needs k0 = f_yield / d_yield; a parameter file written by hand gets
// this relative slack for rounding in the quoted figures.
constexpr double kBilinearStiffnessTolerance = 1e-6;
// A monotone move crosses at most four branches (docs/takeda.md); more means a logic error.
constexpr int kMaxBranchTransitions = 16;
constexpr double kInf = std::numeric_limits<double>::infinity();

[[noreturn]] void bad(const std::string& field, const std::string& what) {
  throw std::invalid_argument("takeda::Parameters: " + field + " " + what);
}

int sign_of(double x) { return x >= 0.0 ? 1 : -1; }

// The fields that a move along a straight branch changes (move_on_line).
void copy_moving_fields(const State& from, State& to) {
  to.d = from.d;
  to.f = from.f;
  to.work = from.work;
}

// std::pow(base, exponent), remembered. A yielded spring asks for the unloading stiffness
// of the same peak at nearly every step (each trial that reverses on the backbone or a
// reloading line), and pow dominated the cost of the update; a small direct-mapped table per
// thread returns the very same value without recomputing it.
double memo_pow(double base, double exponent) {
  struct Entry {
    double base = std::numeric_limits<double>::quiet_NaN();  // NaN never matches: empty
    double exponent = 0.0;
    double value = 0.0;
  };
  constexpr std::size_t kEntries = 16;  // a few springs, each with its current peak
  thread_local std::array<Entry, kEntries> table;
  std::uint64_t bits = 0;
  std::memcpy(&bits, &base, sizeof bits);
  Entry& e = table[(bits ^ (bits >> 17) ^ (bits >> 37)) % kEntries];
  if (!(e.base == base && e.exponent == exponent)) {
    e.base = base;
    e.exponent = exponent;
    e.value = std::pow(base, exponent);
  }
  return e.value;
}

}  // namespace

void Parameters::validate() const {
  if (!(k0 > 0.0) || !std::isfinite(k0)) bad("k0", "must be finite and > 0");
  if (!(d_yield > 0.0) || !std::isfinite(d_yield)) bad("d_yield", "must be finite and > 0");
  if (!(f_yield > 0.0) || !std::isfinite(f_yield)) bad("f_yield", "must be finite and > 0");
  if (!(f_crack >= 0.0) || !std::isfinite(f_crack)) bad("f_crack", "must be finite and >= 0");
  if (!(f_crack < f_yield)) bad("f_crack", "must be < f_yield");
  if (!(post_yield_ratio >= 0.0 && post_yield_ratio < 1.0)) {
    bad("post_yield_ratio", "must be in [0, 1)");
  }
  if (!(unloading_exponent >= 0.0 && unloading_exponent <= 1.0)) {
    bad("unloading_exponent", "must be in [0, 1]");
  }
  const double k_y = f_yield / d_yield;
  if (f_crack == 0.0) {
    if (std::abs(k0 - k_y) > kBilinearStiffnessTolerance * k_y) {
      bad("k0", "must equal f_yield/d_yield = " + std::to_string(k_y) +
                    " for the bilinear variant (f_crack = 0); use Parameters::bilinear");
    }
    return;
  }
  if (!(k0 > k_y)) {
    bad("k0", "must exceed f_yield/d_yield = " + std::to_string(k_y) +
                  " so that cracking (f_crack/k0) precedes yield (d_yield)");
  }
  const double d_crack = f_crack / k0;
  const double k_crack = (f_yield - f_crack) / (d_yield - d_crack);
  if (!(post_yield_ratio * k_y < k_crack)) {
    bad("post_yield_ratio", "must give a post-yield stiffness below the cracked stiffness " +
                                std::to_string(k_crack) + " kN/m");
  }
}

Parameters Parameters::bilinear(double f_yield, double d_yield, double post_yield_ratio,
                                double unloading_exponent) {
  Parameters p;
  p.k0 = f_yield / d_yield;
  p.f_crack = 0.0;
  p.f_yield = f_yield;
  p.d_yield = d_yield;
  p.post_yield_ratio = post_yield_ratio;
  p.unloading_exponent = unloading_exponent;
  return p;
}

Spring::Spring(const Parameters& p) : p_(p) {
  p_.validate();
  const double k_y = p_.f_yield / p_.d_yield;
  k_post_ = p_.post_yield_ratio * k_y;
  if (p_.f_crack > 0.0) {
    k_elastic_ = p_.k0;
    d_crack_ = p_.f_crack / p_.k0;
    f_crack_ = p_.f_crack;
    k_crack_ = (p_.f_yield - p_.f_crack) / (p_.d_yield - d_crack_);
  } else {
    // Bilinear: the elastic branch ends at the yield point; k0 = k_y (validated), and k_y is
    // used so that the backbone is exactly continuous at (d_yield, f_yield).
    k_elastic_ = k_y;
    d_crack_ = p_.d_yield;
    f_crack_ = p_.f_yield;
    k_crack_ = k_y;
  }
  // Rule 5 (Takeda et al. 1970): the yield stiffness of the unloading rule is the slope of
  // the line from the cracking point on one side to the yield point on the other; it equals
  // f_yield/d_yield for the bilinear variant (f_crack = 0, d_crack = 0 there).
  const double fc = p_.f_crack > 0.0 ? p_.f_crack : 0.0;
  const double dc = p_.f_crack > 0.0 ? d_crack_ : 0.0;
  k_yield_unload_ = (p_.f_yield + fc) / (p_.d_yield + dc);
  committed_.peak_pos_d = d_crack_;
  committed_.peak_neg_d = -d_crack_;
  trial_ = committed_;
  committed_tangent_ = trial_tangent_ = k_elastic_;
}

double Spring::backbone_magnitude(double x) const {
  if (x <= d_crack_) return k_elastic_ * x;
  if (x <= p_.d_yield) return f_crack_ + k_crack_ * (x - d_crack_);
  return p_.f_yield + k_post_ * (x - p_.d_yield);
}

double Spring::backbone(double d) const { return sign_of(d) * backbone_magnitude(std::abs(d)); }

double Spring::backbone_integral(double x) const {
  // Antiderivative of the backbone magnitude, integral_0^x b(s) ds, x >= 0.
  const double e1 = 0.5 * k_elastic_ * d_crack_ * d_crack_;
  if (x <= d_crack_) return 0.5 * k_elastic_ * x * x;
  if (x <= p_.d_yield) {
    const double s = x - d_crack_;
    return e1 + f_crack_ * s + 0.5 * k_crack_ * s * s;
  }
  const double sc = p_.d_yield - d_crack_;
  const double e2 = e1 + f_crack_ * sc + 0.5 * k_crack_ * sc * sc;
  const double s = x - p_.d_yield;
  return e2 + p_.f_yield * s + 0.5 * k_post_ * s * s;
}

double Spring::backbone_slope(double x) const {
  // Slope of the backbone segment that ends at or contains x (left limit at a kink).
  if (x <= d_crack_) return k_elastic_;
  if (x <= p_.d_yield) return k_crack_;
  return k_post_;
}

double Spring::backbone_slope_right(double x) const {
  // Slope of the backbone segment that starts at or contains x (right limit at a kink).
  if (x < d_crack_) return k_elastic_;
  if (x < p_.d_yield) return k_crack_;
  return k_post_;
}

double Spring::unloading_stiffness(int side, double peak_d) const {
  (void)side;  // the backbone is symmetric; the side only selects the peak
  const double x = std::abs(peak_d);
  if (x <= d_crack_) return k_elastic_;  // rule 1: still elastic on this side
  if (x <= p_.d_yield) {
    // Rule 4: unloading from the cracked branch aims at the cracking point of the other side.
    return (backbone_magnitude(x) + f_crack_) / (x + d_crack_);
  }
  // Rule 5: k_u = k_y (d_y / d_max)^alpha.
  return k_yield_unload_ * memo_pow(p_.d_yield / x, p_.unloading_exponent);
}

double Spring::peak_magnitude(const State& s, int side) {
  return side > 0 ? s.peak_pos_d : -s.peak_neg_d;
}

void Spring::start_reloading(State& s, int side) const {
  // Rules 6-8: a straight line from the zero-force point (s.d, 0) towards the target of
  // `side`. Magnitudes x are measured along `side`.
  const double x0 = side * s.d;
  const double xp = peak_magnitude(s, side);
  // Rule 6: the furthest backbone point of the side; before yield on that side this is its
  // yield point (bilinear) or its cracking point or cracked-branch peak (trilinear).
  const double xt = xp;
  const double ft = backbone_magnitude(xt);
  const double ku = unloading_stiffness(side, xp);
  const double slope_to_target = xt > x0 ? ft / (xt - x0) : kInf;
  double k = 0.0, x_end = 0.0;
  const bool crosses_post_yield = xt > p_.d_yield && slope_to_target < k_post_;
  if (slope_to_target <= ku && !crosses_post_yield) {
    k = slope_to_target;
    x_end = xt;
  } else if (crosses_post_yield) {
    // Rule 7: aiming at the peak would cross above the post-yield branch; aim at the yield
    // point and follow the backbone from there.
    k = p_.f_yield / (p_.d_yield - x0);
    x_end = p_.d_yield;
  } else {
    // Rule 8: a line steeper than k_u would gain stored energy without work (negative
    // dissipation); reload at k_u until the line meets the backbone.
    k = ku;
    x_end = reloading_meets_backbone(x0, k);
  }
  s.branch = Branch::kReloading;
  s.side = side;
  s.line_d = s.d;
  s.line_f = 0.0;
  s.line_k = k;
  s.line_end_d = side * x_end;
  s.parent_reloading = false;
}

double Spring::reloading_meets_backbone(double x0, double k) const {
  // Last point where the line f = k (x - x0) is still on or below the backbone b(x), for
  // x >= max(x0, 0): g(x) = b(x) - k (x - x0) is concave, so {g >= 0} is an interval and the
  // line reaches the backbone from below at its right end. Infinity if the line never does.
  const double x_start = x0 > 0.0 ? x0 : 0.0;
  double pts[3];
  int n = 0;
  pts[n++] = x_start;
  if (d_crack_ > x_start && d_crack_ < p_.d_yield) pts[n++] = d_crack_;
  if (p_.d_yield > x_start) pts[n++] = p_.d_yield;
  auto g = [&](double x) { return backbone_magnitude(x) - k * (x - x0); };
  int last = -1;
  for (int i = 0; i < n; ++i) {
    if (g(pts[i]) >= 0.0) last = i;
  }
  if (last < 0) return kInf;
  const double xa = pts[last];
  const double ga = g(xa);
  if (last + 1 < n) {
    const double xb = pts[last + 1];
    const double gb = g(xb);
    return xa + ga * (xb - xa) / (ga - gb);
  }
  const double slope = backbone_slope_right(xa) - k;  // slope of g beyond the last point
  if (slope >= 0.0) return kInf;
  return xa - ga / slope;
}

void Spring::move_on_line(State& s, double d_new, double f_new) {
  s.work += 0.5 * (s.f + f_new) * (d_new - s.d);  // exact: the force is linear in d here
  s.d = d_new;
  s.f = f_new;
}

// Each step below moves s towards d (direction m = +-1) on its current branch. It returns
// true when d is reached on that branch, and false after it has moved s to the end of the
// branch and switched s to the next one, from where advance() continues.

// Rule 1: linear up to the elastic limit (cracking, or yield for the bilinear variant).
bool Spring::move_on_elastic(State& s, double d, int m) const {
  const double d_end = m * d_crack_;
  if ((d - d_end) * m <= 0.0) {
    move_on_line(s, d, k_elastic_ * d);
    return true;
  }
  move_on_line(s, d_end, k_elastic_ * d_end);
  s.branch = Branch::kBackbone;
  s.side = m;
  return false;
}

bool Spring::move_on_backbone(State& s, double d, int m) const {
  if (m == s.side) {
    // Rules 2-3: loading along the backbone; the peak of the side follows.
    // With D = side x on this side, integral F dD = integral b(x) dx.
    s.work += backbone_integral(std::abs(d)) - backbone_integral(std::abs(s.d));
    s.d = d;
    s.f = backbone(d);
    if (s.side > 0 && d > s.peak_pos_d) s.peak_pos_d = d;
    if (s.side < 0 && d < s.peak_neg_d) s.peak_neg_d = d;
    return true;
  }
  // Rules 4-5: reversal on the backbone starts an unloading line.
  s.branch = Branch::kUnloading;
  s.line_d = s.d;
  s.line_f = s.f;
  s.line_k = unloading_stiffness(s.side, s.side > 0 ? s.peak_pos_d : s.peak_neg_d);
  s.parent_reloading = false;
  return false;
}

bool Spring::move_on_unloading(State& s, double d, int m) const {
  auto line = [&](double x) { return s.line_f + s.line_k * (x - s.line_d); };
  if (m != s.side) {
    // Towards zero force; past it, rule 6 reloads towards the other side.
    const double d_zero = s.line_d - s.line_f / s.line_k;
    if ((d - d_zero) * m <= 0.0) {
      move_on_line(s, d, line(d));
      return true;
    }
    move_on_line(s, d_zero, 0.0);
    start_reloading(s, -s.side);
    return false;
  }
  // Rule 9: back along the same line to its anchor, then to the branch it came from.
  if ((d - s.line_d) * m <= 0.0) {
    move_on_line(s, d, line(d));
    return true;
  }
  move_on_line(s, s.line_d, s.line_f);
  if (s.parent_reloading) {
    s.branch = Branch::kReloading;
    s.line_d = s.parent_d;
    s.line_f = s.parent_f;
    s.line_k = s.parent_k;
    s.line_end_d = s.parent_end_d;
    s.parent_reloading = false;
  } else {
    s.branch = Branch::kBackbone;
  }
  return false;
}

bool Spring::move_on_reloading(State& s, double d, int m) const {
  if (m == s.side) {
    auto line = [&](double x) { return s.line_f + s.line_k * (x - s.line_d); };
    if ((d - s.line_end_d) * m <= 0.0) {
      move_on_line(s, d, line(d));
      return true;
    }
    // Rule 6: the target reached, loading continues on the backbone.
    move_on_line(s, s.line_end_d, backbone(s.line_end_d));
    s.branch = Branch::kBackbone;
    if (s.side > 0 && s.d > s.peak_pos_d) s.peak_pos_d = s.d;
    if (s.side < 0 && s.d < s.peak_neg_d) s.peak_neg_d = s.d;
    return false;
  }
  // Rule 9: reversal on a reloading line (an inner loop) unloads at k_u of this side and
  // remembers the line, to which it returns past the reversal point.
  s.parent_reloading = true;
  s.parent_d = s.line_d;
  s.parent_f = s.line_f;
  s.parent_k = s.line_k;
  s.parent_end_d = s.line_end_d;
  s.branch = Branch::kUnloading;
  s.line_d = s.d;
  s.line_f = s.f;
  s.line_k = unloading_stiffness(s.side, s.side > 0 ? s.peak_pos_d : s.peak_neg_d);
  return false;
}

void Spring::advance(State& s, double d) const {
  for (int it = 0; it < kMaxBranchTransitions; ++it) {
    const int m = d > s.d ? 1 : -1;  // direction of motion (d != s.d here)
    bool reached = false;
    switch (s.branch) {
      case Branch::kElastic: reached = move_on_elastic(s, d, m); break;
      case Branch::kBackbone: reached = move_on_backbone(s, d, m); break;
      case Branch::kUnloading: reached = move_on_unloading(s, d, m); break;
      case Branch::kReloading: reached = move_on_reloading(s, d, m); break;
    }
    if (reached) return;
  }
  throw std::logic_error("takeda::Spring: too many branch changes in one move");
}

double Spring::tangent_of(const State& s) const {
  switch (s.branch) {
    case Branch::kElastic: return k_elastic_;
    case Branch::kBackbone: return backbone_slope(std::abs(s.d));
    case Branch::kUnloading:
    case Branch::kReloading: return s.line_k;
  }
  return k_elastic_;
}

bool Spring::stays_on_branch(double d, double& f) const {
  // The first test advance() makes on the committed state's branch, and the force it then
  // sets: the same conditions and expressions, so that the fast path of set_trial() gives
  // the same numbers.
  const State& s = committed_;
  const int m = d > s.d ? 1 : -1;
  switch (s.branch) {
    case Branch::kElastic: {
      const double d_end = m * d_crack_;
      if ((d - d_end) * m > 0.0) return false;
      f = k_elastic_ * d;
      return true;
    }
    case Branch::kBackbone: return false;  // loading moves the peak; reversal starts a line
    case Branch::kUnloading: {
      if (m != s.side) {
        const double d_zero = s.line_d - s.line_f / s.line_k;
        if ((d - d_zero) * m > 0.0) return false;
      } else if ((d - s.line_d) * m > 0.0) {
        return false;
      }
      break;
    }
    case Branch::kReloading: {
      if (m != s.side || (d - s.line_end_d) * m > 0.0) return false;
      break;
    }
  }
  f = s.line_f + s.line_k * (d - s.line_d);
  return true;
}

double Spring::set_trial(double d) {
  if (!std::isfinite(d)) {
    // A non-finite trial displacement comes from a numerical blow-up of the integration, not
    // from a caller's input: it yields a non-finite force and tangent, which the integrator
    // reports as divergence. The committed state is untouched, so revert() recovers it.
    trial_ = committed_;
    trial_.d = d;
    trial_.f = std::numeric_limits<double>::quiet_NaN();
    trial_.work = std::numeric_limits<double>::quiet_NaN();
    trial_tangent_ = std::numeric_limits<double>::quiet_NaN();
    trial_moved_on_branch_ = true;  // it differs from the committed state in d, f, work only
    return trial_.f;
  }
  // A move that stays on the committed state's straight branch (rule 1 on the initial
  // branch; rules 4-9 along an unloading or reloading line), or no move: the trial state is
  // the committed one with another d, f and work, computed as advance() would, without the
  // branch logic and, when the previous trial was such a move too, without copying the whole
  // state. Most trials of a yielded spring are such moves (a step moves it by a little).
  double f_line = 0.0;
  if (d == committed_.d || stays_on_branch(d, f_line)) {
    if (trial_moved_on_branch_) {
      copy_moving_fields(committed_, trial_);
    } else {
      trial_ = committed_;
      trial_moved_on_branch_ = true;
    }
    if (d != committed_.d) {
      move_on_line(trial_, d, f_line);
      trial_tangent_ = tangent_of(committed_);  // the branch's slope: k_elastic or line_k
    } else {
      trial_tangent_ = committed_tangent_;
    }
    return trial_.f;
  }
  trial_ = committed_;
  advance(trial_, d);
  trial_moved_on_branch_ = false;
  trial_tangent_ = tangent_of(trial_);
  return trial_.f;
}

State Spring::moved(const State& from, double d) const {
  State s = from;
  if (d != s.d) advance(s, d);
  return s;
}

bool Spring::elastic() const { return committed_.branch == Branch::kElastic; }

double Spring::stored_energy() const {
  const State& s = trial_;
  if (s.f == 0.0) return 0.0;
  double k = k_elastic_;
  switch (s.branch) {
    case Branch::kElastic: k = k_elastic_; break;
    case Branch::kUnloading: k = s.line_k; break;
    case Branch::kBackbone:
    case Branch::kReloading: {
      const int side = sign_of(s.f);
      k = unloading_stiffness(side, side > 0 ? s.peak_pos_d : s.peak_neg_d);
      break;
    }
  }
  // The energy returned by unloading to zero force along the current unloading line.
  return 0.5 * s.f * s.f / k;
}

double Spring::dissipated_energy() const { return trial_.work - stored_energy(); }

void Spring::commit() {
  if (trial_moved_on_branch_) {
    copy_moving_fields(trial_, committed_);  // the other fields are equal
  } else {
    committed_ = trial_;
    trial_moved_on_branch_ = true;  // now equal
  }
  committed_tangent_ = trial_tangent_;
}

void Spring::revert() {
  if (trial_moved_on_branch_) {
    copy_moving_fields(committed_, trial_);
  } else {
    trial_ = committed_;
    trial_moved_on_branch_ = true;
  }
  trial_tangent_ = committed_tangent_;
}

const Parameters& Spring::parameters() const { return p_; }

}  // namespace nsb::models::takeda
