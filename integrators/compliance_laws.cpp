// The contact laws of the compliance method (compliance.hpp): eq. (9)'s damping factor chi
// from the coefficient of restitution under each damping law, the Hertz-damp normal force
// and the regularized Coulomb friction of eq. (10).
#include "integrators/compliance.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace nsb::integrators {

std::string_view to_string(DampingLaw law) {
  return config::name_of(kDampingLawNames, law);
}

const std::vector<std::string>& damping_law_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const auto& n : kDampingLawNames) v.emplace_back(n.name);
    return v;
  }();
  return names;
}

DampingLaw parse_damping_law(std::string_view name) {
  if (const auto law = config::value_of(kDampingLawNames, name)) return *law;
  throw std::invalid_argument("damping_law: '" + std::string(name) +
                              "' is not one of hertzdamp, flores, hunt_crossley_exact");
}

double hunt_crossley_restitution(double chi) {
  if (!(chi >= 0.0) || !std::isfinite(chi)) {
    throw std::invalid_argument("hunt_crossley_restitution: chi must be finite and >= 0");
  }
  if (chi == 0.0) return 1.0;
  // psi(e) = 1 - chi e - (1 + chi) exp(-chi (1 + e)) is > 0 at e = 0 and < 0 at
  // e = min(1, 1/chi) (docs/compliance.md); its root there is the restitution.
  const auto psi = [chi](double e) { return 1.0 - chi * e - (1.0 + chi) * std::exp(-chi * (1.0 + e)); };
  double lo = 0.0, hi = std::min(1.0, 1.0 / chi);
  for (int it = 0; it < 200 && hi - lo > 1e-16; ++it) {
    const double mid = 0.5 * (lo + hi);
    (psi(mid) > 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double damping_factor(DampingLaw law, double restitution) {
  if (!(restitution >= 0.0 && restitution <= 1.0)) {
    throw std::invalid_argument("damping_factor: restitution must be in [0, 1]");
  }
  const double e = std::max(restitution, kMinLawRestitution);
  switch (law) {
    case DampingLaw::kHertzDamp: return 0.75 * (1.0 - restitution * restitution);
    case DampingLaw::kFlores: return 8.0 * (1.0 - e) / (5.0 * e);
    case DampingLaw::kHuntCrossleyExact: {
      if (e >= 1.0) return 0.0;
      // Invert hunt_crossley_restitution: e(chi) decreases from 1 (chi = 0) towards 0, and
      // e(chi) < 1/chi, so the root lies in (0, 1/e]. Bisection in log(chi) (the range
      // spans decades).
      double lo = 1e-12, hi = 1.0 / e;
      for (int it = 0; it < 200 && hi / lo - 1.0 > 1e-15; ++it) {
        const double mid = std::sqrt(lo * hi);
        (hunt_crossley_restitution(mid) > e ? lo : hi) = mid;
      }
      return std::sqrt(lo * hi);
    }
  }
  return 0.0;
}

NormalForce hertz_damp_force(double k, double chi, double v_minus, double delta,
                             double delta_rate) {
  NormalForce r;
  if (!(delta > 0.0)) return r;
  const double root = std::sqrt(delta);
  const double spring = k * delta * root;             // k delta^1.5
  const double factor = 1.0 + chi * delta_rate / v_minus;
  const double force = spring * factor;
  if (force <= 0.0) return r;  // no adhesion: the dashpot cannot pull
  r.force = force;
  r.d_penetration = 1.5 * k * root * factor;
  r.d_rate = spring * chi / v_minus;
  return r;
}

TangentForce regularized_coulomb(double mu, double lambda_n, double slip_rate, double eps_v) {
  TangentForce r;
  const double x = slip_rate / eps_v;
  const double sat = std::clamp(x, -1.0, 1.0);
  r.force = -mu * lambda_n * sat;
  r.d_normal = -mu * sat;
  r.d_slip = (std::abs(x) < 1.0) ? -mu * lambda_n / eps_v : 0.0;
  return r;
}

}  // namespace nsb::integrators
