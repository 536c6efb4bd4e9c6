// Closed-form references of the simple systems; see analytic.hpp for the formulas and
// docs/analytic.md for the derivations. The deck impact is deck_impact.cpp.
#include "models/analytic.hpp"
#include "models/field_checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace nsb::models::analytic {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

// Bisection on the closed-form slip velocity stops at this relative width of the bracket
// (near double precision; the function is smooth and cheap).
constexpr double kBisectionWidth = 1e-14;
// Phases (w t) below this are round-off of a zero phase in first_arrival.
constexpr double kPhaseRoundOff = 1e-9;
// Safety cap on impacts generated when stepping the oscillator to a time t.
constexpr int kMaxOscillatorImpacts = 1000000;

double deg2rad(double d) { return d * kPi / 180.0; }
double sgn(double x) { return (x > 0.0) - (x < 0.0); }

}  // namespace

// =======================================================================================
// Bouncing ball

namespace {
// The ball references need g > 0 (with g = 0 a ball never returns after its first rebound).
void require_ball(const BouncingBall::Parameters& p) {
  p.validate();
  require(p.gravity > 0.0, "gravity", "the closed form needs g > 0");
}
}  // namespace

double ball_first_impact_speed(const BouncingBall::Parameters& p) {
  require_ball(p);
  // Energy: v^2 = v0^2 + 2 g h at y = 0.
  return std::sqrt(p.velocity * p.velocity + 2.0 * p.gravity * p.height);
}

double ball_first_impact_time(const BouncingBall::Parameters& p) {
  const double v1 = ball_first_impact_speed(p);
  if (p.height == 0.0 && p.velocity <= 0.0) return 0.0;  // already on the ground, approaching
  // Root of h + v0 t - g t^2/2 = 0 with t > 0.
  return (p.velocity + v1) / p.gravity;
}

std::vector<BallImpact> ball_impacts(const BouncingBall::Parameters& p, int count) {
  require(count >= 0, "count", "must be >= 0");
  std::vector<BallImpact> out;
  if (count == 0) return out;
  double t = ball_first_impact_time(p);
  double v = ball_first_impact_speed(p);
  for (int k = 0; k < count; ++k) {
    out.push_back({t, v, p.restitution * v});
    if (p.restitution == 0.0 || v == 0.0) break;  // at rest after this impact
    // Flight time of a ballistic arc leaving the ground at e v: 2 e v / g.
    t += 2.0 * p.restitution * v / p.gravity;
    v *= p.restitution;
  }
  return out;
}

double ball_accumulation_time(const BouncingBall::Parameters& p) {
  const double t1 = ball_first_impact_time(p);
  const double v1 = ball_first_impact_speed(p);
  const double e = p.restitution;
  if (e >= 1.0) return kInf;
  // t1 + sum_{k>=1} 2 e^k V1 / g = t1 + 2 e V1 / (g (1 - e)).
  return t1 + 2.0 * e * v1 / (p.gravity * (1.0 - e));
}

double ball_energy_after(const BouncingBall::Parameters& p, int k) {
  require(k >= 0, "k", "must be >= 0");
  if (k == 0) {
    require_ball(p);
    return 0.5 * p.mass * p.velocity * p.velocity + p.mass * p.gravity * p.height;
  }
  const double v = std::pow(p.restitution, k) * ball_first_impact_speed(p);
  return 0.5 * p.mass * v * v;
}

State1 ball_state(const BouncingBall::Parameters& p, double t) {
  require(t >= 0.0 && std::isfinite(t), "t", "must be finite and >= 0");
  const double g = p.gravity;
  const double t1 = ball_first_impact_time(p);
  if (t < t1) {
    return {p.height + p.velocity * t - 0.5 * g * t * t, p.velocity - g * t};
  }
  if (t >= ball_accumulation_time(p)) return {0.0, 0.0};
  // Walk the arcs: the k-th arc starts at t_k with upward speed e V_k.
  double tk = t1;
  double v = p.restitution * ball_first_impact_speed(p);
  for (;;) {
    const double flight = 2.0 * v / g;
    if (t < tk + flight || v == 0.0) {
      const double s = t - tk;
      return {v * s - 0.5 * g * s * s, v - g * s};
    }
    tk += flight;
    v *= p.restitution;
  }
}

// =======================================================================================
// Oscillator against a rigid stop

double oscillator_impact_speed(double omega, double amplitude, double gap) {
  require(omega > 0.0, "omega", "must be > 0");
  require(amplitude >= std::abs(gap), "amplitude", "must be >= |gap| for the stop to be reached");
  // Energy: (v/w)^2 + x^2 = A^2 at x = d.
  return omega * std::sqrt(amplitude * amplitude - gap * gap);
}

double oscillator_next_amplitude(double omega, double impact_speed, double gap,
                                 double restitution) {
  require(omega > 0.0, "omega", "must be > 0");
  const double r = restitution * impact_speed / omega;
  return std::sqrt(gap * gap + r * r);
}

double oscillator_time_between_impacts(double omega, double impact_speed, double gap,
                                       double restitution) {
  require(omega > 0.0, "omega", "must be > 0");
  require(restitution >= 0.0 && restitution <= 1.0, "restitution", "must be in [0, 1]");
  // After the impact x = A' cos(phase) with phase phi = atan2(e V / w, d) (x = d,
  // v = -e V < 0); the orbit returns to x = d, moving towards the stop, at 2 pi - phi.
  const double phi = std::atan2(restitution * impact_speed / omega, gap);
  return 2.0 * (kPi - phi) / omega;
}

namespace {
void require_free_oscillator(const ImpactOscillator::Parameters& p) {
  p.validate();
  require(p.stiffness > 0.0, "stiffness", "the closed form needs k > 0");
  require(p.damping_ratio == 0.0, "damping_ratio", "the closed form needs an undamped oscillator");
  require(p.force_amplitude == 0.0, "force_amplitude", "the closed form needs no forcing");
}

// First time t >= 0 at which the free orbit from (x0, v0) reaches x = d moving towards +x;
// +infinity if it never does.
double first_arrival(double omega, double x0, double v0, double d) {
  if (x0 == d && v0 > 0.0) return 0.0;
  const double a = std::hypot(x0, v0 / omega);
  // Out of reach, or (d < 0, x0 = d, v0 = 0) at rest pressed onto the stop by the spring.
  if (a <= std::abs(d)) return kInf;
  // x = A cos(w t - psi); psi = atan2(v0/w, x0). Arrival phase theta with cos = d/A and
  // sin < 0 (velocity -A w sin > 0): theta = -acos(d/A) + 2 pi n.
  const double psi = std::atan2(v0 / omega, x0);
  const double c = std::clamp(d / a, -1.0, 1.0);
  double theta = -std::acos(c);
  double t = (theta + psi) / omega;
  while (t <= 0.0) {
    theta += 2.0 * kPi;
    t = (theta + psi) / omega;
  }
  // The orbit passes phase 2 pi n as well; the earliest positive solution is wanted.
  while (t - 2.0 * kPi / omega > 0.0) t -= 2.0 * kPi / omega;
  // Starting on the stop moving away (x0 = d, v0 < 0) the phase is at the arrival phase
  // up to round-off; the next arrival is a full period later.
  if (omega * t < kPhaseRoundOff && v0 <= 0.0) t += 2.0 * kPi / omega;
  return t;
}

State1 free_oscillator(double omega, double x0, double v0, double s) {
  const double c = std::cos(omega * s);
  const double sn = std::sin(omega * s);
  return {x0 * c + v0 / omega * sn, -x0 * omega * sn + v0 * c};
}
}  // namespace

std::vector<OscillatorImpact> oscillator_impacts(const ImpactOscillator::Parameters& p,
                                                 int count) {
  require_free_oscillator(p);
  require(count >= 0, "count", "must be >= 0");
  const double w = std::sqrt(p.stiffness / p.mass);
  const double d = p.gap;
  std::vector<OscillatorImpact> out;
  if (count == 0) return out;
  const double t1 = first_arrival(w, p.initial_position, p.initial_velocity, d);
  if (!std::isfinite(t1)) return out;
  double t = t1;
  double v = free_oscillator(w, p.initial_position, p.initial_velocity, t1).velocity;
  for (int k = 0; k < count; ++k) {
    const double a_next = oscillator_next_amplitude(w, v, d, p.restitution);
    out.push_back({t, v, p.restitution * v, a_next});
    if (p.restitution == 0.0 && d <= 0.0) break;  // the spring holds it on the stop
    if (p.restitution == 0.0) {
      // Leaves the stop from rest at x = d > 0: amplitude d, returns after 2 pi / w with
      // speed 0 (grazing); stop listing.
      break;
    }
    t += oscillator_time_between_impacts(w, v, d, p.restitution);
    // Speed at the next impact: energy amplitude A' at x = d again gives e V.
    v *= p.restitution;
    if (v == 0.0) break;
  }
  return out;
}

State1 oscillator_state(const ImpactOscillator::Parameters& p, double t) {
  require_free_oscillator(p);
  require(t >= 0.0 && std::isfinite(t), "t", "must be finite and >= 0");
  const double w = std::sqrt(p.stiffness / p.mass);
  const double d = p.gap;
  const double e = p.restitution;
  if (d < 0.0 && p.initial_position == d && p.initial_velocity == 0.0) return {d, 0.0};
  const double t1 = first_arrival(w, p.initial_position, p.initial_velocity, d);
  if (t < t1) return free_oscillator(w, p.initial_position, p.initial_velocity, t);
  double tk = t1;
  double v = free_oscillator(w, p.initial_position, p.initial_velocity, t1).velocity;
  for (int k = 0; k < kMaxOscillatorImpacts; ++k) {
    if (e * v == 0.0) {
      // Rest at the stop: for d <= 0 the spring presses the mass onto it; for d > 0 the
      // mass leaves from rest at x = d and oscillates with amplitude d (grazing the stop).
      if (d <= 0.0) return {d, 0.0};
      return free_oscillator(w, d, 0.0, t - tk);
    }
    const double dt = oscillator_time_between_impacts(w, v, d, e);
    if (t < tk + dt) return free_oscillator(w, d, -e * v, t - tk);
    tk += dt;
    v *= e;
  }
  throw std::invalid_argument("t: too many impacts before t for the closed-form reference");
}

// =======================================================================================
// Block with Coulomb friction

double block_stopping_time(double v0, double mu, double g) {
  require(mu > 0.0 && g > 0.0, "mu, g", "must be > 0 for the block to stop");
  // Constant deceleration mu g.
  return std::abs(v0) / (mu * g);
}

double block_stopping_distance(double v0, double mu, double g) {
  require(mu > 0.0 && g > 0.0, "mu, g", "must be > 0 for the block to stop");
  return v0 * v0 / (2.0 * mu * g);
}

bool block_sticks(double tangential_load, double mu, double normal_force) {
  return std::abs(tangential_load) <= mu * normal_force;
}

State1 block_state(const SlidingBlock::Parameters& p, double t) {
  p.validate();
  require(p.force_amplitude == 0.0, "force_amplitude", "the closed form needs a constant force");
  require(t >= 0.0 && std::isfinite(t), "t", "must be finite and >= 0");
  const double beta = deg2rad(p.incline_deg);
  const double normal = p.mass * p.gravity * std::cos(beta);
  const double load = p.force - p.mass * p.gravity * std::sin(beta);  // F_a
  const double fr = p.friction * normal;
  double x = 0.0;
  double v = p.initial_velocity;
  double s = t;
  if (v != 0.0) {
    const double a = (load - fr * sgn(v)) / p.mass;
    // Decelerating (a opposite to v): stops at t_s = -v/a.
    if (a * v < 0.0) {
      const double ts = -v / a;
      if (s < ts) return {v * s + 0.5 * a * s * s, v + a * s};
      x = v * ts + 0.5 * a * ts * ts;
      s -= ts;
      v = 0.0;
    } else {
      return {v * s + 0.5 * a * s * s, v + a * s};
    }
  }
  // At rest: sticks if |F_a| <= mu N, else slides in the direction of F_a.
  if (block_sticks(load, p.friction, normal)) return {x, 0.0};
  const double a = (load - fr * sgn(load)) / p.mass;
  return {x + 0.5 * a * s * s, a * s};
}

HarmonicSlip block_harmonic_first_slip(const SlidingBlock::Parameters& p) {
  p.validate();
  require(p.initial_velocity == 0.0, "initial_velocity", "the closed form starts from rest");
  require(p.force_frequency > 0.0, "force_frequency", "must be > 0 for a harmonic force");
  const double beta = deg2rad(p.incline_deg);
  const double m = p.mass;
  const double normal = m * p.gravity * std::cos(beta);
  const double fr = p.friction * normal;
  const double f0 = p.force_amplitude;
  const double c = p.force - m * p.gravity * std::sin(beta);  // constant part of F_a
  const double om = 2.0 * kPi * p.force_frequency;
  HarmonicSlip out;
  // F_a(t) = c + F0 sin(om t) ranges over [c - |F0|, c + |F0|].
  if (std::abs(c) + std::abs(f0) <= fr) return out;
  out.slips = true;
  if (std::abs(c) > fr || (std::abs(c) == fr && c * f0 > 0.0)) {
    // Already beyond static friction at t = 0, or at its limit and pushed further.
    out.start_time = 0.0;
    out.direction = sgn(c);
  } else {
    // Earliest t > 0 with c + F0 sin(om t) = +- fr. Candidates from asin on each side.
    double best = kInf;
    for (double target : {fr, -fr}) {
      const double sv = (target - c) / f0;
      if (std::abs(sv) > 1.0) continue;
      const double a0 = std::asin(sv);
      for (double ph : {a0, kPi - a0, a0 + 2.0 * kPi}) {
        if (ph > 0.0 && ph / om < best) {
          best = ph / om;
          out.direction = sgn(target);
        }
      }
    }
    // F_a(0) = c with |c| <= fr: the first crossing is the breakaway.
    out.start_time = best;
  }
  const double tb = out.start_time;
  const double dir = out.direction;
  // m v(t) = c (t - tb) + F0 (cos(om tb) - cos(om t)) / om - dir fr (t - tb), while sliding.
  auto velocity = [&](double tt) {
    return ((c - dir * fr) * (tt - tb) + f0 * (std::cos(om * tb) - std::cos(om * tt)) / om) / m;
  };
  auto position = [&](double tt) {  // integral of v from tb to tt
    const double s = tt - tb;
    return (0.5 * (c - dir * fr) * s * s +
            f0 * (std::cos(om * tb) * s - (std::sin(om * tt) - std::sin(om * tb)) / om) / om) /
           m;
  };
  // Find the first return of dir * v to zero: scan by a small fraction of the period, then
  // bisect. If the slip never ends (|c| > fr drives it forever), report +infinity.
  const double period = 2.0 * kPi / om;
  const double dt = period / 2000.0;
  double lo = tb;
  double hi = tb + dt;
  const double horizon = tb + 1000.0 * period;
  while (hi < horizon && dir * velocity(hi) > 0.0) {
    lo = hi;
    hi += dt;
  }
  if (hi >= horizon) {
    out.end_time = kInf;
    out.displacement = kInf * dir;
    return out;
  }
  while (hi - lo > kBisectionWidth * std::max(1.0, hi)) {
    const double mid = 0.5 * (lo + hi);
    (dir * velocity(mid) > 0.0 ? lo : hi) = mid;
  }
  out.end_time = 0.5 * (lo + hi);
  out.displacement = position(out.end_time);
  return out;
}

void FrictionOscillator::validate() const {
  require(std::isfinite(omega) && omega > 0.0, "omega", "must be > 0");
  require(std::isfinite(friction) && friction >= 0.0, "friction", "must be >= 0");
  require(std::isfinite(gravity) && gravity >= 0.0, "gravity", "must be >= 0");
  require(std::isfinite(initial_position), "initial_position", "must be finite");
}

std::vector<double> friction_oscillator_turning_points(const FrictionOscillator& p) {
  p.validate();
  const double delta = p.friction * p.gravity / (p.omega * p.omega);
  std::vector<double> x{p.initial_position};
  require(delta > 0.0 || p.initial_position == 0.0,
          "friction", "must be > 0 for the oscillation to stop");
  while (std::abs(x.back()) > delta) {
    const double xn = x.back();
    x.push_back(sgn(xn) * (2.0 * delta - std::abs(xn)));
  }
  return x;
}

State1 friction_oscillator_state(const FrictionOscillator& p, double t) {
  require(t >= 0.0 && std::isfinite(t), "t", "must be finite and >= 0");
  const auto x = friction_oscillator_turning_points(p);
  const double w = p.omega;
  const double delta = p.friction * p.gravity / (w * w);
  const double half = kPi / w;
  const auto n = static_cast<std::size_t>(std::floor(t / half));
  if (n + 1 >= x.size()) return {x.back(), 0.0};
  // Half cycle n: harmonic about c = sgn(x_n) delta from rest at x_n.
  const double c = sgn(x[n]) * delta;
  const double s = t - static_cast<double>(n) * half;
  return {c + (x[n] - c) * std::cos(w * s), -(x[n] - c) * w * std::sin(w * s)};
}

}  // namespace nsb::models::analytic
