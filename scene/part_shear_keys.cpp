// Exterior shear keys at the abutments (docs/bridge.md, "Shear keys"; the part and its keys:
// models/shear_keys.hpp): `[model.shear_keys]`, four key contacts on the seats that break at
// their capacity.
#include "scene/bridge_part_kinds.hpp"

#include "models/shear_keys.hpp"

namespace nsb::scene {

using namespace models;  // the systems and parts a scene builds

namespace {

std::any read_shear_keys(const Section& m, const PartShape&) {
  const toml::table* t = m.subtable("shear_keys");
  if (t == nullptr) return {};
  Section s(m.context(), *t, m.key_path("shear_keys"));
  s.only(keys_of(shear_key_fields()));
  ShearKeyParameters keys;
  s.read_all(shear_key_fields(), keys);
  return keys;
}

void add_keys(const std::any& settings, PartSite& site, Assembly::Parts& parts) {
  add_shear_keys(parts, std::any_cast<const ShearKeyParameters&>(settings), site.deck_bodies);
}

void shear_key_docs(std::vector<DocTable>& out) {
  out.push_back(doc_tables::table("model.shear_keys", shear_key_fields(), ShearKeyParameters{}));
}

}  // namespace

BridgePartKind shear_keys_part() {
  return {"shear_keys", read_shear_keys, add_keys, shear_key_docs};
}

}  // namespace nsb::scene
