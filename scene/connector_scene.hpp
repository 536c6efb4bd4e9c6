// The connector keys of a bridge scene (docs/bridge.md, "Connectors"): restrainer cables
// across the hinges (`[[model.hinges]] restrainer = {...}`) and at the abutments,
// `[model.abutments]` (prescribed or backfill seats) and `[[model.bearings]]`. Each key is
// declared once here as a config::Field; docs/scenes.md's tables are generated from these.
// A bridge scene with any of them is an assembly of parts (models/assembly.hpp).
//
// Units: kN, t, m, s, rad.
#pragma once

#include "config/schema.hpp"
#include "models/assembly.hpp"
#include "models/bridge_design.hpp"
#include "models/connectors.hpp"
#include "scene/scene_reader.hpp"

#include <array>
#include <optional>
#include <span>
#include <vector>

namespace nsb::scene {

// A restrainer's inline table: the cable law and its length at rest, anchored on the deck
// axis at (length - clear gap) / 2 inside each side of the joint.
struct RestrainerSettings {
  models::connectors::CableParameters cable;
  double length = 1.0;  // rest length between the anchors [m], > the joint's gap
  static std::span<const config::Field<RestrainerSettings>> fields();
};

// What an abutment seat is.
enum class SeatKind { kPrescribed, kBackfill };
inline constexpr std::array<config::Name<SeatKind>, 2> kSeatKindNames{
    {{"prescribed", SeatKind::kPrescribed}, {"backfill", SeatKind::kBackfill}}};

// [model.abutments]: the seats of both abutments and their backfill. The backfill defaults
// are OpenSees HyperbolicGapMaterial's recommended values (Wilson & Elgamal's calibration of
// the UCSD large-scale backwall tests, a 1.68 m backwall, per metre of wall width).
struct AbutmentSettings {
  SeatKind seat = SeatKind::kPrescribed;
  double mass = 10.0;            // backwall + participating soil, each abutment [t]
  double thickness = 0.3;        // backwall thickness along the deck axis [m]
  double width = 0.0;            // wall width [m]; 0: the deck's width
  double stiffness_per_width = 20300.0;   // K_max [kN/m per m]
  double ultimate_force_per_width = 326.0;  // F_ult [kN per m]
  double failure_ratio = 0.7;               // R_f
  double unloading_stiffness_per_width = 20300.0;  // K_ur [kN/m per m]
  double pile_stiffness = 7000.0;  // linear x spring in parallel [kN/m]
  double tie_frequency = 20.0;     // y and theta ties' frequency on the wall's mass [Hz]
  static std::span<const config::Field<AbutmentSettings>> fields();
};

// One [[model.bearings]] element: x and y laws alike, linear or bilinear.
struct BearingSettings {
  int segment = 0;
  double position = 0.0;
  double stiffness = 0.0;
  double yield_force = 0.0;
  double post_yield_ratio = 0.1;
  static std::span<const config::Field<BearingSettings>> fields();
};

// The connectors read from a bridge scene.
struct BridgeConnectors {
  std::vector<std::optional<RestrainerSettings>> hinge_restrainers;  // one per hinge
  std::optional<AbutmentSettings> abutments;
  std::optional<RestrainerSettings> abutment_restrainer;
  std::vector<BearingSettings> bearings;
  bool any() const;
};

// Reads [[model.hinges]] restrainer, [model.abutments] and [[model.bearings]] of [model] m;
// `lengths` are the segments' lengths (bearing positions are checked against them), `deck`
// gives the abutment gaps (a restrainer's length must exceed its joint's gap).
BridgeConnectors read_connectors(const Section& m, const std::vector<double>& lengths,
                                 const models::DeckGeometry& deck);

// Adds the connectors to the parts of a bridge (models::bridge_parts): p gives the gaps,
// width and skew; ground the zero-delay support motions (x, y) of the bearings and
// backfills. A backfill seat replaces the prescribed seat as the obstacle of that end's two
// deck-corner contacts. Hinge k joins bodies k and k + 1.
void add_connectors(const BridgeConnectors& c, const models::BridgeDesign& p,
                    const std::vector<double>& hinge_gaps,
                    const std::array<models::parts::Motion, 2>& ground,
                    models::Assembly::Parts& parts);

}  // namespace nsb::scene
