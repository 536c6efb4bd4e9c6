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
           "initial penetration: initial_position (" + config::format_value(p.initial_position) +
               " m) must be <= gap (" + config::format_value(p.gap) + " m)");
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

BridgeScene build_rigid_deck(Section& m) {
  m.only(model_keys(rigid_deck_fields()));
  BridgeDesign p = BridgeDesign::free_deck();
  m.read_all(rigid_deck_fields(), p);
  // A free deck has no benchmark to take its size from.
  for (const char* k : {"mass", "inertia", "length", "width"}) {
    if (!m.has(k)) m.fail_table(std::string("missing key ") + k + " (required for rigid_deck)");
  }
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
