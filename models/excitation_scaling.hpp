// The amplitude of a scene's ground-motion records as the supports receive them: peak ground
// acceleration and pseudo-spectral acceleration (models/response_spectrum.hpp) of each scaled
// component, and the factor that scaled it. A scene carries these facts (Scene::input) to its
// run record, and summary.json reports them under "input" (docs/outputs.md).
//
// Units: m, s; accelerations in g = kSpectrumGravity.
#pragma once

#include <optional>

#include "models/ground_motion.hpp"

namespace nsb::models {

// One component of the excitation after scaling.
struct InputComponent {
  double pga_g = 0.0;         // max |a| over the scaled record's samples [g]
  double sa_g = 0.0;          // PSA of the scaled record at sa_period and sa_damping [g]
  double sa_period = 0.0;     // oscillator period T [s]
  double sa_damping = 0.0;    // oscillator damping ratio zeta [-]
  double scale_factor = 1.0;  // factor on the record as read (after record_unit) [-]
};

// The components a scene's excitation has ([model.excitation]); nullopt for a missing one.
struct InputMotion {
  std::optional<InputComponent> transverse, longitudinal;
};

// The record with its times multiplied by time_scale (> 0): the time axis the supports follow
// (GroundMotionOptions::time_scale), on which a spectral acceleration is taken.
Record time_scaled(Record record, double time_scale);

// max |a| over the samples [g].
double peak_acceleration_g(const Record& record);

// PSA [g] of the record at one period (> 0) [s] and damping ratio zeta in [0, 1), computed by
// models::response_spectrum.
double spectral_acceleration_g(const Record& record, double period, double zeta);

// The facts of a component: record is on the supports' time axis (time_scaled) and not yet
// multiplied by factor; PGA and PSA scale linearly with the factor.
InputComponent describe_input(const Record& record, double factor, double period, double zeta);

}  // namespace nsb::models
