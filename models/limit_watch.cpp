#include "models/limit_watch.hpp"

#include "models/field_checks.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace nsb::models {

namespace {

integrators::LimitStateValue value(std::string name, const char* unit, bool exceeded,
                                   double time, double margin) {
  integrators::LimitStateValue v;
  v.name = std::move(name);
  v.unit = unit;
  v.exceeded = exceeded;
  if (exceeded) v.time = time;
  v.margin = margin;
  return v;
}

}  // namespace

void LimitSpec::validate(int contacts, int bents, int bodies) const {
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const std::string field = "joints[" + std::to_string(j) + "].";
    for (int c : joints[j].contacts) {
      require(c >= 0 && c < contacts, "limits." + field + "contacts",
              "must name contacts of the assembly");
    }
    require(joints[j].seat_length > 0, "limits." + field + "seat_length", "must be > 0 [m]");
  }
  require(std::isfinite(drift_ratio) && drift_ratio >= 0, "limits.drift_ratio",
          "must be >= 0 [-]");
  if (drift_ratio > 0) {
    require(bent_heights.size() == static_cast<std::size_t>(bents), "limits.bent_heights",
            "one height per bent [m]");
    for (double h : bent_heights) {
      require(std::isfinite(h) && h > 0, "limits.bent_heights", "every height must be > 0 [m]");
    }
  }
  require(std::isfinite(residual_rotation) && residual_rotation >= 0, "limits.residual_rotation",
          "must be >= 0 [rad]");
  require(bodies >= 1, "limits.bodies", "at least one body");
}

LimitWatch::LimitWatch(LimitSpec spec, int bodies)
    : spec_(std::move(spec)),
      joints_(spec_.joints.size()),
      drifts_(spec_.drift_ratio > 0 ? spec_.bent_heights.size() : 0),
      theta_end_(spec_.residual_rotation > 0 ? static_cast<std::size_t>(bodies) : 0) {}

bool LimitWatch::joints(double t, const std::vector<double>& gaps,
                        const integrators::Vector* impulse) {
  bool unseated = false;
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    const JointLimit& spec = spec_.joints[j];
    Joint& w = joints_[j];
    double open = -std::numeric_limits<double>::infinity();
    double least = std::numeric_limits<double>::infinity();
    bool pushed = false;
    for (int c : spec.contacts) {
      const double g = gaps[static_cast<std::size_t>(c)];
      open = std::max(open, g);
      least = std::min(least, g);
      if (impulse != nullptr && (*impulse)(c) > 0.0) pushed = true;
    }
    w.min_gap = std::min(w.min_gap, least);
    if (std::isnan(w.closure_time) && (least <= 0.0 || pushed)) w.closure_time = t;
    if (std::isfinite(spec.seat_length)) {
      const double overlap = spec.seat_length - open;
      w.min_overlap = std::min(w.min_overlap, overlap);
      if (overlap < 0.0 && std::isnan(w.unseat_time)) {
        w.unseat_time = t;
        unseated = true;
      }
    }
  }
  return unseated;
}

void LimitWatch::drift(double t, std::size_t b, double dx, double dy) {
  Drift& d = drifts_[b];
  const double r = std::hypot(dx, dy) / spec_.bent_heights[b];
  if (r > d.peak) d.peak = r;
  if (std::isnan(d.time) && r >= spec_.drift_ratio) d.time = t;
}

void LimitWatch::end_state(double t, const integrators::Vector& q) {
  t_end_ = t;
  for (std::size_t i = 0; i < theta_end_.size(); ++i) {
    theta_end_[i] = std::abs(q(static_cast<Eigen::Index>(3 * i + 2)));
  }
}

std::vector<integrators::LimitStateValue> LimitWatch::values() const {
  std::vector<integrators::LimitStateValue> out;
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    const JointLimit& spec = spec_.joints[j];
    const Joint& w = joints_[j];
    if (std::isfinite(spec.seat_length)) {
      out.push_back(value("unseating_" + spec.name, "m", !std::isnan(w.unseat_time),
                          w.unseat_time, w.min_overlap));
    }
    if (spec.closure) {
      out.push_back(value("closure_" + spec.name, "m", !std::isnan(w.closure_time),
                          w.closure_time, w.min_gap));
    }
  }
  for (std::size_t b = 0; b < drifts_.size(); ++b) {
    out.push_back(value("drift_bent_" + std::to_string(b + 1), "-", !std::isnan(drifts_[b].time),
                        drifts_[b].time, spec_.drift_ratio - drifts_[b].peak));
  }
  for (std::size_t i = 0; i < theta_end_.size(); ++i) {
    const double margin = spec_.residual_rotation - theta_end_[i];
    out.push_back(value(theta_end_.size() == 1 ? std::string("residual_rotation")
                                               : "residual_rotation_" + std::to_string(i + 1),
                        "rad", margin <= 0.0, t_end_, margin));
  }
  return out;
}

}  // namespace nsb::models
