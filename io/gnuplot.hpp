// Drawing a figure with gnuplot: one script, rendered twice, as PNG (pngcairo) and as SVG.
#pragma once

#include <filesystem>
#include <string>

namespace nsb::io {

// The picture's size [pixels] and font ("name,size"; empty: gnuplot's default).
struct ImageSize {
  int width = 900;
  int height = 600;
  std::string font;
};

// Runs `gnuplot` (an executable on PATH, or a path) in dir on <stem>.gp, once with
// "set terminal pngcairo size W,H; set output '<stem>.png'" and once with the svg terminal,
// the script setting everything else. gnuplot's messages go to <stem>.<ext>.log, removed when
// it succeeds. Returns an empty string, or what failed: "<stem>.<ext>: gnuplot failed (see
// <stem>.<ext>.log)".
std::string render_gnuplot(const std::string& gnuplot, const std::filesystem::path& dir,
                           const std::string& stem, const ImageSize& size = {});

// The gnuplot terminal for a picture file of the given size, chosen by its extension (any
// case): .png pngcairo (libgd's png where this gnuplot has no cairo terminals), .svg svg,
// .pdf pdfcairo (W/150 by H/150 inches; gnuplot stops with "this gnuplot has no pdfcairo
// terminal" where it has none, as Debian's gnuplot-nox built without cairo). Empty for
// another extension.
std::string terminal_for(const std::filesystem::path& picture, const ImageSize& size = {});

// Draws one picture: writes `script` (everything but the terminal and output) into a hidden
// file beside `picture`, runs gnuplot on it with terminal_for(picture, size), and removes the
// script and gnuplot's log. Returns an empty string, or what failed (with the log's first
// line); a failed drawing leaves no file behind.
std::string draw_gnuplot(const std::string& gnuplot, const std::string& script,
                         const std::filesystem::path& picture, const ImageSize& size = {});

// s as a gnuplot string literal: in double quotes, with '"' and '\\' escaped.
std::string gnuplot_string(const std::string& s);

// s quoted for the POSIX shell.
std::string shell_quote(const std::string& s);

}  // namespace nsb::io
