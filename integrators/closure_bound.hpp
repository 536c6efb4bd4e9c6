// A sufficient condition for an open gap to stay open over a step, from its value and rate at
// the step's two ends: the compliance method's closure search (integrators/compliance.cpp)
// probes the step's interpolant only for gaps that fail it.
//
// A cubic p on [0, 1] with p(0) = g0, p(1) = g1, p'(0) = h d0, p'(1) = h d1 is, in the
// Hermite basis, p = h00 g0 + h01 g1 + h (h10 d0 + h11 d1) with h00 + h01 = 1, h00, h01 >= 0
// and |h10|, |h11| <= 4/27 on [0, 1], so p(s) >= min(g0, g1) - (4/27) h (|d0| + |d1|).
// The gap probed on the step's interpolant is such a cubic up to the curvature of the gap
// function (rotation) and the ground motion's deviation from its cubic over the step, which
// is at most a h^2 / 8 for a ground acceleration bounded by a. The condition below asks for
// 27/4 times the cubic's bound plus kClearanceAcceleration h^2 with
// kClearanceAcceleration = 100 m/s^2 (10 g, beyond any record of the suite): a margin of
// 6.75 on the cubic part and of 8 on a 10 g ground motion.
//
// Units: m, m/s, s.
#pragma once

#include <algorithm>
#include <cmath>

namespace nsb::integrators {

inline constexpr double kClearanceAcceleration = 100.0;  // [m/s^2]

// True when the gap with values g0, g1 [m] and rates d0, d1 [m/s] at the ends of a step of
// length h [s] cannot become negative within the step.
inline bool gap_stays_open(double g0, double d0, double g1, double d1, double h) {
  const double clearance = h * (std::abs(d0) + std::abs(d1)) + kClearanceAcceleration * h * h;
  return std::min(g0, g1) > clearance;  // false for NaN
}

}  // namespace nsb::integrators
