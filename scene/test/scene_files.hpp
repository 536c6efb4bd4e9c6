// Scene files for the models' tests: written into a scratch folder of the test process,
// which is removed when the process ends, and the error message of loading one.
#pragma once

#include "scene/scene.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace nsb::scene::test_files {

// The scratch folder, created at first use and removed at exit.
inline const std::filesystem::path& scratch_dir() {
  struct Scratch {
    std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                ("nsb-scene-files-" + std::to_string(::getpid()));
    Scratch() { std::filesystem::create_directories(dir); }
    ~Scratch() {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    }
  };
  static const Scratch scratch;
  return scratch.dir;
}

// Writes `text` to the scratch file `name` and returns its path.
inline std::filesystem::path write(const std::string& name, const std::string& text) {
  const std::filesystem::path p = scratch_dir() / name;
  std::ofstream(p) << text;
  return p;
}

// The error message of loading `text` as a scene with `overrides` (empty when it loads).
inline std::string error_of(const std::string& name, const std::string& text,
                            const std::vector<std::string>& overrides = {}) {
  const std::filesystem::path p = write(name, text);
  try {
    load_scene(p, overrides);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

}  // namespace nsb::scene::test_files
