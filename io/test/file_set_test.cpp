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

TEST_CASE("check_output_dir finds before a run what write_file_set would fail on, and creates nothing") {
  const auto base = fresh_dir("check");
  std::filesystem::create_directories(base);
  CHECK_THROWS_WITH_AS(io::check_output_dir(""), doctest::Contains("empty path"),
                       std::invalid_argument);
  io::check_output_dir(base / "a" / "b");
  CHECK(!std::filesystem::exists(base / "a"));  // made only when the outputs move in
  std::ofstream(base / "file") << "x";
  CHECK_THROWS_WITH_AS(io::check_output_dir(base / "file" / "sub"),
                       doctest::Contains("cannot create the directory"), std::invalid_argument);
  CHECK_THROWS_WITH_AS(io::check_output_dir(base / "file"),
                       doctest::Contains("cannot create the directory"), std::invalid_argument);
  CHECK(entries(base) == 1);
  std::filesystem::remove_all(base);
}

TEST_CASE("the one writer reports a full disk with the file and the reason") {
  // /dev/full accepts open(2) and fails every write(2) with ENOSPC, as a full disk does.
  if (!std::filesystem::exists("/dev/full")) return;
  CHECK_THROWS_WITH_AS(io::write_whole_file("/dev/full", std::string(100, 'x'), "out/history.csv"),
                       "cannot write 'out/history.csv': No space left on device", io::WriteError);
  // Nothing written is nothing to fail on: an empty text only opens and closes.
  CHECK_NOTHROW(io::write_whole_file("/dev/full", ""));
}

TEST_CASE("a set that is dropped before commit leaves nothing, not even its parents") {
  const auto base = fresh_dir("drop");
  std::filesystem::create_directories(base);
  {
    io::FileSet set(base / "out");
    set.add("a.csv", "1");
    CHECK(entries(base) == 1);  // the staging directory, beside the target
  }
  CHECK(entries(base) == 0);
  { io::FileSet unused(base / "deep" / "out"); }
  CHECK(entries(base) == 0);  // nothing added: nothing created
  std::filesystem::remove_all(base);
}

TEST_CASE("a set for a symbolic link goes to the folder the link points to") {
  const auto base = fresh_dir("link");
  io::write_file_set(base / "real", {{"a.csv", "old"}});
  std::filesystem::create_directory_symlink("real", base / "link");
  io::write_file_set(base / "link", {{"a.csv", "new"}});
  CHECK(std::filesystem::is_symlink(base / "link"));
  CHECK(read(base / "real" / "a.csv") == "new");
  CHECK(entries(base) == 2);
  CHECK(io::output_target(base / "link") == std::filesystem::canonical(base / "real"));
  std::filesystem::remove_all(base);
}

TEST_CASE("a set for the current directory is moved into it, never in its place") {
  const auto base = fresh_dir("cwd");
  std::filesystem::create_directories(base / "sub");
  const auto before = std::filesystem::current_path();
  std::filesystem::current_path(base / "sub");
  CHECK(io::holds_current_directory(io::output_target(".")));
  CHECK(io::holds_current_directory(io::output_target("..")));
  CHECK(!io::holds_current_directory(io::output_target("other")));
  io::write_file_set(".", {{"a.csv", "1"}, {"b.json", "2"}});
  io::write_file_set("..", {{"a.csv", "3"}});
  // The directory is the same one: a replaced one would be gone from its parent's listing
  // while this process still stood in it.
  CHECK(std::filesystem::equivalent(std::filesystem::current_path(), base / "sub"));
  CHECK(read(base / "sub" / "a.csv") == "1");
  CHECK(read(base / "a.csv") == "3");
  CHECK(entries(base / "sub") == 2);  // no staging left inside
  CHECK(entries(base) == 2);          // "sub" and a.csv
  std::filesystem::current_path(before);
  std::filesystem::remove_all(base);
}

}  // namespace nsb
