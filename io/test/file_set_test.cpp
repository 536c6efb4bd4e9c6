// Tests of files written whole or not at all: a single file through a temporary name, a set
// of files that replaces an older set without ever leaving a mix, and the check before a run.
#include "io/files.hpp"

#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace nsb {
namespace {

std::string read(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::filesystem::path fresh_dir(const std::string& name) {
  auto d = std::filesystem::temp_directory_path() /
           ("nsb-file-set-test-" + std::to_string(::getpid()) + "-" + name);
  std::filesystem::remove_all(d);
  return d;
}

int entries(const std::filesystem::path& dir) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
  return n;
}

}  // namespace

TEST_CASE("write_file_atomically writes the whole text and leaves no temporary") {
  const auto base = fresh_dir("atomic");
  std::filesystem::create_directories(base);
  io::write_file_atomically(base / "a.txt", "old");
  io::write_file_atomically(base / "a.txt", "new text\n");
  CHECK(read(base / "a.txt") == "new text\n");
  CHECK(entries(base) == 1);
  CHECK_THROWS_WITH_AS(io::write_file_atomically(base / "missing" / "b.txt", "x"),
                       doctest::Contains("b.txt"), std::runtime_error);
  CHECK(entries(base) == 1);
  std::filesystem::remove_all(base);
}

TEST_CASE("write_file_set writes a set in order and replaces an older one as a whole") {
  const auto base = fresh_dir("set");
  const auto dir = base / "out";
  io::write_file_set(dir, {{"a.csv", "1"}, {"b.json", "2"}});
  CHECK(read(dir / "a.csv") == "1");
  CHECK(read(dir / "b.json") == "2");
  io::write_file_set(dir, {{"a.csv", "3"}, {"b.json", "4"}});
  CHECK(read(dir / "a.csv") == "3");
  CHECK(entries(base) == 1);  // no staging or old directory left beside it
  CHECK(entries(dir) == 2);
  CHECK_THROWS_WITH_AS(io::write_file_set("", {}), doctest::Contains("empty path"),
                       std::invalid_argument);
  std::filesystem::remove_all(base);
}

TEST_CASE("prepare_output_dir finds before a run what write_file_set would fail on") {
  const auto base = fresh_dir("prepare");
  CHECK_THROWS_WITH_AS(io::prepare_output_dir(""), doctest::Contains("empty path"),
                       std::invalid_argument);
  io::prepare_output_dir(base / "a" / "b");
  CHECK(std::filesystem::is_directory(base / "a" / "b"));
  std::ofstream(base / "file") << "x";
  CHECK_THROWS_WITH_AS(io::prepare_output_dir(base / "file" / "sub"),
                       doctest::Contains("cannot create the directory"), std::invalid_argument);
  CHECK_THROWS_WITH_AS(io::prepare_output_dir(base / "file"),
                       doctest::Contains("cannot create the directory"), std::invalid_argument);
  CHECK(entries(base) == 2);  // "a" and "file": the probe is gone
  std::filesystem::remove_all(base);
}

}  // namespace nsb
