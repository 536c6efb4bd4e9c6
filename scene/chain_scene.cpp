// The deck bodies and joints of a scene ([[model.segments]] and [[model.hinges]] of a bridge,
// [[model.decks]] and [[model.joints]] of a deck chain) and the deck chain of [model]
// kind = "deck_chain" (models/deck_chain.hpp, docs/bridge.md "Bridges in parts").
#include "scene/scene_builders.hpp"

#include "models/assembly.hpp"
#include "models/bridge_fields.hpp"
#include "models/deck_chain.hpp"
#include "scene/scene_schema.hpp"

#include <optional>

namespace nsb::scene {

using namespace models;  // the systems and parts a scene builds

namespace {

// The element `i` of the array of tables `key` of m, as a section restricted to fields.
template <class S>
Section element(const Section& m, const toml::array& a, std::string_view key, std::size_t i,
                std::span<const config::Field<S>> fields,
                const std::vector<std::string_view>& extra = {}) {
  const toml::table* t = a[i].as_table();
  Section s(m.context(), *t, m.key_path(key) + "[" + std::to_string(i) + "]");
  std::vector<std::string_view> keys = keys_of(fields);
  keys.insert(keys.end(), extra.begin(), extra.end());
  s.only(keys);
  return s;
}

}  // namespace

std::vector<parts::RigidBody> read_bodies(const Section& m, std::string_view key) {
  const toml::array* a = m.array_of_tables(key);
  if (a == nullptr || a->empty()) {
    m.fail_table("missing [[" + m.key_path(key) + "]] (at least one deck body)");
  }
  std::vector<parts::RigidBody> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const Section s = element(m, *a, key, i, segment_fields());
    parts::RigidBody b;
    s.read_all(segment_fields(), b);
    for (const char* required : {"mass", "inertia", "length", "width"}) {
      if (!s.has(required)) s.fail_table(std::string("missing key ") + required);
    }
    check_body(s, b.mass, b.inertia, b.length, b.width);
    out.push_back(b);
  }
  return out;
}

std::vector<DeckChain::Joint> read_joints(const Section& m, std::string_view key,
                                          std::size_t count, const std::string& rule,
                                          const std::vector<std::string_view>& extra) {
  const toml::array* a = m.array_of_tables(key);
  const std::size_t given = a == nullptr ? 0 : a->size();
  if (given != count) {
    const std::string what = "needs " + std::to_string(count) + " [[" + m.key_path(key) +
                             "]] (" + rule + "), got " + std::to_string(given);
    if (a == nullptr) m.fail_table(what);
    m.fail(key, what);
  }
  std::vector<DeckChain::Joint> out;
  for (std::size_t i = 0; i < given; ++i) {
    const Section s = element(m, *a, key, i, joint_fields(), extra);
    DeckChain::Joint j;
    s.read_all(joint_fields(), j);
    if (!s.has("gap")) s.fail_table("missing key gap (clear distance along the axis [m])");
    out.push_back(j);
  }
  return out;
}

std::unique_ptr<integrators::System> build_deck_chain(Section& m) {
  m.only({"kind", "skew_deg", "decks", "joints"});
  LayoutSettings layout;
  m.read_all(LayoutSettings::fields(), layout);
  const std::vector<parts::RigidBody> bodies = read_bodies(m, "decks");
  DeckChain::Parameters p;
  p.skew_deg = layout.skew_deg;
  p.width = bodies[0].width;
  for (const auto& b : bodies) {
    p.decks.push_back({.mass = b.mass, .inertia = b.inertia, .length = b.length,
                       .width = b.width, .initial_displacement = b.initial_position,
                       .initial_velocity = b.initial_velocity});
  }
  p.joints = read_joints(m, "joints", bodies.size() + 1,
                         "one per deck plus one: left abutment, hinges, right abutment");
  try {
    // The coordinates of the outputs: each deck's displacement from its rest position.
    Assembly::Parts parts = DeckChain::parts(p);
    for (std::size_t i = 0; i < parts.bodies.size(); ++i) {
      parts.bodies[i].rest = Eigen::Vector3d(DeckChain::rest_position(p, static_cast<int>(i)),
                                             0.0, 0.0);
      parts.bodies[i].initial_position = p.decks[i].initial_displacement;
    }
    return std::make_unique<Assembly>(std::move(parts));
  } catch (const std::invalid_argument& e) {
    rethrow_penetration(m, "decks", "joints", e);
    m.rethrow(e);
  }
}

void rethrow_penetration(const Section& m, std::string_view bodies, std::string_view joints,
                         const std::invalid_argument& e) {
  const std::string what = e.what();
  if (what.find("initial penetration") == std::string::npos) return;
  // The inputs that set the initial gaps: the bodies' initial positions and the joints' gaps
  // given in the scene; the message is reported at the first initial position given.
  std::optional<Section> first;
  std::string inputs;
  const auto collect = [&](std::string_view list, std::string_view key, bool report) {
    const toml::array* a = m.array_of_tables(list);
    for (std::size_t i = 0; a != nullptr && i < a->size(); ++i) {
      const toml::table* t = (*a)[i].as_table();
      if (t == nullptr || t->get(key) == nullptr) continue;
      Section s(m.context(), *t, m.key_path(list) + "[" + std::to_string(i) + "]");
      inputs += (inputs.empty() ? "" : ", ") + s.key_path(key);
      if (report && !first) first.emplace(s);
    }
  };
  collect(bodies, "initial_position", true);
  collect(joints, "gap", false);
  if (!first) return;
  first->fail("initial_position", what + " (set by " + inputs + ")");
}

}  // namespace nsb::scene
