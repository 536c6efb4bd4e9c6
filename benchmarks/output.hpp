// Where the benchmarks write. A file named on the command line is written where it says; by
// default every benchmark writes under out/ (ignored by git), never into the current folder,
// so that no benchmark output ends up beside the sources.
#pragma once

#include <filesystem>
#include <fstream>

namespace nsb::benchmarks {

// The folder of every benchmark's default output.
inline const std::filesystem::path kOutputDir = "out";

// `path` opened for writing, its parent folders created first.
inline std::ofstream open_output(const std::filesystem::path& path) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  return std::ofstream(path);
}

}  // namespace nsb::benchmarks
