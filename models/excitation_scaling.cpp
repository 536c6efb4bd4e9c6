#include "models/excitation_scaling.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "models/response_spectrum.hpp"

namespace nsb::models {

Record time_scaled(Record record, double time_scale) {
  for (double& t : record.t) t *= time_scale;
  return record;
}

double peak_acceleration_g(const Record& record) {
  double p = 0.0;
  for (const double a : record.a) p = std::max(p, std::abs(a));
  return p / kSpectrumGravity;
}

double spectral_acceleration_g(const Record& record, double period, double zeta) {
  SpectrumOptions o;
  o.damping = zeta;
  o.periods = {period};
  return response_spectrum(record, o).psa_g.front();
}

InputComponent describe_input(const Record& record, double factor, double period, double zeta) {
  InputComponent c;
  c.scale_factor = factor;
  c.sa_period = period;
  c.sa_damping = zeta;
  c.pga_g = std::abs(factor) * peak_acceleration_g(record);
  c.sa_g = std::abs(factor) * spectral_acceleration_g(record, period, zeta);
  return c;
}

}  // namespace nsb::models
