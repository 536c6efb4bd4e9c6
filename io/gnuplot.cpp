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

std::string terminal_for(const std::filesystem::path& picture, const ImageSize& size) {
  std::string ext = picture.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const std::string pixels = std::to_string(size.width) + "," + std::to_string(size.height);
  const std::string font = size.font.empty() ? "" : " font '" + size.font + "'";
  if (ext == ".png") {
    // A gnuplot without cairo (GPVAL_TERMINALS lists what it has) draws with libgd instead.
    return "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size " +
           pixels + font + " } else { set terminal png size " + pixels + " }";
  }
  if (ext == ".svg") return "set terminal svg size " + pixels + font;
  if (ext == ".pdf") {
    // 150 pixels to the inch: the default 900 x 600 is 6 x 4 in.
    const auto inches = [](int px) {
      std::string s = std::to_string(px / 150.0);
      s.erase(s.find_last_not_of('0') + 1);
      if (s.back() == '.') s.pop_back();
      return s + "in";
    };
    return "if (strstrt(GPVAL_TERMINALS, 'pdfcairo') == 0) { exit error 'this gnuplot has no "
           "pdfcairo terminal: draw a .png or .svg' }; set terminal pdfcairo size " +
           inches(size.width) + "," + inches(size.height) + font;
  }
  return {};
}

std::string draw_gnuplot(const std::string& gnuplot, const std::string& script,
                         const std::filesystem::path& picture, const ImageSize& size) {
  const std::string terminal = terminal_for(picture, size);
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
