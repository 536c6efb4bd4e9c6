// nsbridge --version: what a bug report needs to reproduce a result.
#include "app/commands.hpp"

#include "io/build_info.hpp"

#include <CLI/Version.hpp>

#include <string>

namespace nsb::app {

namespace {

// "<name>" padded to the width of the other labels, then the value.
std::string line(const std::string& name, const std::string& value) {
  constexpr std::size_t kWidth = 11;
  return name + std::string(name.size() < kWidth ? kWidth - name.size() : 1, ' ') + value;
}

}  // namespace

std::string version_text() {
  const io::BuildInfo& b = io::build_info();
  std::string text = "nsbridge " + b.version + "\n" + line("revision", b.revision) +
                     " (git, at build time)\n" + line("build", b.build_type) + "\n" +
                     line("compiler", b.compiler) + "\n";
  // The engine's libraries (io::build_info), then the command line's own.
  for (const auto& [name, version] : b.libraries) text += line(name, version) + "\n";
  return text + line("CLI11", CLI11_VERSION);
}

}  // namespace nsb::app
