// libFuzzer target: the reader of Siconos .dat LCP files (lcp::parse_siconos_lcp).
//
// Input: the file. A bad file must throw lcp::FormatError (a std::invalid_argument); a file
// that is read must give a problem that passes Problem::validate().
#include "lcp/siconos_format.hpp"

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  nsb::lcp::Problem p;
  try {
    p = nsb::lcp::parse_siconos_lcp(in, "fuzz.dat", size);
  } catch (const nsb::lcp::FormatError&) {
    return 0;  // bad input, reported as such
  }
  p.validate();  // throws (and so fails the target) for a problem the reader should have refused
  return 0;
}
