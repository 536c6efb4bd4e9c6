#include "models/connectors.hpp"
#include "models/field_checks.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace nsb::models::connectors {

namespace {

bool finite_positive(double v) { return std::isfinite(v) && v > 0; }
bool finite_non_negative(double v) { return std::isfinite(v) && v >= 0; }

}  // namespace

void CableParameters::validate(const std::string& prefix) const {
  require(finite_positive(stiffness), prefix + "stiffness", "must be > 0 [kN/m]");
  require(finite_non_negative(slack), prefix + "slack", "must be >= 0 [m]");
  require(finite_non_negative(yield_force), prefix + "yield_force",
          "must be >= 0 [kN] (0: no yield)");
}

double Cable::set_trial(double elongation) {
  State s = committed_;
  s.elongation = elongation;
  const double stretch = elongation - p_.slack - s.plastic;  // beyond slack and set
  if (!(stretch > 0)) {
    s.f = std::isfinite(stretch) ? 0.0 : stretch;
    s.tangent = 0.0;
  } else if (p_.yield_force > 0 && p_.stiffness * stretch > p_.yield_force) {
    // Elastic-perfectly plastic in tension: the force stays at F_y and the excess
    // elongation is permanent.
    s.plastic += stretch - p_.yield_force / p_.stiffness;
    s.f = p_.yield_force;
    s.tangent = 0.0;
  } else {
    s.f = p_.stiffness * stretch;
    s.tangent = p_.stiffness;
  }
  trial_ = s;
  return s.f;
}

double Cable::stored_energy() const { return trial_.f * trial_.f / (2.0 * p_.stiffness); }

double Cable::dissipated_energy() const { return p_.yield_force * trial_.plastic; }

void LawParameters::validate(const std::string& prefix) const {
  require(finite_positive(stiffness), prefix + "stiffness", "must be > 0 [kN/m]");
  if (kind == Kind::kBilinear) {
    require(finite_positive(yield_force), prefix + "yield_force", "must be > 0 [kN]");
    require(std::isfinite(post_yield_ratio) && post_yield_ratio >= 0 && post_yield_ratio < 1,
            prefix + "post_yield_ratio", "must be in [0, 1)");
  }
  if (kind == Kind::kHyperbolicGap) {
    require(finite_positive(ultimate_force), prefix + "ultimate_force", "must be > 0 [kN]");
    require(std::isfinite(failure_ratio) && failure_ratio > 0 && failure_ratio <= 1,
            prefix + "failure_ratio", "must be in (0, 1]");
    // K_ur >= K_max keeps the energy dissipated by a load-unload cycle >= 0 (the envelope's
    // secant stiffness is at most K_max).
    require(std::isfinite(unloading_stiffness) && unloading_stiffness >= stiffness,
            prefix + "unloading_stiffness", "must be >= the stiffness K_max [kN/m]");
    require(compression_sign == 1.0 || compression_sign == -1.0, prefix + "compression_sign",
            "must be +1 or -1");
  }
}

LawParameters LawParameters::linear(double k) { return {.kind = Kind::kLinear, .stiffness = k}; }

LawParameters LawParameters::bilinear(double k, double f_yield, double ratio) {
  return {.kind = Kind::kBilinear, .stiffness = k, .yield_force = f_yield,
          .post_yield_ratio = ratio};
}

LawParameters LawParameters::hyperbolic_gap(double k_max, double f_ult, double r_f, double k_ur,
                                            double compression_sign) {
  return {.kind = Kind::kHyperbolicGap, .stiffness = k_max, .ultimate_force = f_ult,
          .failure_ratio = r_f, .unloading_stiffness = k_ur,
          .compression_sign = compression_sign};
}

Law::Law(const LawParameters& p) : p_(p) {
  committed_.tangent = p.stiffness;
  trial_ = committed_;
}

double Law::envelope(double c) const {
  if (!(c > 0)) return 0.0;
  return c / (1.0 / p_.stiffness + p_.failure_ratio * c / p_.ultimate_force);
}

double Law::envelope_work(double c) const {
  if (!(c > 0)) return 0.0;
  // integral_0^c x / (a + b x) dx = c / b - (a / b^2) ln(1 + b c / a).
  const double a = 1.0 / p_.stiffness, b = p_.failure_ratio / p_.ultimate_force;
  return c / b - a / (b * b) * std::log1p(b * c / a);
}

void Law::bilinear(State& s, double d) const {
  // Kinematic hardening as a linear spring r k in parallel with an elastic-perfectly plastic
  // one of stiffness (1 - r) k and yield force (1 - r) F_y (Naeim & Kelly 1999).
  const double k_ep = (1.0 - p_.post_yield_ratio) * p_.stiffness;
  const double g_max = (1.0 - p_.post_yield_ratio) * p_.yield_force;
  double g = k_ep * (d - s.back);
  s.tangent = p_.stiffness;
  if (std::abs(g) > g_max) {
    const double g_new = std::copysign(g_max, g);
    const double slip = (g - g_new) / k_ep;
    s.back += slip;
    s.dissipated += g_max * std::abs(slip);
    g = g_new;
    s.tangent = p_.post_yield_ratio * p_.stiffness;
  }
  s.f = p_.post_yield_ratio * p_.stiffness * d + g;
}

void Law::hyperbolic(State& s, double d) const {
  const double c = p_.compression_sign * d;  // compression of the backfill
  double fc = 0.0;
  if (c >= s.c_max && c > 0) {
    s.c_max = c;  // on the envelope
    fc = envelope(c);
    const double a = 1.0 / p_.stiffness, b = p_.failure_ratio / p_.ultimate_force;
    s.tangent = a / ((a + b * c) * (a + b * c));
  } else {
    // The unloading-reloading line through the envelope point at c_max, slope K_ur, zero
    // force below the permanent deformation c_max - F(c_max) / K_ur.
    fc = envelope(s.c_max) - p_.unloading_stiffness * (s.c_max - c);
    s.tangent = fc > 0 ? p_.unloading_stiffness : 0.0;
    fc = std::max(fc, 0.0);
  }
  s.f = p_.compression_sign * fc;
}

double Law::set_trial(double d) {
  State s = committed_;
  s.d = d;
  switch (p_.kind) {
    case Kind::kLinear:
      s.f = p_.stiffness * d;
      s.tangent = p_.stiffness;
      break;
    case Kind::kBilinear:
      bilinear(s, d);
      break;
    case Kind::kHyperbolicGap:
      hyperbolic(s, d);
      break;
  }
  trial_ = s;
  return s.f;
}

double Law::stored_energy() const {
  const State& s = trial_;
  switch (p_.kind) {
    case Kind::kLinear:
      return 0.5 * p_.stiffness * s.d * s.d;
    case Kind::kBilinear: {
      const double kr = p_.post_yield_ratio * p_.stiffness;
      const double g = s.f - kr * s.d;
      return 0.5 * kr * s.d * s.d + g * g / (2.0 * (1.0 - p_.post_yield_ratio) * p_.stiffness);
    }
    case Kind::kHyperbolicGap:
      return s.f * s.f / (2.0 * p_.unloading_stiffness);
  }
  return 0.0;
}

double Law::dissipated_energy() const {
  const State& s = trial_;
  switch (p_.kind) {
    case Kind::kLinear:
      return 0.0;
    case Kind::kBilinear:
      return s.dissipated;
    case Kind::kHyperbolicGap: {
      // Work along the envelope to c_max less what the unloading line returns from there.
      const double f = envelope(s.c_max);
      return envelope_work(s.c_max) - f * f / (2.0 * p_.unloading_stiffness);
    }
  }
  return 0.0;
}

}  // namespace nsb::models::connectors
