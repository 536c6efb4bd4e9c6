// What a binary was built from, for `nsbridge --version`, the sweep's manifest.toml, the
// benchmarks' headers and the Python module: one answer, taken when the code is built.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace nsb::io {

struct BuildInfo {
  std::string version;     // the project's version (CMakeLists.txt project())
  std::string revision;    // git revision (12 hex digits, "-dirty" with uncommitted changes,
                           //   "unknown" outside git), taken at build time
  std::string build_type;  // CMAKE_BUILD_TYPE ("none" when empty)
  std::string compiler;    // "gcc <version>" or "clang <version>"
  // The libraries the engine is compiled against, (name, version), in this order: Eigen,
  // Boost, GSL, toml++ (their headers' version macros).
  std::vector<std::pair<std::string, std::string>> libraries;
};

const BuildInfo& build_info();

}  // namespace nsb::io
