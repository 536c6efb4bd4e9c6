#include "scene/scene_docs.hpp"

#include "integrators/run.hpp"
#include "models/bridge_fields.hpp"
#include "models/deck_chain.hpp"
#include "models/shear_keys.hpp"
#include "models/simple_systems.hpp"
#include "scene/connector_scene.hpp"
#include "scene/scene_schema.hpp"

#include <map>
#include <set>
#include <stdexcept>
#include <type_traits>
#include <variant>

namespace nsb::scene {

using namespace models;  // the systems and parts a scene builds

namespace {

namespace c = config;

// Keys whose default is not the member's value: required keys, values derived when absent.
using DefaultNotes = std::map<std::string_view, std::string_view>;

// Text for a markdown cell: a '|' would end the cell.
std::string cell(std::string_view text) {
  std::string out;
  for (char ch : text) {
    if (ch == '|') out += '\\';
    out += ch;
  }
  return out;
}

// The allowed values of a field as the docs state them.
template <class S>
std::string allowed(const c::Field<S>& f) {
  switch (f.kind) {
    case c::Kind::kNumber: return f.range.describe() == "any" ? "finite" : f.range.describe();
    case c::Kind::kInteger: return "integer " + f.range.describe();
    case c::Kind::kBoolean: return "true, false";
    case c::Kind::kChoice: {
      std::string list;
      for (const auto& name : f.choices) list += (list.empty() ? "`\"" : ", `\"") + std::string(name) + "\"`";
      return list;
    }
    case c::Kind::kText: return "text";
    case c::Kind::kVector3: return "3 finite numbers";
  }
  return {};
}

template <class S>
std::string default_text(const c::Field<S>& f, const S& defaults, const DefaultNotes& notes) {
  if (const auto it = notes.find(f.key); it != notes.end()) return std::string(it->second);
  const c::Value v = f.get(defaults);
  if (const auto* s = std::get_if<std::string>(&v); s != nullptr && s->empty()) return "none";
  return "`" + c::format_value(v) + "`";
}

const std::string kHeader =
    "| key | unit | default | allowed | meaning |\n|---|---|---|---|---|\n";

template <class S>
std::string rows(std::span<const c::Field<S>> fields, const S& defaults,
                 const DefaultNotes& notes = {}) {
  std::string out;
  for (const auto& f : fields) {
    const std::string unit = f.unit.empty() || f.unit == "-" ? "–" : std::string(f.unit);
    out += "| `" + std::string(f.key) + "` | " + unit + " | " +
           cell(default_text(f, defaults, notes)) + " | " + cell(allowed(f)) + " | " +
           cell(f.meaning) + " |\n";
  }
  return out;
}

template <class S>
DocTable table(std::string name, std::span<const c::Field<S>> fields, const S& defaults,
               const DefaultNotes& notes = {}) {
  return {std::move(name), kHeader + rows(fields, defaults, notes)};
}

// One [solver] table per registered method, with the method's own defaults.
void add_method_tables(std::vector<DocTable>& out) {
  [&]<class... O>(std::type_identity<std::variant<O...>>) {
    (out.push_back(table("solver." + std::string(O::kMethod), O::fields(), O{})), ...);
  }(std::type_identity<integrators::RunConfig>{});
}

void add_bridge_tables(std::vector<DocTable>& out) {
  const BridgeDesign bridge = BridgeDesign::benchmark();
  out.push_back(table("model.deck", bridge_deck_fields(), bridge));
  out.push_back(table("model.gaps", bridge_gap_fields(), bridge));
  out.push_back(table("model.damping", bridge_damping_fields(), bridge));
  out.push_back(table("model.shear_keys", shear_key_fields(), ShearKeyParameters{}));
  const DefaultNotes derived{{"position", "required"},
                             {"height", "none"},
                             {"stiffness_longitudinal", "derived"},
                             {"yield_force_longitudinal", "derived"},
                             {"stiffness_transverse", "derived"},
                             {"yield_force_transverse", "derived"}};
  out.push_back(table("model.bents", BentSettings::fields(), BentSettings{}, derived));
  out.push_back({"model.seats", kHeader + rows(bridge_seat_fields(), bridge) +
                                    rows(SeatMotionSettings::fields(), SeatMotionSettings{})});
  out.push_back(table("model.excitation", ExcitationSettings::fields(), ExcitationSettings{}));
  // A deck in several bodies: the bridge's [[model.segments]] and [[model.hinges]], the deck
  // chain's [[model.decks]] and [[model.joints]] (the same keys).
  out.push_back(table("model.layout", LayoutSettings::fields(), LayoutSettings{}));
  const DefaultNotes required{
      {"mass", "required"}, {"inertia", "required"}, {"length", "required"}, {"width", "required"}};
  out.push_back(table("model.segments", segment_fields(), parts::RigidBody{}, required));
  out.push_back({"model.hinges",
                 kHeader + rows(joint_fields(), DeckChain::Joint{}, {{"gap", "required"}}) +
                     rows(SeatLengthSettings::fields(), SeatLengthSettings{},
                          {{"seat_length", "none"}})});
  // Connectors (scene/connector_scene.hpp); seat_length is a limit state's.
  out.push_back(table("model.restrainer", RestrainerSettings::fields(), RestrainerSettings{},
                      {{"stiffness", "required"}}));
  out.push_back({"model.abutments",
                 kHeader + rows(AbutmentSettings::fields(), AbutmentSettings{}) +
                     rows(SeatLengthSettings::fields(), SeatLengthSettings{},
                          {{"seat_length", "none"}})});
  out.push_back(table("model.bearings", BearingSettings::fields(), BearingSettings{},
                      {{"position", "required"}, {"stiffness", "required"}}));
  out.push_back(table("model.limit_states", LimitStateSettings::fields(), LimitStateSettings{},
                      {{"drift_ratio", "none"}, {"residual_rotation", "none"}}));
}

// The marker comments around a generated table.
constexpr std::string_view kBegin = "<!-- schema:begin ";
constexpr std::string_view kEnd = "<!-- schema:end -->";

}  // namespace

std::vector<DocTable> scene_doc_tables() {
  std::vector<DocTable> out;
  out.push_back(table("top", SceneHeader::fields(), SceneHeader{}, {{"kind", "required"}}));
  out.push_back({"solver", kHeader + rows(MethodSetting::fields(), MethodSetting{}) +
                               rows(EstimateSettings::fields(), EstimateSettings{})});
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
