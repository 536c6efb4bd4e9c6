// The limit states an Assembly watches (models/limit_watch.hpp, docs/limit-states.md): each
// accepted step's contact gaps, bent drifts and end state go to the LimitWatch.
#include "models/assembly.hpp"

#include "config/schema.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace nsb::models {

void Assembly::build_limits() {
  const LimitSpec& spec = parts_.limits;
  spec.validate(contacts(), static_cast<int>(parts_.bents.size()),
                static_cast<int>(parts_.bodies.size()));
  const int bodies = static_cast<int>(parts_.bodies.size());
  watch_ = LimitWatch(spec, spec.deck_bodies > 0 ? std::min(spec.deck_bodies, bodies) : bodies);
  if (watch_.watches_joints()) {
    watch_gaps_.assign(parts_.contacts.size(), 0.0);
    normals_.q = integrators::Vector::Zero(dofs());
    normals_.u = integrators::Vector::Zero(dofs());
    normals_.seat.resize(seat_contacts_.size());
    normals_.body.resize(body_contacts_.size());
  }
  // The initial state is the first value of every watched quantity; a seat shorter than the
  // initial opening of its joint is bad input, not a result.
  const integrators::Vector q0 = initial_position(), u0 = initial_velocity();
  const integrators::AcceptedStep start{.t = initial_time(), .h = 0.0, .q = &q0, .u = &u0};
  if (watch_limits(start) == integrators::StepVerdict::kUnseated) {
    for (const auto& v : watch_.values()) {
      if (v.exceeded) {
        char overlap[32];
        std::snprintf(overlap, sizeof overlap, "%.6g", v.margin);
        throw std::invalid_argument("limits." + v.name + ": seat_length is shorter than the "
                                    "joint's opening at t0 (overlap " + std::string(overlap) +
                                    " m); it must exceed it");
      }
    }
  }
}

// g_N of every contact, the numbers contact_normals() writes (and keeps for its call at the
// same accepted state), without the dofs()-sized columns.
void Assembly::watch_gaps(double t, const integrators::Vector& q, const integrators::Vector& u) {
  evaluate_normals(t, q, u);
  normals_.t = t;
  normals_.q = q;
  normals_.u = u;
  for (std::size_t i = 0; i < seat_contacts_.size(); ++i) {
    watch_gaps_[seat_contacts_[i].slot] = normals_.seat[i].gap_normal;
  }
  for (std::size_t i = 0; i < body_contacts_.size(); ++i) {
    watch_gaps_[body_contacts_[i].slot] = normals_.body[i].k.a.gap_normal;
  }
}

integrators::StepVerdict Assembly::watch_limits(const integrators::AcceptedStep& step) {
  if (watch_.empty()) return integrators::StepVerdict::kContinue;
  const integrators::Vector& q = *step.q;
  bool unseated = false;
  if (watch_.watches_joints()) {
    watch_gaps(step.t, q, *step.u);
    unseated = watch_.joints(step.t, watch_gaps_, step.normal_impulse);
  }
  if (watch_.watches_drift()) {
    update_motions(step.t);
    // The bent top's displacement relative to its support, as the bent's springs see it.
    // A bent with columns: each column's top, the watch keeping the largest.
    for (std::size_t j = 0; j < parts_.bents.size(); ++j) {
      for (std::size_t c = 0; c < bent_columns_[j]; ++c) {
        const BentState& b = bents_[bent_slot_[j] + c];
        const int o = b.offset;
        if (b.general) {
          const double dx = q(o) - b.point.y() * q(o + 2) - motions_.value(b.ground_x).d;
          const double dy = q(o + 1) + b.point.x() * q(o + 2) - motions_.value(b.ground_y).d;
          watch_.drift(step.t, j, dx, dy);
          continue;
        }
        const double dx = q(o) - motions_.value(b.ground_x).d;
        const double dy = q(o + 1) + b.position * q(o + 2) - motions_.value(b.ground_y).d;
        watch_.drift(step.t, j, dx, dy);
      }
    }
  }
  watch_.end_state(step.t, q);
  return unseated ? integrators::StepVerdict::kUnseated : integrators::StepVerdict::kContinue;
}

std::vector<integrators::LimitStateValue> Assembly::watched_limit_states() const {
  return watch_.values();
}

integrators::StepVerdict Assembly::accept_step(const integrators::AcceptedStep& step) {
  if (!watches_steps_) return integrators::StepVerdict::kContinue;
  const integrators::StepVerdict keys = watch_keys(step);
  const integrators::StepVerdict limits = watch_limits(step);
  return limits == integrators::StepVerdict::kUnseated ? limits : keys;
}

std::vector<integrators::LimitStateValue> Assembly::limit_states() const {
  std::vector<integrators::LimitStateValue> out = key_limit_states();
  for (auto& v : watched_limit_states()) out.push_back(std::move(v));
  return out;
}

}  // namespace nsb::models
