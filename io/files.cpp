#include "io/files.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <system_error>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

namespace nsb::io {

namespace {

namespace fs = std::filesystem;

[[noreturn]] void write_failed(const fs::path& shown, int error) {
  throw WriteError("cannot write '" + shown.string() +
                   "': " + std::generic_category().message(error));
}

[[noreturn]] void io_error(const std::string& what, const fs::path& p, const std::error_code& ec) {
  throw WriteError(what + " '" + p.string() + "': " + ec.message());
}

// A fresh hidden name: ".<name>.<tag>-<pid>-<n>", unique within the process (the sweep's
// worker threads write their sets at the same time) and across processes.
std::string fresh_name(const std::string& name, const char* tag) {
  static std::atomic<int> counter{0};
  std::string out = ".";
  out.append(name).append(".").append(tag).append("-");
  out.append(std::to_string(static_cast<long>(::getpid())));
  out.append("-").append(std::to_string(counter++));
  return out;
}

// ".<name>.<tag>-<pid>-<n>" beside target.
fs::path beside(const fs::path& target, const char* tag) {
  return target.parent_path() / fresh_name(target.filename().string(), tag);
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

// access(2) for writing and entering; the reason when not.
bool writable(const fs::path& dir, std::string& reason) {
  if (::access(dir.c_str(), W_OK | X_OK) == 0) return true;
  reason = std::generic_category().message(errno);
  return false;
}

}  // namespace

fs::path output_target(const fs::path& dir) {
  std::error_code ec;
  fs::path d = fs::absolute(dir, ec);
  if (ec) d = dir;
  d = d.lexically_normal();
  if (d.filename().empty() && d.has_parent_path() && d != d.root_path()) d = d.parent_path();
  // weakly_canonical follows every link of the existing part of the path; a dangling link at
  // the end is left as it is, so it is followed here, to the place it names.
  constexpr int kMaxLinks = 40;  // as the kernel's limit on links in one lookup (ELOOP)
  for (int hops = 0; hops < kMaxLinks; ++hops) {
    const fs::path w = fs::weakly_canonical(d, ec);
    if (ec) return d;
    if (!fs::is_symlink(w, ec)) return w;
    const fs::path to = fs::read_symlink(w, ec);
    if (ec) return w;
    d = (to.is_absolute() ? to : w.parent_path() / to).lexically_normal();
  }
  return d;
}

bool holds_current_directory(const fs::path& target) {
  std::error_code ec;
  const fs::path cwd = fs::current_path(ec);
  if (ec) return false;
  auto c = cwd.begin();
  for (const fs::path& part : target) {
    if (c == cwd.end() || *c != part) return false;
    ++c;
  }
  return true;
}

void check_output_dir(const fs::path& dir) {
  if (dir.empty()) throw std::invalid_argument("empty path; expected a directory");
  const fs::path target = output_target(dir);
  std::error_code ec;
  std::string reason;
  const fs::file_status st = fs::status(target, ec);
  if (fs::exists(st)) {
    if (!fs::is_directory(st)) {
      throw std::invalid_argument("cannot create the directory '" + target.string() +
                                  "': a file of that name exists");
    }
    if (!writable(target, reason)) {
      throw std::invalid_argument("cannot write into '" + target.string() + "': " + reason);
    }
    // The set is written beside the directory and renamed into place.
    if (!holds_current_directory(target) && !writable(target.parent_path(), reason)) {
      throw std::invalid_argument("cannot write beside '" + target.string() + "' in '" +
                                  target.parent_path().string() + "': " + reason);
    }
    return;
  }
  // An absent directory is made, with its parents, in its nearest existing ancestor.
  fs::path ancestor = target.parent_path();
  while (ancestor.has_relative_path() && !fs::exists(fs::status(ancestor, ec)))
    ancestor = ancestor.parent_path();
  if (!fs::is_directory(fs::status(ancestor, ec))) {
    throw std::invalid_argument("cannot create the directory '" + target.string() +
                                "': Not a directory");
  }
  if (!writable(ancestor, reason)) {
    throw std::invalid_argument("cannot create the directory '" + target.string() + "': " +
                                reason + " (in '" + ancestor.string() + "')");
  }
}

FileSet::FileSet(fs::path dir) {
  if (dir.empty()) throw std::invalid_argument("empty path; expected a directory");
  target_ = output_target(dir);
  in_place_ = holds_current_directory(target_);
}

FileSet::~FileSet() { drop(); }

void FileSet::drop() noexcept {
  std::error_code ec;
  if (!staging_.empty()) fs::remove_all(staging_, ec);
  staging_.clear();
  // fs::remove removes only an empty directory: one that received something else is kept.
  if (!committed_) {
    for (const fs::path& d : made_) fs::remove(d, ec);
  }
  made_.clear();
}

void FileSet::stage() {
  std::error_code ec;
  if (in_place_) {
    // The current directory (or one that holds it) is written into, never replaced: the
    // staging directory is inside it, on the same file system as the files' places.
    staging_ = target_ / fresh_name("nsbridge", "tmp");
  } else {
    for (fs::path d = target_.parent_path(); d.has_relative_path() && !fs::exists(d, ec);
         d = d.parent_path()) {
      made_.push_back(d);
    }
    fs::create_directories(target_.parent_path(), ec);
    if (ec) io_error("cannot create the directory", target_.parent_path(), ec);
    staging_ = beside(target_, "tmp");
  }
  if (!fs::create_directory(staging_, ec) || ec) {
    const fs::path failed = staging_;
    staging_.clear();
    io_error("cannot create", failed, ec ? ec : std::make_error_code(std::errc::file_exists));
  }
}

void FileSet::add(const std::string& name, const std::string& text) {
  if (staging_.empty()) stage();
  write_whole_file(staging_ / name, text, target_ / name);
  names_.push_back(name);
}

void FileSet::commit() {
  if (staging_.empty()) stage();
  std::error_code ec;
  const fs::path& target = target_;
  // A target that is absent, or holds nothing but files of this set, is replaced as a whole
  // by two renames.
  const bool exists = fs::exists(target, ec);
  if (!in_place_ && (!exists || (fs::is_directory(target, ec) && holds_only(target, names_)))) {
    const fs::path old = beside(target, "old");
    if (exists) {
      fs::rename(target, old, ec);
      if (ec) io_error("cannot move the previous outputs aside:", target, ec);
    }
    fs::rename(staging_, target, ec);
    if (ec) {
      const std::error_code failure = ec;
      if (exists) fs::rename(old, target, ec);
      io_error("cannot rename '" + staging_.string() + "' to", target, failure);
    }
    staging_.clear();
    if (exists) fs::remove_all(old, ec);
    committed_ = true;
    return;
  }
  // A target that holds other files too (the user's own), or the current directory, keeps
  // them: the files of the set move in one by one, the last one named last, after its old
  // version has been removed first. A set is therefore complete exactly when its last file is
  // present.
  if (!fs::is_directory(target, ec)) throw WriteError("'" + target.string() + "' is not a directory");
  if (!names_.empty()) {
    fs::remove(target / names_.back(), ec);
    if (ec) io_error("cannot remove the previous", target / names_.back(), ec);
  }
  for (const auto& name : names_) {
    fs::rename(staging_ / name, target / name, ec);
    if (ec) io_error("cannot move '" + (staging_ / name).string() + "' to", target / name, ec);
  }
  committed_ = true;
  drop();
}

void write_file_set(const fs::path& dir,
                    const std::vector<std::pair<std::string, std::string>>& files) {
  FileSet set(dir);
  for (const auto& [name, text] : files) set.add(name, text);
  set.commit();
}

void write_file_atomically(const fs::path& file, const std::string& text) {
  const fs::path tmp = file.parent_path() / fresh_name(file.filename().string(), "tmp");
  std::error_code ec;
  try {
    write_whole_file(tmp, text, file);
  } catch (const WriteError&) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, file, ec);
  if (ec) {
    const std::error_code failure = ec;
    fs::remove(tmp, ec);
    io_error("cannot write", file, failure);
  }
}

void write_whole_file(const fs::path& path, const std::string& text, const fs::path& shown) {
  const fs::path& named = shown.empty() ? path : shown;
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) write_failed(named, errno);
  const char* p = text.data();
  std::size_t left = text.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = n < 0 ? errno : EIO;
      ::close(fd);
      write_failed(named, error);
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  // close(2) reports what a file system defers (NFS, quotas) to it.
  if (::close(fd) != 0) write_failed(named, errno);
}

}  // namespace nsb::io
