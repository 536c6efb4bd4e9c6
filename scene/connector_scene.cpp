#include "scene/connector_scene.hpp"

#include "scene/scene_builders.hpp"
#include "scene/scene_schema.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace nsb::scene {

using namespace models;  // the systems and parts a scene builds

namespace c = config;

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

std::span<const c::Field<AbutmentSettings>> AbutmentSettings::fields() {
  using S = AbutmentSettings;
  static const c::Field<S> f[] = {
      c::choice<&kSeatKindNames, &S::seat>(
          "seat", "\"prescribed\": the seats move with the ground (as [model.seats]); "
                  "\"backfill\": each seat is a backwall body on the hyperbolic backfill"),
      c::number<&S::mass>("mass", "t", c::positive(),
                          "backfill: backwall and participating soil of one abutment"),
      c::number<&S::thickness>("thickness", "m", c::positive(),
                               "backfill: backwall thickness along the deck axis"),
      c::number<&S::width>("width", "m", c::non_negative(),
                           "backfill: wall width w; 0: the deck's width"),
      c::number<&S::stiffness_per_width>("stiffness_per_width", "kN/m per m", c::positive(),
                                         "backfill: initial stiffness K_max / w (1.68 m wall)"),
      c::number<&S::ultimate_force_per_width>("ultimate_force_per_width", "kN per m",
                                              c::positive(),
                                              "backfill: F_ult / w (1.68 m wall)"),
      c::number<&S::failure_ratio>("failure_ratio", "-", c::open_closed(0, 1),
                                   "backfill: R_f, the asymptote is F_ult / R_f"),
      c::number<&S::unloading_stiffness_per_width>(
          "unloading_stiffness_per_width", "kN/m per m", c::positive(),
          "backfill: unloading-reloading slope K_ur / w, >= stiffness_per_width"),
      c::number<&S::pile_stiffness>("pile_stiffness", "kN/m", c::positive(),
                                    "backfill: linear x spring of the wall's piles, in "
                                    "parallel with the backfill (assumed)"),
      c::number<&S::tie_frequency>("tie_frequency", "Hz", c::positive(),
                                   "backfill: the wall's y and θ ties to the ground, as "
                                   "frequencies on its mass and inertia (far above the "
                                   "bridge's)"),
  };
  return f;
}

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

bool BridgeConnectors::any() const {
  for (const auto& r : hinge_restrainers) {
    if (r) return true;
  }
  return abutments.has_value() || !bearings.empty();
}

namespace {

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

void read_bearings(const Section& m, const std::vector<double>& lengths,
                   BridgeConnectors& out) {
  const toml::array* a = m.array_of_tables("bearings");
  if (a == nullptr) return;
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
    out.bearings.push_back(b);
  }
}

}  // namespace

BridgeConnectors read_connectors(const Section& m, const std::vector<double>& lengths,
                                 const DeckGeometry& deck) {
  BridgeConnectors out;
  if (const toml::array* h = m.array_of_tables("hinges"); h != nullptr) {
    for (std::size_t i = 0; i < h->size(); ++i) {
      const Section s(m.context(), *(*h)[i].as_table(),
                      m.key_path("hinges") + "[" + std::to_string(i) + "]");
      out.hinge_restrainers.push_back(
          read_restrainer(s, s.table()["gap"].value_or(0.0)));
    }
  }
  if (const toml::table* t = m.subtable("abutments"); t != nullptr) {
    Section s(m.context(), *t, m.key_path("abutments"));
    std::vector<std::string_view> keys = keys_of(AbutmentSettings::fields());
    keys.push_back("restrainer");
    for (std::string_view k : keys_of(SeatLengthSettings::fields())) keys.push_back(k);
    s.only(keys);  // seat_length: a limit state's (read_bridge_limits)
    AbutmentSettings a;
    s.read_all(AbutmentSettings::fields(), a);
    if (a.unloading_stiffness_per_width < a.stiffness_per_width) {
      s.fail("unloading_stiffness_per_width", "must be >= stiffness_per_width (a load-unload "
                                              "cycle must not create energy)");
    }
    out.abutments = a;
    out.abutment_restrainer = read_restrainer(s, std::max(deck.gap_left, deck.gap_right));
  }
  read_bearings(m, lengths, out);
  return out;
}

}  // namespace nsb::scene
