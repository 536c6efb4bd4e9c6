// The keys of the bridge's deck, gaps, damping and seats, which set the BridgeDesign, of the
// free rigid deck, and of one rigid deck body: key, unit, range and meaning, declared once (docs/scenes.md is generated
// from them; the default is the benchmark's value).
#pragma once

#include "config/schema.hpp"
#include "models/bridge_design.hpp"
#include "models/parts.hpp"

#include <span>

namespace nsb::models {

std::span<const config::Field<BridgeDesign>> bridge_deck_fields();     // [model.deck]
std::span<const config::Field<BridgeDesign>> bridge_gap_fields();      // [model.gaps]
std::span<const config::Field<BridgeDesign>> bridge_damping_fields();  // [model.damping]
std::span<const config::Field<BridgeDesign>> bridge_seat_fields();     // [model.seats]

// [model] of kind = "rigid_deck" besides kind: a free deck, a design without bents.
std::span<const config::Field<BridgeDesign>> rigid_deck_fields();

// One rigid deck body: an element of [[model.segments]] (bridge) or [[model.decks]] (deck
// chain); skew_deg comes from the scene's layout. initial_position is the displacement from
// the rest layout (docs/bridge.md, "Bridges in parts").
std::span<const config::Field<parts::RigidBody>> segment_fields();

}  // namespace nsb::models
