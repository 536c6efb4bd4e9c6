// The rotation criterion of eq. (1); see criterion.hpp for the formulas and docs/criterion.md
// for the derivation.
#include "models/criterion.hpp"
#include "models/field_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

namespace nsb::models::analytic {

namespace {

double deg2rad(double d) { return d * std::numbers::pi / 180.0; }
double sgn(double x) { return (x > 0.0) - (x < 0.0); }

}  // namespace

void CriterionInput::validate() const {
  require(std::isfinite(skew_deg) && std::abs(skew_deg) < 90.0,
          "skew", "must be in (-90, 90) degrees");
  require(std::isfinite(width) && width > 0.0, "width", "must be > 0 [m]");
  require(std::isfinite(length) && length > 0.0, "length", "must be > 0 [m]");
  require(std::isfinite(friction) && friction >= 0.0, "friction", "must be >= 0");
}

bool finite_criterion(const CriterionInput& in, const Criterion& c) {
  return std::isnormal(in.width / in.length) && std::isfinite(c.eta_plus) &&
         std::isfinite(c.eta_minus) && std::isfinite(c.printed_eta_plus) &&
         std::isfinite(c.printed_eta_minus);
}

Criterion checked_rotation_criterion(const CriterionInput& in) {
  const Criterion c = rotation_criterion(in);
  if (!finite_criterion(in, c)) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "W = %.6g m and L = %.6g m (W/L = %.6g, mu = %.6g) make eta non-finite; "
                  "expected W/L, L/W and mu L/W within the range of a double",
                  in.width, in.length, in.width / in.length, in.friction);
    throw std::invalid_argument(std::string("width: ") + text);
  }
  return c;
}

double eta(const CriterionInput& in, double impulse_ratio) {
  in.validate();
  const double a = deg2rad(in.skew_deg);
  const double wl = in.width / in.length;
  // (L/W) cos a (sin a - k cos a): the offset of the impulse line of action along the end
  // face, in units of the half face length W/(2 cos a); see docs/criterion.md.
  return std::sin(2.0 * a) / (2.0 * wl) - impulse_ratio * std::cos(a) * std::cos(a) / wl;
}

Criterion rotation_criterion(const CriterionInput& in) {
  in.validate();
  const double a = deg2rad(in.skew_deg);
  const double wl = in.width / in.length;
  const double base = std::sin(2.0 * a) / (2.0 * wl);
  const double fr = in.friction * std::cos(a) * std::cos(a) / wl;
  Criterion c;
  c.eta_plus = base + fr;
  c.eta_minus = base - fr;
  c.rotation = std::max(std::abs(c.eta_plus), std::abs(c.eta_minus)) > 1.0;
  c.printed_eta_plus = base + 2.0 * fr;
  c.printed_eta_minus = base - 2.0 * fr;
  c.printed_rotation = std::max(std::abs(c.printed_eta_plus), std::abs(c.printed_eta_minus)) > 1.0;
  return c;
}

CriterionPrediction predict_right_end_impact(const CriterionInput& in, double vx, double vy,
                                             double restitution) {
  in.validate();
  require(std::isfinite(vx) && vx > 0.0, "vx", "must be > 0 (towards the right abutment)");
  require(std::isfinite(vy), "vy", "must be finite");
  require(restitution >= 0.0 && restitution <= 1.0, "restitution", "must be in [0, 1]");
  const double a = deg2rad(in.skew_deg);
  const double gn = -vx * std::cos(a) + vy * std::sin(a);
  const double gt = -vx * std::sin(a) - vy * std::cos(a);
  require(gn < 0.0, "vx, vy", "the end must approach the abutment (gdot_N- < 0)");
  CriterionPrediction out;
  const double e = restitution;
  out.sliding = std::abs(gt) > in.friction * (1.0 + e) * std::abs(gn);
  out.impulse_ratio = out.sliding ? -sgn(gt) * in.friction : gt / ((1.0 + e) * gn);
  out.eta = eta(in, out.impulse_ratio);
  out.rotation = std::abs(out.eta) > 1.0;
  return out;
}

double end_eta(const DeckGeometry& deck, int end, double impulse_ratio) {
  deck.validate();
  require(end == 0 || end == 1, "end", "must be 0 (left) or 1 (right)");
  require(std::isfinite(impulse_ratio), "impulse_ratio", "must be finite");
  const int plus = 2 * end, minus = 2 * end + 1;  // the end's +W/2 and -W/2 corners
  const Eigen::Vector2d p = deck.corner(plus), q = deck.corner(minus);
  const Eigen::Vector2d mid = 0.5 * (p + q), half = 0.5 * (p - q);
  const Eigen::Vector2d n = deck.face_normal(plus);
  const Eigen::Vector2d d = n + impulse_ratio * perp(n);
  // The line c d through the centroid meets the face's line mid + xi half where
  // (mid + xi half) x d = 0, xi = -(mid x d) / (half x d); eta = -xi (docs/criterion.md).
  return cross2(mid, d) / cross2(half, d);
}

EndCriterion end_criterion(const DeckGeometry& deck, int end, double friction) {
  require(std::isfinite(friction) && friction >= 0.0, "friction", "must be >= 0");
  EndCriterion c;
  c.eta_plus = end_eta(deck, end, -friction);
  c.eta_minus = end_eta(deck, end, friction);
  c.rotation = std::max(std::abs(c.eta_plus), std::abs(c.eta_minus)) > 1.0;
  return c;
}

PlanCriterion plan_criterion(const DeckGeometry& deck, double friction) {
  deck.validate();
  PlanCriterion c;
  bool finite = std::isnormal(deck.width / deck.length);
  for (int end = 0; end < 2; ++end) {
    const EndCriterion e = end_criterion(deck, end, friction);
    finite = finite && std::isfinite(e.eta_plus) && std::isfinite(e.eta_minus);
    c.ends[static_cast<std::size_t>(end)] = e;
    c.rotation = c.rotation || e.rotation;
  }
  if (!finite) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "W = %.6g m and L = %.6g m (W/L = %.6g, mu = %.6g) make eta non-finite; "
                  "expected W/L, L/W and mu L/W within the range of a double",
                  deck.width, deck.length, deck.width / deck.length, friction);
    throw std::invalid_argument(std::string("width: ") + text);
  }
  return c;
}

CriterionPrediction predict_end_impact(const DeckGeometry& deck, int end,
                                       const Eigen::Vector2d& velocity, double friction,
                                       double restitution) {
  require(velocity.allFinite(), "velocity", "must be finite");
  require(std::isfinite(friction) && friction >= 0.0, "friction", "must be >= 0");
  require(restitution >= 0.0 && restitution <= 1.0, "restitution", "must be in [0, 1]");
  const Eigen::Vector2d n = deck.face_normal(2 * end);
  const double gn = n.dot(velocity), gt = perp(n).dot(velocity);
  require(gn < 0.0, "velocity", "the end must approach its abutment (gdot_N- < 0)");
  // As predict_right_end_impact: both corners slide (k = -sgn(gdot_T-) mu) or stick
  // (k = gdot_T- / ((1 + e) gdot_N-), the impulse that stops the tangential motion).
  CriterionPrediction out;
  const double e = restitution;
  out.sliding = std::abs(gt) > friction * (1.0 + e) * std::abs(gn);
  out.impulse_ratio = out.sliding ? -sgn(gt) * friction : gt / ((1.0 + e) * gn);
  out.eta = end_eta(deck, end, out.impulse_ratio);
  out.rotation = std::abs(out.eta) > 1.0;
  return out;
}

}  // namespace nsb::models::analytic
