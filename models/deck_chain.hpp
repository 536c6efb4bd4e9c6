// A chain of N free rigid decks in a row between two fixed abutment faces: no bents, no
// excitation, no gravity in the plane; only the N + 1 joints (left abutment, N - 1 hinges,
// right abutment), each a pair of unilateral frictional corner contacts (models/parts.hpp).
//
// Geometry at rest: the decks lie along global x at y = 0, theta = 0, each of its own width
// (W unless the deck gives one) and all of skew alpha (every face is parallel to the line
// x = y tan(alpha)). The left abutment face passes
// through x = 0; joint k's gap is the clear distance along the axis between the faces it
// joins, so deck i's centre is at x_i = sum_{k <= i} gap_k + sum_{k < i} L_k + L_i / 2, and the
// right abutment face passes through x_{N-1} + L_{N-1} / 2 + gap_N. The normal gap of joint k is
// gap_k cos(alpha), as in models/deck_geometry.hpp.
//
// Contacts, in output order (two per joint, y_b = +W/2 first):
//   joint 0:        corners 0, 1 (left end) of deck 0 against the left abutment face;
//   joint k, 0<k<N: corners 0, 1 (left end) of deck k against the right end face of deck k-1;
//   joint N:        corners 2, 3 (right end) of deck N-1 against the right abutment face.
// Each hinge contact is one side of the joint (parts::CornerContact, docs/bridge.md "Contacts
// with edges"): the corner of deck k's left end on deck k - 1's right end face, or the corner
// of deck k - 1's right end (2 for +W/2, 3 for -W/2) on deck k's left end face, whichever lies
// further inside the other's face. The faces end at the decks' corners; the abutment faces are
// lines (models/contact_geometry.hpp). Neighbouring decks may differ in width: a corner beyond
// the other deck's face is no candidate, so the narrower deck's corners meet the wider one's
// face. With equal widths and no relative offset the two
// corners of a side coincide and have the same columns; the side is then one contact (deck
// k's corner), so the Delassus matrix W^T M^-1 W has no repeated columns.
//
// Units: kN, t, m, s, rad, deg.
#pragma once

#include "config/schema.hpp"
#include "models/assembly.hpp"

#include <span>
#include <Eigen/Dense>

#include <vector>

namespace nsb::models {

struct DeckChain {
  struct Deck {
    double mass = 0.0;      // [t], > 0
    double inertia = 0.0;   // about the centre [t m^2], > 0
    double length = 0.0;    // along the axis [m], > 0
    double width = 0.0;     // across the axis [m], >= 0; 0: Parameters::width
    Eigen::Vector3d initial_displacement = Eigen::Vector3d::Zero();  // from rest [m, m, rad]
    Eigen::Vector3d initial_velocity = Eigen::Vector3d::Zero();      // [m/s, m/s, rad/s]
  };
  struct Joint {
    double gap = 0.0;          // clear distance along the axis at rest [m], >= 0
    double restitution = 0.0;  // Newton's eps_N in [0, 1]
    double friction = 0.0;     // Coulomb's mu >= 0
    double compliance_stiffness = 0.0;  // Hertz k of its contacts under the compliance
                                        //   method [kN/m^1.5]; 0: the run's default scaled to
                                        //   the colliding mass (integrators::contact_stiffness)
  };
  struct Parameters {
    std::vector<Deck> decks;    // N >= 1
    std::vector<Joint> joints;  // N + 1: left abutment, N - 1 hinges, right abutment
    double width = 0.0;         // W of a deck that gives none [m], > 0
    double skew_deg = 0.0;      // alpha of every face [deg], |alpha| < 80
    // Throws std::invalid_argument naming the field ("joints[2].gap: must be >= 0 [m]").
    void validate() const;
  };

  // The assembly's parts; throws std::invalid_argument for bad parameters (Assembly's
  // constructor then rejects an initial penetration).
  static Assembly::Parts parts(const Parameters& p);
  // Centre x of deck i at rest [m].
  static double rest_position(const Parameters& p, int deck);
};

// One joint between two deck bodies or a deck and an abutment: the keys of an element of
// [[model.hinges]] (bridge) or [[model.joints]] (deck chain).
std::span<const config::Field<DeckChain::Joint>> joint_fields();

}  // namespace nsb::models
