// The registered part kinds of a bridge scene, and reading and adding every kind a scene has.
#include "scene/bridge_part_kinds.hpp"

namespace nsb::scene {

// Each kind's entry, defined in its file.
BridgePartKind hinge_restrainers_part();    // scene/part_restrainers.cpp
BridgePartKind bearings_part();             // scene/part_bearings.cpp
BridgePartKind abutments_part();            // scene/part_abutments.cpp
BridgePartKind abutment_restrainers_part();  // scene/part_restrainers.cpp
BridgePartKind shear_keys_part();           // scene/part_shear_keys.cpp

// The order is that in which the parts are added: an abutment's restrainer is anchored on
// the backwall body its abutment adds, and the shear keys sit on the prescribed seats (a
// backfill abutment moves the deck-corner contacts to its wall, not the keys' contacts).
const std::vector<BridgePartKind>& bridge_part_kinds() {
  static const std::vector<BridgePartKind> kinds{
      hinge_restrainers_part(),
      bearings_part(),
      abutments_part(),
      abutment_restrainers_part(),
      shear_keys_part(),
  };
  return kinds;
}

bool BridgePartSettings::any() const {
  for (const auto& s : settings) {
    if (s.has_value()) return true;
  }
  return false;
}

BridgePartSettings read_bridge_parts(const Section& m, const PartShape& shape) {
  BridgePartSettings out;
  for (const auto& kind : bridge_part_kinds()) out.settings.push_back(kind.read(m, shape));
  return out;
}

void add_bridge_parts(const BridgePartSettings& s, PartSite& site,
                      models::Assembly::Parts& parts) {
  const auto& kinds = bridge_part_kinds();
  for (std::size_t k = 0; k < kinds.size() && k < s.settings.size(); ++k) {
    if (s.settings[k].has_value()) kinds[k].add(s.settings[k], site, parts);
  }
}

}  // namespace nsb::scene
