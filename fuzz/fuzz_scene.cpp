// libFuzzer target: the scene reader with overrides (scene::load_scene).
//
// Input: the first line is one override "section.key=value"; the rest is the scene file. A
// bad scene or override must throw std::invalid_argument; anything else (another exception,
// a crash, a sanitizer report, a hang) is a bug. Records named by a scene are found through
// ./data/, so the fuzzer runs from the repository root (fuzz/run.sh).
#include "scene/scene.hpp"

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto eol = text.find('\n');
  const std::string override_text(text.substr(0, eol));
  const std::string_view scene = eol == std::string_view::npos ? "" : text.substr(eol + 1);
  // One scene file per process, rewritten for every input.
  static const std::filesystem::path file =
      std::filesystem::temp_directory_path() /
      ("nsb-fuzz-scene-" + std::to_string(static_cast<long>(::getpid())) + ".toml");
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(scene.data(), static_cast<std::streamsize>(scene.size()));
  }
  try {
    if (override_text.empty()) {
      (void)nsb::scene::load_scene(file);
    } else {
      (void)nsb::scene::load_scene(file, {override_text});
    }
  } catch (const std::invalid_argument&) {
    // bad input, reported as such
  }
  return 0;
}
