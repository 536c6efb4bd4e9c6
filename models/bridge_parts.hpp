// A bridge design (models/bridge_design.hpp) as an assembly of parts (models/assembly.hpp):
// one rigid deck, the two abutment seats as prescribed bodies, one Takeda bent per
// BridgeDesign::Bent, Rayleigh damping on modes i and j (with bents), and the four deck-corner
// contacts in the order of models/deck_geometry.hpp. verification/parts_bridge_check.cpp
// holds the benchmark scenes' histories to values recorded with the bridge model this
// assembly replaced.
//
// Units: kN, t, m, s, rad.
#pragma once

#include "models/assembly.hpp"
#include "models/bridge_design.hpp"
#include "models/deck_chain.hpp"

#include <limits>
#include <optional>
#include <vector>

namespace nsb::models {

// Throws std::invalid_argument naming the field (BridgeDesign::validate): bad values, a bent
// excitation of the wrong size, an initial penetration.
Assembly::Parts bridge_parts(const BridgeDesign& p);

// A bridge deck cut into segments (frames) joined by hinges (docs/bridge.md, "Bridges in
// parts"). Layout at rest: the segments lie along global x at y = 0, theta = 0, left to
// right, hinge k clear distance gap_k along the axis between segments k and k + 1; the whole
// deck (segments and hinge gaps, total length L_tot) is centred on x = 0, so that one segment
// is the deck of the one-deck bridge. Segment i's coordinates are its displacement from its rest centre
// (parts::RigidBody::rest), as the one deck's are: segments[i].initial_position is that
// displacement at t = 0.
struct SegmentedDeck {
  std::vector<parts::RigidBody> segments;  // >= 1, straight; their end angles are replaced by
                                           //   their joints' (abutments', hinges')
  std::vector<DeckChain::Joint> hinges;    // segments - 1; hinge k joins segments k and k + 1
  std::vector<int> bent_segment;           // the segment of each BridgeDesign bent
  // Hinge k's own angle [deg] (both faces of the joint), |alpha| < 80; empty or none: the
  // bridge's deck.skew_deg.
  std::vector<std::optional<double>> hinge_skews_deg;
  // The angle of hinge k's faces [deg].
  double hinge_skew_deg(std::size_t k, const DeckGeometry& deck) const;
  // Centre x of segment i at rest [m].
  double rest_position(std::size_t i) const;
  // Throws std::invalid_argument naming the field ("hinges: ...", "bent_segment[2]: ...",
  // "segments[1]: ..." for a segment without two bents at distinct positions).
  void validate(const std::vector<BridgeDesign::Bent>& bents) const;
};

// Whether the segment carries bents at two distinct positions at least: the bents' initial
// stiffness K0 of one body, [[sum kx, 0, 0], [0, sum ky, sum ky s], [0, sum ky s,
// sum ky s^2]], is then positive definite (Cauchy-Schwarz is strict), so the segment has
// torsional stiffness, the Rayleigh damping C = a0 M + a1 K0 and the quasi-static support
// motion K0^-1 (...) exist. One bent leaves the rotation about its position free.
bool torsionally_restrained(const std::vector<BridgeDesign::Bent>& bents,
                            const std::vector<int>& bent_segment, int segment);
inline constexpr const char* kTwoBents =
    "needs bents at two distinct positions at least (torsional stiffness; the bents' K0 is "
    "singular otherwise, and Rayleigh damping needs it)";

// The bridge of p with its deck in segments: p's deck angles (skew_deg, the abutments' own
// skew_left_deg / skew_right_deg; each hinge its hinge_skews_deg), gaps, seats' contact law,
// damping and bents (bent j at position p.bents[j].position from the centre of segment
// deck.bent_segment[j]) apply; p's mass, inertia, length and width are replaced by the
// segments'. Contacts in output order, two per joint (y_b = +W/2 first), as DeckChain:
//   left seat: corners 0, 1 of segment 0;
//   hinge k (1 <= k < N): corners 0, 1 (left end) of segment k against the right end face of
//     segment k - 1 (models/deck_chain.hpp: why only this pair);
//   right seat: corners 2, 3 of segment N - 1.
// With one segment at its rest centre this is bridge_parts(p): the same parts in the same
// order. Throws std::invalid_argument for bad parameters.
Assembly::Parts bridge_parts(const BridgeDesign& p, const SegmentedDeck& deck);

// The limit states a bridge's scene asks for (docs/limit-states.md): the seat lengths of the
// abutments and hinges, the bents' heights and the limits of [model.limit_states].
struct BridgeLimits {
  double abutment_seat = std::numeric_limits<double>::infinity();  // [m]; inf: not watched
  std::vector<double> hinge_seats;   // [m] per hinge (segments - 1); inf: not watched
  std::vector<double> bent_heights;  // [m] per bent, as BridgeDesign::bents
  double drift_ratio = 0.0;          // [-]; 0: not watched
  double residual_rotation = 0.0;    // [rad]; 0: not watched
};

// The LimitSpec of a bridge of `segments` segments in the contact order of bridge_parts:
// joints "left" (contacts 0, 1), "hinge_<k>" (2k, 2k + 1) and "right" (2N, 2N + 1), each
// with its closure watched and its unseating where a seat length is given.
LimitSpec bridge_limit_spec(const BridgeLimits& limits, std::size_t segments);

}  // namespace nsb::models
