// Restrainer cables (docs/bridge.md, "Connectors"; the law: models::connectors::Cable): across
// a hinge (`[[model.hinges]] restrainer = {...}`, body k to body k + 1) and at the abutments
// (`[model.abutments] restrainer = {...}`, one cable from each deck end to its seat, the
// prescribed seat or the backwall body of a backfill abutment). Each cable is anchored on the
// deck axis at (length - clear gap) / 2 inside each side of its joint.
#include "scene/bridge_part_kinds.hpp"

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>

namespace nsb::scene {

using namespace models;  // the systems and parts a scene builds

namespace {

namespace c = config;

// A restrainer's inline table: the cable law and its length at rest.
struct RestrainerSettings {
  connectors::CableParameters cable;
  double length = 1.0;  // rest length between the anchors [m], > the joint's gap
  static std::span<const c::Field<RestrainerSettings>> fields();
};

std::span<const c::Field<RestrainerSettings>> RestrainerSettings::fields() {
  using S = RestrainerSettings;
  using C = connectors::CableParameters;
  static const c::Field<S> f[] = {
      c::number<&S::cable, &C::stiffness>("stiffness", "kN/m", c::positive(),
                                          "axial stiffness k of all cables of the joint "
                                          "(required)"),
      c::number<&S::cable, &C::slack>("slack", "m", c::non_negative(),
                                      "elongation before the cables take tension"),
      c::number<&S::cable, &C::yield_force>("yield_force", "kN", c::non_negative(),
                                            "tension at yield (elastic-perfectly plastic, "
                                            "permanent elongation); 0: no yield"),
      c::number<&S::length>("length", "m", c::positive(),
                            "cable length at rest, > the joint's gap; anchored on the deck "
                            "axis, half the excess inside each side"),
  };
  return f;
}

// The restrainer of joint table s, whose gap is `gap` [m] (its length must exceed it).
std::optional<RestrainerSettings> read_restrainer(const Section& s, double gap) {
  const toml::table* t = s.subtable("restrainer");
  if (t == nullptr) return std::nullopt;
  Section r(s.context(), *t, s.key_path("restrainer"));
  r.only(keys_of(RestrainerSettings::fields()));
  RestrainerSettings out;
  r.read_all(RestrainerSettings::fields(), out);
  if (!r.has("stiffness")) r.fail_table("missing key stiffness (cable stiffness [kN/m])");
  if (!(out.length > gap)) {
    r.fail("length", "must exceed the joint's gap " + c::format_value(gap) + " m (got " +
                         c::format_value(out.length) + ")");
  }
  return out;
}

// Anchor offset from a joint face along the axis: half the cable's excess over the gap.
double anchor_inset(const RestrainerSettings& r, double gap, const std::string& key) {
  if (!(r.length > gap)) {
    throw std::invalid_argument(key + ".length: must exceed the joint's gap (" +
                                std::to_string(gap) + " m)");
  }
  return 0.5 * (r.length - gap);
}

// ---------------------------------------------------------------------------------------------
// Across the hinges: one optional restrainer per hinge.

using HingeRestrainers = std::vector<std::optional<RestrainerSettings>>;

std::any read_hinge_restrainers(const Section& m, const PartShape&) {
  const toml::array* h = m.array_of_tables("hinges");
  if (h == nullptr) return {};
  HingeRestrainers out;
  bool any = false;
  for (std::size_t i = 0; i < h->size(); ++i) {
    const Section s(m.context(), *(*h)[i].as_table(),
                    m.key_path("hinges") + "[" + std::to_string(i) + "]");
    out.push_back(read_restrainer(s, s.table()["gap"].value_or(0.0)));
    any = any || out.back().has_value();
  }
  if (!any) return {};
  return out;
}

void add_hinge_restrainers(const std::any& settings, PartSite& site, Assembly::Parts& parts) {
  const auto& restrainers = std::any_cast<const HingeRestrainers&>(settings);
  const std::vector<double>& gaps = site.hinge_gaps;
  for (std::size_t k = 0; k < restrainers.size() && k < gaps.size(); ++k) {
    if (!restrainers[k]) continue;
    const RestrainerSettings& r = *restrainers[k];
    const double inset =
        anchor_inset(r, gaps[k], "hinges[" + std::to_string(k) + "].restrainer");
    const double la = parts.bodies[k].length, lb = parts.bodies[k + 1].length;
    parts.restrainers.push_back({.body = static_cast<int>(k),
                                 .anchor = Eigen::Vector2d(0.5 * la - inset, 0.0),
                                 .other = parts::Obstacle::kBody,
                                 .other_index = static_cast<int>(k + 1),
                                 .other_anchor = Eigen::Vector2d(-0.5 * lb + inset, 0.0),
                                 .cable = r.cable});
  }
}

// The table of docs/scenes.md (the same keys at the hinges and at the abutments).
void restrainer_docs(std::vector<DocTable>& out) {
  out.push_back(doc_tables::table("model.restrainer", RestrainerSettings::fields(),
                                  RestrainerSettings{}, {{"stiffness", "required"}}));
}

// ---------------------------------------------------------------------------------------------
// At the abutments: one cable per abutment from the deck end (body 0, or the last deck body)
// to its seat: the prescribed seat or the backwall body site.seat_body[a] (>= 0).

std::any read_abutment_restrainer(const Section& m, const PartShape& shape) {
  const toml::table* t = m.subtable("abutments");
  if (t == nullptr) return {};
  const Section s(m.context(), *t, m.key_path("abutments"));
  auto r = read_restrainer(s, std::max(shape.deck.gap_left, shape.deck.gap_right));
  if (!r) return {};
  return *r;
}

void add_abutment_restrainers(const std::any& settings, PartSite& site, Assembly::Parts& parts) {
  const auto& r = std::any_cast<const RestrainerSettings&>(settings);
  const BridgeDesign& p = site.design;
  const double gaps[2] = {p.deck.gap_left, p.deck.gap_right};
  for (std::size_t a = 0; a < 2; ++a) {
    const double side = a == 0 ? -1.0 : 1.0;
    const double inset = anchor_inset(r, gaps[a], "abutments.restrainer");
    const std::size_t deck = a == 0 ? 0 : site.deck_bodies - 1;
    parts::Restrainer cable{.body = static_cast<int>(deck), .cable = r.cable};
    cable.anchor = Eigen::Vector2d(side * (0.5 * parts.bodies[deck].length - inset), 0.0);
    if (site.seat_body[a] >= 0) {
      // The backwall's face towards the deck is at -side t/2 in its frame.
      const double t = parts.bodies[static_cast<std::size_t>(site.seat_body[a])].length;
      cable.other = parts::Obstacle::kBody;
      cable.other_index = site.seat_body[a];
      cable.other_anchor = Eigen::Vector2d(-side * 0.5 * t + side * inset, 0.0);
    } else {
      // The prescribed seat's frame origin is its face point.
      cable.other = parts::Obstacle::kPrescribed;
      cable.other_index = static_cast<int>(a);
      cable.other_anchor = Eigen::Vector2d(side * inset, 0.0);
    }
    parts.restrainers.push_back(cable);
  }
}

}  // namespace

BridgePartKind hinge_restrainers_part() {
  return {"", read_hinge_restrainers, add_hinge_restrainers, restrainer_docs};
}

BridgePartKind abutment_restrainers_part() {
  return {"", read_abutment_restrainer, add_abutment_restrainers, nullptr};
}

}  // namespace nsb::scene
