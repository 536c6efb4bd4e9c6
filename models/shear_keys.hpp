// Exterior shear keys at the abutments (docs/bridge.md, "Shear keys"): concrete blocks on each
// abutment seat, on both sides of the deck, that restrain the deck transversely once a clear
// gap is closed, and that are designed to break (sacrificial keys) before the abutment's
// piles and wall are damaged (Megally, Silva & Seible 2001, UCSD SSRP-2001/23; Caltrans
// Seismic Design Criteria, sec. 7.8.4).
//
// Each key is a unilateral frictional contact of a deck end corner against a face of the
// seat (a prescribed body: it moves with the seat), the face parallel to the bridge's
// longitudinal axis at the clear gap `gap` from the deck's side at rest. A key with a
// capacity breaks at the first accepted step whose mean contact force (normal impulse / h)
// exceeds it; its contact is far from then on (Assembly::watch_keys).
//
// Units: kN, m.
#pragma once

#include "config/schema.hpp"
#include "models/assembly.hpp"

#include <span>
#include <string>

namespace nsb::models {

struct ShearKeyParameters {
  double gap = 0.0;          // clear transverse gap between the deck's side and a key [m], >= 0
  double restitution = 0.0;  // Newton's eps_N of a key contact, in [0, 1]
  double friction = 0.0;     // Coulomb's mu of a key contact, >= 0
  double compliance_stiffness = 0.0;  // Hertz k of a key contact under the compliance method
                                      //   [kN/m^1.5], >= 0; 0: the run's default scaled to the
                                      //   deck's mass (integrators::contact_stiffness)
  double capacity = 0.0;     // the force that breaks a key [kN], >= 0; 0: unbreakable
  // Throws std::invalid_argument naming the field, prefixed with `prefix`.
  void validate(const std::string& prefix) const;
};

// Appends the four key contacts after the existing ones, and their parts::ShearKey entries,
// in this order: left +y, left -y, right +y, right -y ("shear_key_left_plus", ...). The left
// keys sit on prescribed body 0 (the left seat) and touch corners 0 (+y) and 1 (-y) of the
// first body; the right keys sit on prescribed body 1 and touch corners 2 (+y) and 3 (-y) of
// the deck's last body, deck_bodies - 1 (the deck, or the last segment of a segmented deck;
// 0: the last of all bodies; a backfill abutment's backwall bodies follow the deck's). The key face of side
// s = +-1 passes through (x_c, s (W/2 + gap)) at rest, x_c the touching corner's x at rest,
// with the normal (0, -s) pointing from the key towards the deck.
void add_shear_keys(Assembly::Parts& parts, const ShearKeyParameters& keys,
                    std::size_t deck_bodies = 0);

// The keys of [model.shear_keys] (docs/scenes.md).
std::span<const config::Field<ShearKeyParameters>> shear_key_fields();

}  // namespace nsb::models
