#include "io/gnuplot.hpp"

#include "io/files.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <system_error>

namespace nsb::io {

std::string gnuplot_string(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + '"';
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (const char ch : s) out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return out + "'";
}

namespace {

// Runs gnuplot in dir on script with the terminal and output set first; its messages go to
// <output>.log, removed when it succeeds. Returns an empty string or what failed.
std::string run_gnuplot(const std::string& gnuplot, const std::filesystem::path& dir,
                        const std::string& script, const std::string& terminal,
                        const std::string& output) {
  const std::string cmd = "cd " + shell_quote(dir.string()) + " && " + shell_quote(gnuplot) +
                          " -e " + shell_quote(terminal + "; set output '" + output + "'") + ' ' +
                          shell_quote(script) + " > " + shell_quote(output + ".log") + " 2>&1";
  if (std::system(cmd.c_str()) != 0) return output + ": gnuplot failed (see " + output + ".log)";
  std::error_code ec;
  std::filesystem::remove(dir / (output + ".log"), ec);
  return {};
}

}  // namespace

std::string terminal_for(const std::filesystem::path& picture) {
  std::string ext = picture.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".png") return "set terminal pngcairo size 900,600";
  if (ext == ".svg") return "set terminal svg size 900,600";
  if (ext == ".pdf") return "set terminal pdfcairo size 6in,4in";
  return {};
}

std::string draw_gnuplot(const std::string& gnuplot, const std::string& script,
                         const std::filesystem::path& picture) {
  const std::string terminal = terminal_for(picture);
  if (terminal.empty()) return picture.string() + ": expected a .png, .svg or .pdf file";
  const std::filesystem::path dir =
      picture.parent_path().empty() ? std::filesystem::path(".") : picture.parent_path();
  const std::string name = picture.filename().string();
  const std::string script_name = "." + name + ".gp";
  write_file_atomically(dir / script_name, script);
  std::string failed = run_gnuplot(gnuplot, dir, script_name, terminal, name);
  std::error_code ec;
  std::filesystem::remove(dir / script_name, ec);
  if (!failed.empty()) {
    // Nothing is left beside the picture: the log's first line goes into the message.
    std::ifstream log(dir / (name + ".log"));
    std::string first;
    std::getline(log, first);
    failed = name + ": gnuplot failed" + (first.empty() ? "" : ": " + first);
    std::filesystem::remove(dir / (name + ".log"), ec);
    std::filesystem::remove(picture, ec);
  }
  return failed;
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
    std::string failed = run_gnuplot(gnuplot, dir, stem + ".gp", terminal, stem + "." + o.ext);
    if (!failed.empty()) return failed;
  }
  return {};
}

}  // namespace nsb::io
