// The benchmark bridge of models/bridge.hpp as an assembly of parts (models/assembly.hpp):
// one rigid deck, the two abutment seats as prescribed bodies, one Takeda bent per
// Bridge::Bent, Rayleigh damping on modes i and j, and the four deck-corner contacts in the
// order of models/deck_geometry.hpp. From the same parameters and excitation, the assembly
// performs models::Bridge's floating-point operations in the same order
// (verification/parts_bridge_check.cpp).
//
// Units: kN, t, m, s, rad.
#pragma once

#include "models/assembly.hpp"
#include "models/bridge.hpp"

namespace nsb::models {

// Throws std::invalid_argument as Bridge's constructor does: bad parameters (the field named
// as in Bridge::Parameters::validate) or a bent excitation of the wrong size.
Assembly::Parts bridge_parts(const Bridge::Parameters& p, const Bridge::Excitation& excitation);

}  // namespace nsb::models
