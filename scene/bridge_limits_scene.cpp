// The limit-state keys of a bridge scene (docs/limit-states.md): [model.abutments]
// seat_length, [[model.hinges]] seat_length and [model.limit_states].
#include "scene/scene_builders.hpp"

#include "scene/scene_schema.hpp"

#include <limits>

namespace nsb::scene {

using namespace models;  // the systems and parts a scene builds

BridgeLimitKeys read_bridge_limits(const Section& m) {
  BridgeLimitKeys out;
  if (const auto* t = m.subtable("abutments")) {
    // Its other keys are the abutments' (scene/part_abutments.cpp checks the table's keys).
    Section s(m.context(), *t, m.key_path("abutments"));
    SeatLengthSettings seat;
    s.read_all(SeatLengthSettings::fields(), seat);
    if (s.has("seat_length")) {
      out.limits.abutment_seat = seat.seat_length;
      out.requested = true;
    }
  }
  if (const auto* hinges = m.array_of_tables("hinges")) {
    for (std::size_t k = 0; k < hinges->size(); ++k) {
      const toml::table* t = (*hinges)[k].as_table();
      if (t == nullptr) continue;  // read_joints reports it
      Section s(m.context(), *t, m.key_path("hinges") + "[" + std::to_string(k) + "]");
      SeatLengthSettings seat;
      s.read_all(SeatLengthSettings::fields(), seat);
      out.limits.hinge_seats.push_back(s.has("seat_length")
                                           ? seat.seat_length
                                           : std::numeric_limits<double>::infinity());
    }
  }
  if (const auto* t = m.subtable("limit_states")) {
    Section s(m.context(), *t, m.key_path("limit_states"));
    s.only(keys_of(LimitStateSettings::fields()));
    LimitStateSettings l;
    s.read_all(LimitStateSettings::fields(), l);
    out.limits.drift_ratio = l.drift_ratio;
    out.limits.residual_rotation = l.residual_rotation;
    out.requested = out.requested || s.has("drift_ratio") || s.has("residual_rotation");
  }
  return out;
}

}  // namespace nsb::scene
