// The part kinds a bridge scene adds to the deck, its seats and its bents (docs/bridge.md,
// "Connectors", "Shear keys"): restrainer cables, bearings, abutment backfills, shear keys.
// A kind is one file, scene/part_<kind>.cpp, that holds its scene keys (a settings struct
// with its config::Field list, or the parameters struct of models/ that declares them), how it
// reads them from [model], how it adds its parts to the assembly, and its tables of
// docs/scenes.md; and one line in bridge_part_kinds() (scene/bridge_part_kinds.cpp, with its
// declaration above the list). The bridge scene reads every kind's keys after the deck, the
// bents and the seats, then adds the kinds' parts in the order of that list after the deck's
// own; the docs' key tables of every kind are generated with the others.
//
// Units: kN, t, m, s, rad.
#pragma once

#include "models/assembly.hpp"
#include "models/bridge_design.hpp"
#include "scene/scene_docs.hpp"
#include "scene/scene_reader.hpp"

#include <any>
#include <array>
#include <cstddef>
#include <string_view>
#include <vector>

namespace nsb::scene {

// What a kind's keys are checked against when they are read.
struct PartShape {
  std::vector<double> lengths;  // each deck segment's length [m] (the one deck's for [model.deck])
  models::DeckGeometry deck;    // the deck's gaps at the abutments
};

// Where a kind adds its parts. The deck's bodies come first in parts.bodies.
struct PartSite {
  const models::BridgeDesign& design;            // gaps, width, skew, seats
  std::vector<double> hinge_gaps;                // clear gap of each hinge [m]; hinge k joins
                                                 // bodies k and k + 1
  std::array<models::parts::Motion, 2> ground;   // zero-delay support motions (x, y)
  std::size_t deck_bodies = 0;                   // bodies of the deck
  // The body that replaced abutment a's prescribed seat (a backwall on its backfill); -1: the
  // prescribed seat. Set by the kind that adds it, read by the kinds after it.
  std::array<int, 2> seat_body{-1, -1};
};

struct BridgePartKind {
  // Its own key of [model] ("bearings"); empty for a kind whose keys sit in another table
  // (a restrainer in [[model.hinges]] or [model.abutments]).
  std::string_view key;
  // Its settings read from [model] m, checked by key (file, line, key in the message); an
  // empty std::any when the scene has none.
  std::any (*read)(const Section& m, const PartShape& shape);
  // Adds the parts of its settings (never empty). Throws std::invalid_argument for
  // parameters that no part can have.
  void (*add)(const std::any& settings, PartSite& site, models::Assembly::Parts& parts);
  // Appends its tables of docs/scenes.md (none: nullptr).
  void (*docs)(std::vector<DocTable>& out);
};

// Every kind, in the order their parts are added.
const std::vector<BridgePartKind>& bridge_part_kinds();

// The settings of every kind a scene has, by the index of its kind in bridge_part_kinds().
struct BridgePartSettings {
  std::vector<std::any> settings;  // one per kind; empty: none in the scene
  bool any() const;
};
BridgePartSettings read_bridge_parts(const Section& m, const PartShape& shape);
// Adds every kind's parts, in the order of bridge_part_kinds().
void add_bridge_parts(const BridgePartSettings& s, PartSite& site, models::Assembly::Parts& parts);

}  // namespace nsb::scene
