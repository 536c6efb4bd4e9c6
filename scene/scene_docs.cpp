#include "scene/scene_docs.hpp"

#include "integrators/run.hpp"
#include "models/bridge_fields.hpp"
#include "models/deck_chain.hpp"
#include "models/simple_systems.hpp"
#include "scene/bridge_part_kinds.hpp"
#include "scene/scene_schema.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>
#include <type_traits>
#include <variant>

namespace nsb::scene {

using namespace models;  // the systems and parts a scene builds

using namespace doc_tables;  // the key tables' rows

namespace {

// One [solver] table per registered method, with the method's own defaults.
void add_method_tables(std::vector<DocTable>& out) {
  [&]<class... O>(std::type_identity<std::variant<O...>>) {
    (out.push_back(table("solver." + std::string(O::kMethod), O::fields(), O{})), ...);
  }(std::type_identity<integrators::RunConfig>{});
}

void add_bridge_tables(std::vector<DocTable>& out) {
  const BridgeDesign bridge = BridgeDesign::benchmark();
  out.push_back({"model.deck",
                 kHeader + rows(bridge_deck_fields(), bridge) +
                     rows(CurvedDeckSettings::fields(), CurvedDeckSettings{},
                          {{"angle_deg", "none"}}),
                 joined(keys(bridge_deck_fields()), keys(CurvedDeckSettings::fields()))});
  out.push_back(table("model.gaps", bridge_gap_fields(), bridge));
  out.push_back(table("model.damping", bridge_damping_fields(), bridge));
  const DefaultNotes derived{{"position", "required"},
                             {"height", "none"},
                             {"stiffness_longitudinal", "derived"},
                             {"yield_force_longitudinal", "derived"},
                             {"stiffness_transverse", "derived"},
                             {"yield_force_transverse", "derived"}};
  out.push_back(table("model.bents", BentSettings::fields(), BentSettings{}, derived));
  out.push_back({"model.seats",
                 kHeader + rows(bridge_seat_fields(), bridge) +
                     rows(SeatMotionSettings::fields(), SeatMotionSettings{}, {{"rotation_dt", "none"}}),
                 joined(keys(bridge_seat_fields()), keys(SeatMotionSettings::fields()))});
  out.push_back(table("model.excitation", ExcitationSettings::fields(), ExcitationSettings{},
                      {{"record_dt", "none"}}));
  out.push_back(table("model.excitation.sequence", SequenceSettings::fields(), SequenceSettings{}));
  // A deck in several bodies: the bridge's [[model.segments]] and [[model.hinges]], the deck
  // chain's [[model.decks]] and [[model.joints]] (the same keys).
  out.push_back(table("model.layout", LayoutSettings::fields(), LayoutSettings{}));
  const DefaultNotes required{
      {"mass", "required"}, {"inertia", "required"}, {"length", "required"}, {"width", "required"}};
  out.push_back(table("model.segments", segment_fields(), parts::RigidBody{}, required));
  out.push_back({"model.hinges",
                 kHeader + rows(joint_fields(), DeckChain::Joint{}, {{"gap", "required"}}) +
                     rows(SeatLengthSettings::fields(), SeatLengthSettings{},
                           {{"seat_length", "none"}}) +
                     rows(HingeSkewSettings::fields(), HingeSkewSettings{},
                          {{"skew_deg", "[model] skew_deg"}}),
                 joined(joined(keys(joint_fields()), keys(SeatLengthSettings::fields())),
                        keys(HingeSkewSettings::fields()))});
  out.push_back(table("model.limit_states", LimitStateSettings::fields(), LimitStateSettings{},
                      {{"drift_ratio", "none"}, {"residual_rotation", "none"}}));
  // The part kinds' tables (restrainers, abutments, bearings, shear keys).
  for (const auto& kind : bridge_part_kinds()) {
    if (kind.docs != nullptr) kind.docs(out);
  }
}

// The marker comments around a generated table.
constexpr std::string_view kBegin = "<!-- schema:begin ";
constexpr std::string_view kEnd = "<!-- schema:end -->";

}  // namespace

std::vector<DocTable> scene_doc_tables() {
  std::vector<DocTable> out;
  out.push_back(table("top", SceneHeader::fields(), SceneHeader{}, {{"kind", "required"}}));
  out.push_back({"solver", kHeader + rows(MethodSetting::fields(), MethodSetting{}) +
                               rows(EstimateSettings::fields(), EstimateSettings{}),
                 joined(keys(MethodSetting::fields()), keys(EstimateSettings::fields()))});
  add_method_tables(out);
  out.push_back(table("output", OutputSettings::fields(), OutputSettings{}));
  out.push_back(table("model.bouncing_ball", bouncing_ball_fields(), BouncingBall::Parameters{}));
  out.push_back(table("model.impact_oscillator", impact_oscillator_fields(),
                      ImpactOscillator::Parameters{}));
  out.push_back(table("model.sliding_block", sliding_block_fields(), SlidingBlock::Parameters{}));
  const DefaultNotes required{
      {"mass", "required"}, {"inertia", "required"}, {"length", "required"}, {"width", "required"}};
  out.push_back(
      table("model.rigid_deck", rigid_deck_fields(), BridgeDesign::free_deck(), required));
  add_bridge_tables(out);
  return out;
}

namespace {

// A table's marker name as a scene file writes it.
std::string written(const std::string& name) {
  static const std::set<std::string> arrays{"model.bents", "model.segments", "model.hinges",
                                            "model.bearings"};
  static const std::set<std::string> kinds{"model.bouncing_ball", "model.impact_oscillator",
                                           "model.sliding_block", "model.rigid_deck"};
  if (name == "top") return "the top level";
  if (name.rfind("solver.", 0) == 0) {
    return "[solver] with method = \"" + name.substr(7) + "\"";
  }
  if (kinds.count(name) != 0) return "[model] with kind = \"" + name.substr(6) + "\"";
  if (name == "model.restrainer") return "restrainer of [[model.hinges]] or [model.abutments]";
  if (name == "model.layout") return "[model] of a bridge in [[model.segments]]";
  if (arrays.count(name) != 0) return "[[" + name + "]]";
  return "[" + name + "]";
}

// Whether table `name` is the table at key path `path` ("model.bents[0]" is model.bents).
bool is_table_at(const std::string& name, std::string_view path) {
  std::string p;  // path without its indices: model.hinges[0].restrainer -> model.hinges.restrainer
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (path[i] == '[') {
      i = path.find(']', i);
      if (i == std::string_view::npos) break;
      continue;
    }
    p += path[i];
  }
  if (p.empty()) p = "top";
  if (p.size() > 11 && p.ends_with(".restrainer")) p = "model.restrainer";
  // A deck chain's bodies and joints hold the keys of a bridge's segments and hinges.
  if (p == "model.decks") p = "model.segments";
  if (p == "model.joints") p = "model.hinges";
  if (name == p) return true;
  // The method and kind tables are [solver] and [model] themselves.
  return name.rfind(p + ".", 0) == 0 && (p == "solver" || name == "model.layout" ||
                                         written(name).rfind("[model] with kind", 0) == 0);
}

}  // namespace

std::vector<std::string> tables_holding(std::string_view key, std::string_view path) {
  static const std::vector<DocTable> tables = scene_doc_tables();
  std::vector<std::string> out;
  for (const auto& t : tables) {
    if (is_table_at(t.name, path)) continue;
    for (const auto& k : t.keys) {
      if (k.key != key) continue;
      const std::string w = written(t.name);
      if (std::find(out.begin(), out.end(), w) == out.end()) out.push_back(w);
    }
  }
  return out;
}

std::string regenerate_scene_docs(const std::string& doc) {
  std::map<std::string, std::string> tables;
  for (auto& t : scene_doc_tables()) tables[t.name] = std::move(t.markdown);
  std::set<std::string> seen;
  std::string out;
  std::size_t pos = 0;
  while (true) {
    const std::size_t begin = doc.find(kBegin, pos);
    if (begin == std::string::npos) break;
    const std::size_t name_end = doc.find(" -->", begin);
    const std::size_t end = doc.find(kEnd, begin);
    if (name_end == std::string::npos || end == std::string::npos) {
      throw std::invalid_argument("unterminated schema block at offset " + std::to_string(begin));
    }
    const std::string name(doc, begin + kBegin.size(), name_end - begin - kBegin.size());
    const auto it = tables.find(name);
    if (it == tables.end()) throw std::invalid_argument("unknown schema table \"" + name + "\"");
    seen.insert(name);
    out.append(doc, pos, name_end + 4 - pos).append("\n").append(it->second);
    out.append(kEnd);
    pos = end + kEnd.size();
  }
  out.append(doc, pos);
  for (const auto& [name, text] : tables) {
    if (seen.count(name) == 0) {
      throw std::invalid_argument("no block <!-- schema:begin " + name + " --> for table " + name);
    }
  }
  return out;
}

}  // namespace nsb::scene
