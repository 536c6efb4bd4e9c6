// Closed-form references; see analytic.hpp for the formulas and docs/analytic.md for the
// derivations.
#include "models/analytic.hpp"

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

// Relative tolerance of the feasibility tests in the case enumeration: the linear systems
// are of size <= 8 and well scaled (G ~ 1/m), so a solution is accurate to a few ulps of
// the data; 1e-10 separates round-off from a genuinely violated sign condition.
constexpr double kCaseTolerance = 1e-10;
// Two case solutions are the same solution when their post-impact contact velocities agree
// to this relative accuracy (cases sharing a boundary, e.g. stick with gdot_T+ = 0 and
// slide, coincide).
constexpr double kSameSolution = 1e-8;
// Bisection on the closed-form slip velocity stops at this relative width of the bracket
// (near double precision; the function is smooth and cheap).
constexpr double kBisectionWidth = 1e-14;
// Phases (w t) below this are round-off of a zero phase in first_arrival.
constexpr double kPhaseRoundOff = 1e-9;
// Safety cap on impacts generated when stepping the oscillator to a time t.
constexpr int kMaxOscillatorImpacts = 1000000;

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

double deg2rad(double d) { return d * kPi / 180.0; }
double sgn(double x) { return (x > 0.0) - (x < 0.0); }

}  // namespace

// =======================================================================================
// Bouncing ball

namespace {
// The ball references need g > 0 (with g = 0 a ball never returns after its first rebound).
void require_ball(const BouncingBall::Parameters& p) {
  p.validate();
  require(p.gravity > 0.0, "gravity: the closed form needs g > 0");
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
  require(count >= 0, "count: must be >= 0");
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
  require(k >= 0, "k: must be >= 0");
  if (k == 0) {
    require_ball(p);
    return 0.5 * p.mass * p.velocity * p.velocity + p.mass * p.gravity * p.height;
  }
  const double v = std::pow(p.restitution, k) * ball_first_impact_speed(p);
  return 0.5 * p.mass * v * v;
}

State1 ball_state(const BouncingBall::Parameters& p, double t) {
  require(t >= 0.0 && std::isfinite(t), "t: must be finite and >= 0");
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
  require(omega > 0.0, "omega: must be > 0");
  require(amplitude >= std::abs(gap), "amplitude: must be >= |gap| for the stop to be reached");
  // Energy: (v/w)^2 + x^2 = A^2 at x = d.
  return omega * std::sqrt(amplitude * amplitude - gap * gap);
}

double oscillator_next_amplitude(double omega, double impact_speed, double gap,
                                 double restitution) {
  require(omega > 0.0, "omega: must be > 0");
  const double r = restitution * impact_speed / omega;
  return std::sqrt(gap * gap + r * r);
}

double oscillator_time_between_impacts(double omega, double impact_speed, double gap,
                                       double restitution) {
  require(omega > 0.0, "omega: must be > 0");
  require(restitution >= 0.0 && restitution <= 1.0, "restitution: must be in [0, 1]");
  // After the impact x = A' cos(phase) with phase phi = atan2(e V / w, d) (x = d,
  // v = -e V < 0); the orbit returns to x = d, moving towards the stop, at 2 pi - phi.
  const double phi = std::atan2(restitution * impact_speed / omega, gap);
  return 2.0 * (kPi - phi) / omega;
}

namespace {
void require_free_oscillator(const ImpactOscillator::Parameters& p) {
  p.validate();
  require(p.stiffness > 0.0, "stiffness: the closed form needs k > 0");
  require(p.damping_ratio == 0.0, "damping_ratio: the closed form needs an undamped oscillator");
  require(p.force_amplitude == 0.0, "force_amplitude: the closed form needs no forcing");
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
  require(count >= 0, "count: must be >= 0");
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
  require(t >= 0.0 && std::isfinite(t), "t: must be finite and >= 0");
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
  require(mu > 0.0 && g > 0.0, "mu, g: must be > 0 for the block to stop");
  // Constant deceleration mu g.
  return std::abs(v0) / (mu * g);
}

double block_stopping_distance(double v0, double mu, double g) {
  require(mu > 0.0 && g > 0.0, "mu, g: must be > 0 for the block to stop");
  return v0 * v0 / (2.0 * mu * g);
}

bool block_sticks(double tangential_load, double mu, double normal_force) {
  return std::abs(tangential_load) <= mu * normal_force;
}

State1 block_state(const SlidingBlock::Parameters& p, double t) {
  p.validate();
  require(p.force_amplitude == 0.0, "force_amplitude: the closed form needs a constant force");
  require(t >= 0.0 && std::isfinite(t), "t: must be finite and >= 0");
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
  require(p.initial_velocity == 0.0, "initial_velocity: the closed form starts from rest");
  require(p.force_frequency > 0.0, "force_frequency: must be > 0 for a harmonic force");
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
  require(std::isfinite(omega) && omega > 0.0, "omega: must be > 0");
  require(std::isfinite(friction) && friction >= 0.0, "friction: must be >= 0");
  require(std::isfinite(gravity) && gravity >= 0.0, "gravity: must be >= 0");
  require(std::isfinite(initial_position), "initial_position: must be finite");
}

std::vector<double> friction_oscillator_turning_points(const FrictionOscillator& p) {
  p.validate();
  const double delta = p.friction * p.gravity / (p.omega * p.omega);
  std::vector<double> x{p.initial_position};
  require(delta > 0.0 || p.initial_position == 0.0,
          "friction: must be > 0 for the oscillation to stop");
  while (std::abs(x.back()) > delta) {
    const double xn = x.back();
    x.push_back(sgn(xn) * (2.0 * delta - std::abs(xn)));
  }
  return x;
}

State1 friction_oscillator_state(const FrictionOscillator& p, double t) {
  require(t >= 0.0 && std::isfinite(t), "t: must be finite and >= 0");
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

// =======================================================================================
// Deck impact

void DeckBody::validate() const {
  require(std::isfinite(mass) && mass > 0.0, "mass: must be > 0 [t]");
  require(std::isfinite(inertia) && inertia > 0.0, "inertia: must be > 0 [t m^2]");
  deck.validate();
}

Eigen::Vector2d deck_corner(const DeckGeometry& g, int corner) {
  g.validate();
  require(corner >= 1 && corner <= 4, "corner: must be 1, 2, 3 or 4");
  return g.corner(corner - 1);
}

ContactColumns deck_contact_columns(const DeckGeometry& g, int corner) {
  const Eigen::Vector2d r = deck_corner(g, corner);
  // Unit normal of the abutment face, pointing from the abutment to the deck.
  const Eigen::Vector2d n = g.face_normal(corner - 1);
  const Eigen::Vector2d t(-n.y(), n.x());  // n rotated by +90 degrees
  auto cross = [&](const Eigen::Vector2d& v) { return r.x() * v.y() - r.y() * v.x(); };
  return {Eigen::Vector3d(n.x(), n.y(), cross(n)), Eigen::Vector3d(t.x(), t.y(), cross(t))};
}

void ImpactProblem::validate() const {
  const auto m = restitution.size();
  require(m >= 1 && m <= 4, "restitution: 1 to 4 contacts are supported");
  require(friction.size() == m, "friction: size must equal the number of contacts");
  require(gdot_minus.size() == 2 * m, "gdot_minus: size must be 2m");
  require(delassus.rows() == 2 * m && delassus.cols() == 2 * m, "delassus: must be 2m x 2m");
  require(delassus.allFinite() && gdot_minus.allFinite(), "delassus, gdot_minus: must be finite");
  for (Eigen::Index i = 0; i < m; ++i) {
    require(restitution(i) >= 0.0 && restitution(i) <= 1.0, "restitution: must be in [0, 1]");
    require(std::isfinite(friction(i)) && friction(i) >= 0.0, "friction: must be >= 0");
  }
}

ImpactCases solve_impact_by_cases(const ImpactProblem& p) {
  p.validate();
  const auto m = p.restitution.size();
  const Eigen::Index n2 = 2 * m;
  const double vscale = 1.0 + p.gdot_minus.cwiseAbs().maxCoeff();
  const double gscale = p.delassus.cwiseAbs().maxCoeff();
  require(gscale > 0.0, "delassus: must not be zero");
  const double vtol = kCaseTolerance * vscale;
  const double itol = vtol / gscale;  // impulse tolerance
  ImpactCases out;
  int total = 1;
  for (Eigen::Index i = 0; i < m; ++i) total *= 4;
  Eigen::MatrixXd A(n2, n2);
  Eigen::VectorXd b(n2);
  std::vector<ImpactCase> st(static_cast<std::size_t>(m));
  for (int code = 0; code < total; ++code) {
    int c = code;
    bool skip = false;
    for (Eigen::Index i = 0; i < m; ++i) {
      st[static_cast<std::size_t>(i)] = static_cast<ImpactCase>(c % 4);
      c /= 4;
      // Without friction stick and slide coincide (Lambda_T = 0): keep one of them.
      if (p.friction(i) == 0.0 && (st[static_cast<std::size_t>(i)] == ImpactCase::kStick ||
                                   st[static_cast<std::size_t>(i)] ==
                                       ImpactCase::kSlideNegative)) {
        skip = true;
      }
    }
    if (skip) continue;
    A.setZero();
    b.setZero();
    // Unknowns z = [Lambda_N; Lambda_T]; rows i (normal) and m + i (tangential).
    for (Eigen::Index i = 0; i < m; ++i) {
      const double e = p.restitution(i);
      const double mu = p.friction(i);
      switch (st[static_cast<std::size_t>(i)]) {
        case ImpactCase::kInactive:
          A(i, i) = 1.0;          // Lambda_N = 0
          A(m + i, m + i) = 1.0;  // Lambda_T = 0
          break;
        case ImpactCase::kStick:
          // gdot_N+ + e gdot_N- = 0 and gdot_T+ = 0, gdot+ = G z + gdot-.
          A.row(i) = p.delassus.row(i);
          b(i) = -(1.0 + e) * p.gdot_minus(i);
          A.row(m + i) = p.delassus.row(m + i);
          b(m + i) = -p.gdot_minus(m + i);
          break;
        case ImpactCase::kSlidePositive:
        case ImpactCase::kSlideNegative: {
          const double s = st[static_cast<std::size_t>(i)] == ImpactCase::kSlidePositive ? 1.0
                                                                                        : -1.0;
          A.row(i) = p.delassus.row(i);
          b(i) = -(1.0 + e) * p.gdot_minus(i);
          A(m + i, m + i) = 1.0;  // Lambda_T + s mu Lambda_N = 0
          A(m + i, i) = s * mu;
          break;
        }
      }
    }
    Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
    Eigen::VectorXd z;
    if (lu.isInvertible()) {
      z = lu.solve(b);
    } else {
      // Singular case (e.g. two corners of one end share W_T, so their tangential impulses
      // split indeterminately): take the minimum-norm solution if the system is consistent.
      ++out.singular_cases;
      z = A.completeOrthogonalDecomposition().solve(b);
      if ((A * z - b).cwiseAbs().maxCoeff() > vtol) continue;
    }
    const Eigen::VectorXd gp = p.delassus * z + p.gdot_minus;
    bool ok = z.allFinite();
    for (Eigen::Index i = 0; i < m && ok; ++i) {
      const double ln = z(i), lt = z(m + i);
      const double e = p.restitution(i), mu = p.friction(i);
      const double gn0 = gp(i) + e * p.gdot_minus(i);
      switch (st[static_cast<std::size_t>(i)]) {
        case ImpactCase::kInactive:
          ok = gn0 >= -vtol;
          break;
        case ImpactCase::kStick:
          ok = ln >= -itol && std::abs(lt) <= mu * ln + itol;
          break;
        case ImpactCase::kSlidePositive:
          ok = ln >= -itol && (mu == 0.0 || gp(m + i) >= -vtol);
          break;
        case ImpactCase::kSlideNegative:
          ok = ln >= -itol && gp(m + i) <= vtol;
          break;
      }
    }
    if (!ok) continue;
    ImpactSolution s;
    s.lambda_n = z.head(m);
    s.lambda_t = z.tail(m);
    s.gdot_n_plus = gp.head(m);
    s.gdot_t_plus = gp.tail(m);
    s.cases = st;
    // Distinct solutions are distinct post-impact velocities: G z1 = G z2 <=> W z1 = W z2
    // (G = W^T M^-1 W), so equal contact velocities mean equal u+ even when the impulses
    // differ (an indeterminate split between contacts).
    const bool seen = std::any_of(out.solutions.begin(), out.solutions.end(), [&](const auto& o) {
      return (o.gdot_n_plus - s.gdot_n_plus).cwiseAbs().maxCoeff() <= kSameSolution * vscale &&
             (o.gdot_t_plus - s.gdot_t_plus).cwiseAbs().maxCoeff() <= kSameSolution * vscale;
    });
    if (!seen) out.solutions.push_back(std::move(s));
  }
  return out;
}

DeckImpact deck_impact(const DeckBody& g, const std::vector<int>& corners,
                       const Eigen::Vector3d& velocity_before, double restitution,
                       double friction) {
  g.validate();
  require(!corners.empty() && corners.size() <= 4, "corners: give 1 to 4 corners");
  require(velocity_before.allFinite(), "velocity_before: must be finite");
  const auto m = static_cast<Eigen::Index>(corners.size());
  Eigen::MatrixXd W(3, 2 * m);  // [W_N W_T]
  for (Eigen::Index i = 0; i < m; ++i) {
    const auto cc = deck_contact_columns(g.deck, corners[static_cast<std::size_t>(i)]);
    W.col(i) = cc.w_normal;
    W.col(m + i) = cc.w_tangent;
  }
  const Eigen::Vector3d minv(1.0 / g.mass, 1.0 / g.mass, 1.0 / g.inertia);
  DeckImpact out;
  out.problem.delassus = W.transpose() * minv.asDiagonal() * W;  // eq. (8)
  out.problem.gdot_minus = W.transpose() * velocity_before;
  out.problem.restitution = Eigen::VectorXd::Constant(m, restitution);
  out.problem.friction = Eigen::VectorXd::Constant(m, friction);
  const ImpactCases cases = solve_impact_by_cases(out.problem);
  out.solutions = static_cast<int>(cases.solutions.size());
  if (cases.solutions.empty()) {
    out.velocity_after = velocity_before;
    return out;
  }
  out.contact = cases.solutions.front();
  Eigen::VectorXd z(2 * m);
  z << out.contact.lambda_n, out.contact.lambda_t;
  out.velocity_after = velocity_before + minv.asDiagonal() * (W * z);
  return out;
}

}  // namespace nsb::models::analytic
