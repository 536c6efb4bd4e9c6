// Tests of the gnuplot runner with stand-ins for gnuplot: shell scripts that record their
// arguments, so that the test needs no gnuplot and checks exactly what the runner asks for.
#include "io/gnuplot.hpp"

#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace nsb {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  auto d = fs::temp_directory_path() /
           ("nsb-gnuplot-test-" + std::to_string(::getpid()) + "-" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string read(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// An executable shell script at dir/name with the given body.
fs::path script(const fs::path& dir, const std::string& name, const std::string& body) {
  const fs::path p = dir / name;
  std::ofstream(p) << "#!/bin/sh\n" << body;
  fs::permissions(p, fs::perms::owner_all);
  return p;
}

}  // namespace

TEST_CASE("render_gnuplot draws PNG then SVG in dir, with the size and font asked for") {
  const fs::path dir = fresh_dir("ok");
  // Records "-e <terminal and output>" and the script, and writes the output file.
  const fs::path fake = script(dir, "fake gnuplot", "echo \"$2 | $3\" >> calls.txt\n"
                                                    "out=${2##*set output \\'}\n"
                                                    "touch \"${out%\\'}\"\n");
  std::ofstream(dir / "fig.gp") << "plot x\n";
  CHECK(io::render_gnuplot(fake.string(), dir, "fig", {640, 480, ",10"}).empty());
  CHECK(read(dir / "calls.txt") ==
        "set terminal pngcairo size 640,480 font ',10'; set output 'fig.png' | fig.gp\n"
        "set terminal svg size 640,480 font ',10'; set output 'fig.svg' | fig.gp\n");
  CHECK(fs::exists(dir / "fig.png"));
  CHECK(fs::exists(dir / "fig.svg"));
  CHECK(!fs::exists(dir / "fig.png.log"));  // removed once gnuplot succeeded
  fs::remove_all(dir);
}

TEST_CASE("a gnuplot that fails is reported with its log kept") {
  const fs::path dir = fresh_dir("fail");
  const fs::path fake = script(dir, "bad", "echo 'no such terminal' >&2\nexit 1\n");
  std::ofstream(dir / "fig.gp") << "plot x\n";
  CHECK(io::render_gnuplot(fake.string(), dir, "fig") ==
        "fig.png: gnuplot failed (see fig.png.log)");
  CHECK(read(dir / "fig.png.log") == "no such terminal\n");
  CHECK(io::render_gnuplot((dir / "absent").string(), dir, "fig") ==
        "fig.png: gnuplot failed (see fig.png.log)");
  fs::remove_all(dir);
}

TEST_CASE("shell_quote keeps every character, quotes included") {
  CHECK(io::shell_quote("a b") == "'a b'");
  CHECK(io::shell_quote("it's") == "'it'\\''s'");
}

}  // namespace nsb
