// The simple systems and the free rigid deck of scene files: their [model] keys read by field
// (scene/scene_schema.hpp), the conditions between keys checked here, the rest by the models'
// own validate().
#include "scene/scene_builders.hpp"

#include "models/assembly.hpp"
#include "models/bridge_fields.hpp"
#include "models/bridge_parts.hpp"
#include "models/simple_systems.hpp"
#include "scene/scene_schema.hpp"

namespace nsb::scene {

using namespace models;  // the systems and parts a scene builds

namespace {

// The [model] keys of a simple system: kind and its fields.
template <class P>
std::vector<std::string_view> model_keys(std::span<const config::Field<P>> fields) {
  std::vector<std::string_view> keys{"kind"};
  for (const auto& k : keys_of(fields)) keys.push_back(k);
  return keys;
}

// Reads the parameters P of a model M from the [model] table and builds M; a model's own
// validation error is reported at the key it names.
template <class M, class P>
std::unique_ptr<integrators::System> build(Section& m, std::span<const config::Field<P>> fields,
                                           void (*check)(const Section&, const P&) = nullptr) {
  m.only(model_keys(fields));
  P p;
  m.read_all(fields, p);
  if (check != nullptr) check(m, p);
  try {
    return std::make_unique<M>(p);
  } catch (const std::invalid_argument& e) {
    m.rethrow(e);
  }
}

// The oscillator starts at or before its stop.
void check_oscillator(const Section& m, const ImpactOscillator::Parameters& p) {
  if (p.initial_position > p.gap) {
    m.fail(m.has("initial_position") ? "initial_position" : "gap",
           "initial penetration: " + m.key_path("initial_position") + " (" +
               six_digits(p.initial_position) + " m) must be <= " + m.key_path("gap") + " (" +
               six_digits(p.gap) + " m)");
  }
}

}  // namespace

std::unique_ptr<integrators::System> build_simple_system(const std::string& kind, Section& m) {
  if (kind == "bouncing_ball") return build<BouncingBall>(m, bouncing_ball_fields());
  if (kind == "impact_oscillator") {
    return build<ImpactOscillator>(m, impact_oscillator_fields(), &check_oscillator);
  }
  return build<SlidingBlock>(m, sliding_block_fields());
}

void check_body(const Section& s, double mass, double inertia, double length, double width) {
  const double area = length * width;
  const double density = mass / area;
  const std::string plan = six_digits(length) + " m x " + six_digits(width) + " m";
  if (!(density >= 1e-6 && density <= 100.0)) {
    const std::string key = s.has("mass") || !s.has("length") ? "mass" : "length";
    std::string what = "mass " + six_digits(mass) + " t over a plan of " + plan + " is " +
                       derived(density) +
                       " t/m^2; expected 1e-06 to 100 t/m^2 (a concrete deck weighs 1 to 2 "
                       "t/m^2)";
    if (density > 100.0 && density / 1000.0 <= 100.0) {
      what += "; a mass in kg? " + six_digits(mass) + " kg is " + six_digits(mass / 1000.0) + " t";
    }
    s.fail(key, what);
  }
  const double uniform = mass * (length * length + width * width) / 12.0;
  const double ratio = inertia / uniform;
  if (!(ratio >= 1e-6 && ratio <= 100.0)) {
    std::string what = "inertia " + six_digits(inertia) + " t m^2 is " + derived(ratio) +
                       " times that of the mass " + six_digits(mass) + " t spread over " + plan +
                       " (m (L^2 + W^2) / 12 = " + derived(uniform) +
                       " t m^2); expected 1e-06 to 100 times";
    if (ratio > 100.0 && ratio / 1000.0 <= 100.0) {
      what += "; an inertia in kg m^2? " + six_digits(inertia) + " kg m^2 is " +
              six_digits(inertia / 1000.0) + " t m^2";
    }
    s.fail(s.has("inertia") ? "inertia" : "mass", what);
  }
}

BridgeScene build_rigid_deck(Section& m) {
  m.only(model_keys(rigid_deck_fields()));
  BridgeDesign p = BridgeDesign::free_deck();
  m.read_all(rigid_deck_fields(), p);
  // A free deck has no benchmark to take its size from.
  for (const char* k : {"mass", "inertia", "length", "width"}) {
    if (!m.has(k)) m.fail_table(std::string("missing key ") + k + " (required for rigid_deck)");
  }
  check_body(m, p.mass, p.inertia, p.deck.length, p.deck.width);
  BridgeScene out;
  try {
    out.system = std::make_unique<Assembly>(bridge_parts(p));
  } catch (const std::invalid_argument& e) {
    m.rethrow(e);
  }
  out.design = std::move(p);
  return out;
}

}  // namespace nsb::scene
