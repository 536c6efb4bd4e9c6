// libFuzzer target: the ground-motion record readers (PEER AT2, CSV, two-column) and the
// spline motion built from what they accept.
//
// Input: the first byte selects the reader (modulo 3); the rest is the file. A bad file must
// throw std::invalid_argument; a record that is read must build a GroundMotion whose values
// are finite at its samples.
#include "models/ground_motion.hpp"
#include "scene/records.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int reader = data[0] % 3;
  std::istringstream in(std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  nsb::models::Record r;
  try {
    switch (reader) {
      case 0: r = nsb::scene::read_at2(in, "fuzz.AT2"); break;
      case 1: r = nsb::scene::read_csv(in, "fuzz.csv"); break;
      default: r = nsb::scene::read_two_column(in, "fuzz.txt"); break;
    }
  } catch (const std::invalid_argument&) {
    return 0;  // bad input, reported as such
  }
  try {
    const nsb::models::GroundMotion g(r);
    for (double t : r.t) {
      // Finite samples give a finite motion, or a reported error above: never NaN silently.
      const double v = g.acceleration(t) + g.velocity(t) + g.displacement(t);
      if (!std::isfinite(v) && std::isfinite(g.pga())) __builtin_trap();
    }
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
