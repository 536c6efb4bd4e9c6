#include "io/gnuplot.hpp"

#include <cstdlib>
#include <system_error>

namespace nsb::io {

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (const char ch : s) out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return out + "'";
}

std::string render_gnuplot(const std::string& gnuplot, const std::filesystem::path& dir,
                           const std::string& stem, const ImageSize& size) {
  const struct {
    const char* terminal;
    const char* ext;
  } outputs[2] = {{"pngcairo", "png"}, {"svg", "svg"}};
  for (const auto& o : outputs) {
    std::string terminal = std::string("set terminal ") + o.terminal + " size " +
                           std::to_string(size.width) + "," + std::to_string(size.height);
    if (!size.font.empty()) terminal += " font '" + size.font + "'";
    const std::string out = stem + "." + o.ext;
    const std::string cmd = "cd " + shell_quote(dir.string()) + " && " + shell_quote(gnuplot) +
                            " -e " + shell_quote(terminal + "; set output '" + out + "'") + ' ' +
                            shell_quote(stem + ".gp") + " > " + shell_quote(out + ".log") +
                            " 2>&1";
    if (std::system(cmd.c_str()) != 0) return out + ": gnuplot failed (see " + out + ".log)";
    std::error_code ec;
    std::filesystem::remove(dir / (out + ".log"), ec);
  }
  return {};
}

}  // namespace nsb::io
