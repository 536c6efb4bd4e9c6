#include "io/files.hpp"

#include <algorithm>
#include <atomic>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <utility>
#include <vector>

#include <unistd.h>

namespace nsb::io {

namespace {

namespace fs = std::filesystem;

void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) throw std::runtime_error("cannot open '" + path.string() + "' for writing");
  f.write(text.data(), static_cast<std::streamsize>(text.size()));
  f.flush();
  if (!f) throw std::runtime_error("cannot write '" + path.string() + "'");
}


// The output directory as a path with a last component: "out/ball/" and "out/ball/." name
// "out/ball", "." names the current directory by its own name.
fs::path target_of(const fs::path& dir) {
  std::error_code ec;
  fs::path d = fs::absolute(dir, ec);
  if (ec) d = dir;
  d = d.lexically_normal();
  if (d.filename().empty() && d.has_parent_path() && d != d.root_path()) d = d.parent_path();
  return d;
}

// A fresh name beside target: ".<name>.<tag>-<pid>-<n>", hidden, unique within the process
// (the sweep's worker threads write their sets at the same time).
fs::path beside(const fs::path& target, const char* tag) {
  static std::atomic<int> counter{0};
  std::string name = ".";
  name.append(target.filename().string());
  name.append(".").append(tag).append("-");
  name.append(std::to_string(static_cast<long>(::getpid())));
  name.append("-").append(std::to_string(counter++));
  return target.parent_path() / name;
}

// True when every entry of dir is one of `names`: the directory then holds nothing but a set
// of these outputs, and may be replaced as a whole.
bool holds_only(const fs::path& dir, const std::vector<std::string>& names) {
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string n = it->path().filename().string();
    if (std::find(names.begin(), names.end(), n) == names.end()) return false;
    if (!it->is_regular_file(ec)) return false;
  }
  return !ec;
}

[[noreturn]] void io_error(const std::string& what, const fs::path& p, const std::error_code& ec) {
  throw std::runtime_error(what + " '" + p.string() + "': " + ec.message());
}

}  // namespace

void prepare_output_dir(const std::filesystem::path& dir) {
  if (dir.empty()) throw std::invalid_argument("empty path; expected a directory");
  const fs::path target = target_of(dir);
  std::error_code ec;
  fs::create_directories(target, ec);
  if (ec || !fs::is_directory(target)) {
    throw std::invalid_argument("cannot create the directory '" + target.string() + "': " +
                                (ec ? ec.message() : "a file of that name exists"));
  }
  // write_file_set needs a new directory beside the target and write access to the target.
  const fs::path probe = beside(target, "probe");
  if (!fs::create_directory(probe, ec) || ec) {
    throw std::invalid_argument("cannot write beside '" + target.string() + "' in '" +
                                target.parent_path().string() + "': " +
                                (ec ? ec.message() : "the name is taken"));
  }
  fs::remove(probe, ec);
  if (::access(target.c_str(), W_OK | X_OK) != 0) {
    throw std::invalid_argument("cannot write into '" + target.string() + "': permission denied");
  }
}

void write_file_set(const std::filesystem::path& dir,
                    const std::vector<std::pair<std::string, std::string>>& files) {
  if (dir.empty()) throw std::invalid_argument("empty path; expected a directory");
  const fs::path target = target_of(dir);
  std::error_code ec;
  fs::create_directories(target.parent_path(), ec);
  if (ec) io_error("cannot create the directory", target.parent_path(), ec);

  // 1. Every file, complete, in a new directory beside the target.
  const fs::path staging = beside(target, "tmp");
  if (!fs::create_directory(staging, ec) || ec) io_error("cannot create", staging, ec);
  std::vector<std::string> names;
  try {
    for (const auto& [name, text] : files) {
      write_file(staging / name, text);
      names.push_back(name);
    }
  } catch (...) {
    fs::remove_all(staging, ec);
    throw;
  }

  // 2. The set replaces the old one. A target that is absent, or holds nothing but files of
  // this set, is replaced as a whole by two renames: a reader sees the old set, no directory
  // for an instant, then the new set; never a mix.
  if (!fs::exists(target, ec) || (fs::is_directory(target, ec) && holds_only(target, names))) {
    const fs::path old = beside(target, "old");
    const bool had_old = fs::exists(target, ec);
    if (had_old) {
      fs::rename(target, old, ec);
      if (ec) {
        fs::remove_all(staging, ec);
        io_error("cannot move the previous outputs aside", target, ec);
      }
    }
    fs::rename(staging, target, ec);
    if (ec) {
      const std::error_code failure = ec;
      if (had_old) fs::rename(old, target, ec);
      fs::remove_all(staging, ec);
      io_error("cannot rename '" + staging.string() + "' to", target, failure);
    }
    if (had_old) fs::remove_all(old, ec);
    return;
  }
  // A target that holds other files too (the user's own) keeps them: the files of the set
  // move in one by one, the last one named last, after its old version has been removed
  // first. A set is therefore complete exactly when its last file is present.
  if (!fs::is_directory(target, ec)) {
    fs::remove_all(staging, ec);
    throw std::runtime_error("'" + target.string() + "' is not a directory");
  }
  if (!names.empty()) {
    fs::remove(target / names.back(), ec);
    if (ec) {
      const std::error_code failure = ec;
      fs::remove_all(staging, ec);
      io_error("cannot remove the previous", target / names.back(), failure);
    }
  }
  for (const auto& name : names) {
    fs::rename(staging / name, target / name, ec);
    if (ec) {
      const std::error_code failure = ec;
      fs::remove_all(staging, ec);
      io_error("cannot move '" + (staging / name).string() + "' to", target / name, failure);
    }
  }
  fs::remove_all(staging, ec);
}

void write_file_atomically(const std::filesystem::path& file, const std::string& text) {
  std::string name = ".";
  name += file.filename().string();
  name += ".tmp";
  name += std::to_string(::getpid());
  const std::filesystem::path tmp = file.parent_path() / name;
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    out.close();
    if (!out) {
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw std::runtime_error(file.string() + ": cannot write");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw std::runtime_error(file.string() + ": cannot write (" + ec.message() + ")");
  }
}

}  // namespace nsb::io
