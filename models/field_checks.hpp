// Bad parameters of a model or part: std::invalid_argument "field: what", which the scene
// reader prefixes with the file, line and key (scene/scene_reader.hpp).
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace nsb::models {

// Throws std::invalid_argument("<field>: <what>") unless ok.
inline void require(bool ok, const std::string& field, const std::string& what) {
  if (!ok) throw std::invalid_argument(field + ": " + what);
}

// "<list>[i]." : the prefix of the fields of element i of a list of parts.
inline std::string indexed(const char* list, std::size_t i) {
  return std::string(list) + "[" + std::to_string(i) + "].";
}

}  // namespace nsb::models
