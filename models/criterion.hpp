// The rotation criterion eta of eq. (1) of Shi & Dimitrakopoulos (2017), derived from the
// impact law of eqs. (3)-(7); the derivation is docs/criterion.md. A product feature (the
// `nsbridge criterion` command), not a test oracle.
#pragma once

#include "models/deck_geometry.hpp"

#include <Eigen/Dense>

#include <array>

namespace nsb::models::analytic {

// Assumptions: a rigid parallelogram deck, not rotating before the impact, strikes a rigid
// abutment with both corners of one end at once; equal e and mu at both corners. Then a
// post-impact motion without rotation exists if and only if the line of action of the total
// impulse (direction n + k t, k = Lambda_T,total / Lambda_N,total in [-mu, mu]) passes through
// the deck's end face between the two corners, which is
//   |eta(k)| <= 1,  eta(k) = (L/W) cos(a) (sin(a) - k cos(a)) = sin(2a)/(2 W/L) - k cos^2(a)/(W/L).
// Fully mobilised friction (both corners sliding) gives the two branches k = -+mu:
//   eta_+- = sin(2a)/(2 W/L) +- mu cos^2(a)/(W/L).
// eq. (1) as printed has 2 mu in place of mu; see docs/criterion.md.
struct CriterionInput {
  double skew_deg = 0.0;  // alpha [deg], in (-90, 90)
  double width = 1.0;     // W [m], > 0
  double length = 1.0;    // L [m], > 0
  double friction = 0.0;  // mu, >= 0
  void validate() const;  // throws std::invalid_argument naming the field
};
struct Criterion {
  double eta_plus = 0.0;          // sin(2a)/(2W/L) + mu cos^2 a/(W/L)  (derived)
  double eta_minus = 0.0;         // sin(2a)/(2W/L) - mu cos^2 a/(W/L)  (derived)
  bool rotation = false;          // max(|eta_plus|, |eta_minus|) > 1
  double printed_eta_plus = 0.0;  // eq. (1) as printed: + 2 mu cos^2 a/(W/L)
  double printed_eta_minus = 0.0; // eq. (1) as printed: - 2 mu cos^2 a/(W/L)
  bool printed_rotation = false;  // max(|printed_eta_plus|, |printed_eta_minus|) > 1
};
Criterion rotation_criterion(const CriterionInput& in);
// Whether c, the criterion of in, is an answer: eta scales with L/W, so inputs within their
// ranges whose ratio W/L underflows or overflows a double (W = 1e-300 m, L = 1e300 m) make
// eta infinite or NaN. W/L must be a normal double (so that L/W is finite too) and every eta
// finite.
bool finite_criterion(const CriterionInput& in, const Criterion& c);
// rotation_criterion(in), or std::invalid_argument "width: ..." naming W, L, W/L and mu when
// it is not finite_criterion: the one check of `nsbridge criterion` and nsbridge.criterion.
Criterion checked_rotation_criterion(const CriterionInput& in);
// eta(k) for a given ratio k = total tangential / total normal impulse.
double eta(const CriterionInput& in, double impulse_ratio);

// The two-corner impact at the right end (corners 3 and 4) with u- = (vx, vy, 0), vx > 0:
// which branch applies and what the criterion predicts for this particular impact.
//   gdot_N- = -vx cos a + vy sin a (both corners), gdot_T- = -vx sin a - vy cos a.
//   If |gdot_T-| > mu (1 + e) |gdot_N-| the corners slide with sign s = sgn(gdot_T-) and
//   k = -s mu; otherwise they stick and k = gdot_T- / ((1 + e) gdot_N-).
struct CriterionPrediction {
  bool sliding = false;
  double impulse_ratio = 0.0;  // k
  double eta = 0.0;            // eta(k)
  bool rotation = false;       // |eta| > 1
};
CriterionPrediction predict_right_end_impact(const CriterionInput& in, double vx, double vy,
                                             double restitution);

// The criterion for one end of any deck plan (models/deck_geometry.hpp): end faces at
// unequal angles (the centroid then lies off the axis's midpoint) and a curved deck's radial
// ends (docs/criterion.md, "Unequal end angles and curved decks"). With, from the centroid,
// M the midpoint of the end's face (between its corners) and h half the face, from its -W/2
// corner to its +W/2 corner, the total impulse's line of action (direction d = n + k t, n
// and t of that end, k = Lambda_T,total / Lambda_N,total) passes through the centroid and
// meets the face's line at M - eta h with
//   eta(k) = (M x d) / (h x d);
// a motion without rotation exists iff |eta| <= 1. For equal angles at the right end this
// is eta() above; at the left end of such a deck it is eta() with alpha and k of that end.
double end_eta(const DeckGeometry& deck, int end, double impulse_ratio);
// Both sliding branches of one end: eta_plus = end_eta(-mu), eta_minus = end_eta(+mu);
// rotation = max(|eta_plus|, |eta_minus|) > 1.
struct EndCriterion {
  double eta_plus = 0.0;
  double eta_minus = 0.0;
  bool rotation = false;
};
EndCriterion end_criterion(const DeckGeometry& deck, int end, double friction);
// Both ends of a plan at the friction mu: end_criterion of the left (ends[0]) and right
// (ends[1]) end; rotation when either end predicts it. Throws std::invalid_argument naming
// the field for a bad plan or mu, and "width: ..." naming W, L and mu when an eta is not
// finite (eta scales with L/W, so W/L must be a normal double): the one check of
// `nsbridge criterion` with a plan and nsbridge.end_criterion.
struct PlanCriterion {
  std::array<EndCriterion, 2> ends{};
  bool rotation = false;
};
PlanCriterion plan_criterion(const DeckGeometry& deck, double friction);
// The two-corner impact of end `end` (0 left, 1 right) of a deck translating at v, as
// predict_right_end_impact: gdot_N- = n . v < 0, gdot_T- = t . v.
CriterionPrediction predict_end_impact(const DeckGeometry& deck, int end,
                                       const Eigen::Vector2d& velocity, double friction,
                                       double restitution);

}  // namespace nsb::models::analytic
