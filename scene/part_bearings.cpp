// Bearings (docs/bridge.md, "Connectors"; the law: models::connectors::Law, linear or bilinear):
// `[[model.bearings]]`, each an elastomeric or lead-rubber bearing between a deck point and the
// ground, with the same law in x and in y.
#include "scene/bridge_part_kinds.hpp"

#include <cmath>
#include <string>

namespace nsb::scene {

using namespace models;  // the systems and parts a scene builds

namespace {

namespace c = config;

// One [[model.bearings]] element: x and y laws alike, linear or bilinear.
struct BearingSettings {
  int segment = 0;
  double position = 0.0;
  double stiffness = 0.0;
  double yield_force = 0.0;
  double post_yield_ratio = 0.1;
  static std::span<const c::Field<BearingSettings>> fields();
};
using Bearings = std::vector<BearingSettings>;

std::span<const c::Field<BearingSettings>> BearingSettings::fields() {
  using S = BearingSettings;
  static const c::Field<S> f[] = {
      c::integer<&S::segment>("segment", c::non_negative(),
                              "0-based [[model.segments]] index (0 with [model.deck])"),
      c::number<&S::position>("position", "m", c::any(),
                              "along the axis from the segment's centre, |position| <= "
                              "length / 2 (required)"),
      c::number<&S::stiffness>("stiffness", "kN/m", c::positive(),
                               "k in x and in y (required)"),
      c::number<&S::yield_force>("yield_force", "kN", c::non_negative(),
                                 "F_y of the bilinear law; 0: linear"),
      c::number<&S::post_yield_ratio>("post_yield_ratio", "-", c::closed_open(0, 1),
                                      "post-yield / initial stiffness r"),
  };
  return f;
}

std::any read_bearings(const Section& m, const PartShape& shape) {
  const toml::array* a = m.array_of_tables("bearings");
  if (a == nullptr) return {};
  const std::vector<double>& lengths = shape.lengths;
  Bearings out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    Section s(m.context(), *(*a)[i].as_table(), m.key_path("bearings") + "[" +
                                                    std::to_string(i) + "]");
    s.only(keys_of(BearingSettings::fields()));
    BearingSettings b;
    s.read_all(BearingSettings::fields(), b);
    for (const char* key : {"position", "stiffness"}) {
      if (!s.has(key)) s.fail_table(std::string("missing key ") + key);
    }
    if (static_cast<std::size_t>(b.segment) >= lengths.size()) {
      s.fail("segment", "must name one of the " + std::to_string(lengths.size()) +
                            " deck segments, 0-based");
    }
    const double half = 0.5 * lengths[static_cast<std::size_t>(b.segment)];
    if (std::abs(b.position) > half) {
      s.fail("position", "must lie on its segment, |position| <= " + c::format_value(half) +
                             " m");
    }
    out.push_back(b);
  }
  if (out.empty()) return {};
  return out;
}

void add_bearings(const std::any& settings, PartSite& site, Assembly::Parts& parts) {
  for (const auto& b : std::any_cast<const Bearings&>(settings)) {
    const auto law = b.yield_force > 0
                         ? connectors::LawParameters::bilinear(b.stiffness, b.yield_force,
                                                               b.post_yield_ratio)
                         : connectors::LawParameters::linear(b.stiffness);
    parts.links.push_back({.body = b.segment, .position = b.position, .longitudinal = law,
                           .transverse = law, .ground_longitudinal = site.ground[0],
                           .ground_transverse = site.ground[1]});
  }
}

void bearing_docs(std::vector<DocTable>& out) {
  out.push_back(doc_tables::table("model.bearings", BearingSettings::fields(), BearingSettings{},
                                  {{"position", "required"}, {"stiffness", "required"}}));
}

}  // namespace

BridgePartKind bearings_part() { return {"bearings", read_bearings, add_bearings, bearing_docs}; }

}  // namespace nsb::scene
