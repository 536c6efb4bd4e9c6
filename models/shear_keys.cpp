#include "models/shear_keys.hpp"
#include "models/field_checks.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace nsb::models {

namespace {

// One key: corner `corner` of body `body` against a face of seat `seat` on side s = +-1.
void add_key(Assembly::Parts& parts, const ShearKeyParameters& keys, int body, int corner,
             int seat, double side, const std::string& name) {
  const parts::RigidBody& b = parts.bodies[static_cast<std::size_t>(body)];
  const Eigen::Vector2d at_rest = b.rest.head<2>() + b.corner(corner);
  const Eigen::Vector2d reference = parts.prescribed[static_cast<std::size_t>(seat)].reference;
  const Eigen::Vector2d point(at_rest.x(), side * (0.5 * b.width + keys.gap));
  parts.shear_keys.push_back({.contact = static_cast<int>(parts.contacts.size()), .name = name,
                              .capacity = keys.capacity});
  parts.contacts.push_back({.body = body, .corner = corner, .obstacle = parts::Obstacle::kPrescribed,
                            .obstacle_index = seat,
                            .face = {.point = point - reference,
                                     .normal = Eigen::Vector2d(0.0, -side)},
                            .restitution = keys.restitution, .friction = keys.friction,
                            .stiffness = keys.compliance_stiffness,
                            .family = "shear_key", .name = name});
}

}  // namespace

void ShearKeyParameters::validate(const std::string& prefix) const {
  require(std::isfinite(gap) && gap >= 0.0, prefix + "gap", "must be >= 0 [m]");
  require(restitution >= 0.0 && restitution <= 1.0, prefix + "restitution",
          "must be in [0, 1]");
  require(std::isfinite(friction) && friction >= 0.0, prefix + "friction", "must be >= 0");
  require(std::isfinite(compliance_stiffness) && compliance_stiffness >= 0.0,
          prefix + "compliance_stiffness", "must be >= 0 [kN/m^1.5] (0: solver.contact_stiffness)");
  require(std::isfinite(capacity) && capacity >= 0.0, prefix + "capacity",
          "must be >= 0 [kN] (0: unbreakable)");
}

void add_shear_keys(Assembly::Parts& parts, const ShearKeyParameters& keys,
                    std::size_t deck_bodies) {
  keys.validate("shear_keys.");
  require(!parts.bodies.empty() && parts.prescribed.size() >= 2, "shear_keys",
          "need a deck and the two abutment seats (prescribed bodies 0 and 1)");
  const std::size_t deck = deck_bodies > 0 ? deck_bodies : parts.bodies.size();
  require(deck <= parts.bodies.size(), "shear_keys", "more deck bodies than bodies");
  const int last = static_cast<int>(deck) - 1;
  add_key(parts, keys, 0, 0, 0, 1.0, "shear_key_left_plus");
  add_key(parts, keys, 0, 1, 0, -1.0, "shear_key_left_minus");
  add_key(parts, keys, last, 2, 1, 1.0, "shear_key_right_plus");
  add_key(parts, keys, last, 3, 1, -1.0, "shear_key_right_minus");
}

void Assembly::build_keys() {
  for (std::size_t k = 0; k < parts_.shear_keys.size(); ++k) {
    const parts::ShearKey& key = parts_.shear_keys[k];
    const std::string prefix = "shear_keys[" + std::to_string(k) + "].";
    require(key.contact >= 0 && key.contact < contacts(), prefix + "contact",
            "must name one of the contacts");
    require(std::isfinite(key.capacity) && key.capacity >= 0.0, prefix + "capacity",
            "must be >= 0 [kN] (0: unbreakable)");
    keys_.push_back({.slot = static_cast<std::size_t>(key.contact), .capacity = key.capacity});
  }
}

// The step's mean force of each key, normal impulse / h: a key with a capacity breaks at the
// first step where it exceeds it. Under Moreau–Jean an impact's impulse over one step gives a
// mean force that grows as 1/h, so as h shrinks every impact on a key breaks it; event-driven
// delivers an impact's impulse at an instant (step.impact_impulse), and a key that receives
// one breaks at once, the limit of Moreau–Jean's rule (docs/bridge.md, "Shear keys"). Its
// peak is then infinite (margin -infinity).
integrators::StepVerdict Assembly::watch_keys(const integrators::AcceptedStep& step) {
  auto verdict = integrators::StepVerdict::kContinue;
  for (KeyState& k : keys_) {
    if (k.broken) continue;
    const auto slot = static_cast<Eigen::Index>(k.slot);
    const bool percussion =
        step.impact_impulse != nullptr && (*step.impact_impulse)[slot] > 0.0;
    const double force = percussion ? std::numeric_limits<double>::infinity()
                                    : (*step.normal_impulse)[slot] / step.h;
    k.peak = std::max(k.peak, force);
    if (k.capacity > 0.0 && force > k.capacity) {
      k.broken = true;
      k.time = step.t;
      verdict = integrators::StepVerdict::kContactsRemoved;
    }
  }
  return verdict;
}

std::vector<integrators::LimitStateValue> Assembly::key_limit_states() const {
  std::vector<integrators::LimitStateValue> out;
  for (std::size_t k = 0; k < keys_.size(); ++k) {
    const KeyState& s = keys_[k];
    integrators::LimitStateValue v;
    v.name = parts_.shear_keys[k].name;
    v.unit = "kN";
    v.exceeded = s.broken;
    v.time = s.time;
    // An unbreakable key has no margin: NaN, as a limit state that is not watched.
    if (s.capacity > 0.0) v.margin = s.capacity - s.peak;
    v.removes_contact = static_cast<int>(s.slot) + 1;
    out.push_back(v);
  }
  return out;
}

std::span<const config::Field<ShearKeyParameters>> shear_key_fields() {
  namespace c = config;
  using K = ShearKeyParameters;
  static const c::Field<K> f[] = {
      c::number<&K::gap>("gap", "m", c::non_negative(),
                         "clear transverse gap between the deck's side and each key at rest"),
      c::number<&K::restitution>("restitution", "-", c::closed(0, 1),
                                 "Newton's coefficient e of the key contacts"),
      c::number<&K::friction>("friction", "-", c::non_negative(),
                              "Coulomb's coefficient mu of the key contacts"),
      c::number<&K::capacity>("capacity", "kN", c::non_negative(),
                              "mean contact force of a step that breaks a key; 0: unbreakable"),
      c::number<&K::compliance_stiffness>("compliance_stiffness", "kN/m^1.5", c::non_negative(),
                                          "Hertz k of eq. (9) for the key contacts under the "
                                          "compliance method; 0: the default, "
                                          "solver.contact_stiffness scaled to the deck's mass "
                                          "(solver.reference_mass)"),
  };
  return f;
}

}  // namespace nsb::models
