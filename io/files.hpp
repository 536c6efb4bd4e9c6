// Files written so that a reader never sees a partial one: a single file through a temporary
// name and rename, a set of files (one run's outputs) so that its directory never holds a mix
// of an old and a new set.
//
// Where a set goes (docs/cli.md, "Output folders"): the directory named, with every symbolic
// link on its path followed to its target, so that `--out link` renews the folder the link
// points to and the link stays. The set is written, complete, beside that directory and moved
// into place. A directory that is the current directory, or holds it (".", ".."), is never
// renamed or replaced: the files of the set are moved into it one by one.
//
// Every failure to write (a full disk, a quota, a file size limit, a permission lost while a
// run went on) is a WriteError naming the file and the reason, and leaves no partial file.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace nsb::io {

// An output that could not be written: "cannot write '<path>': No space left on device".
// The command line maps it as it maps an unwritable output folder (exit 2, naming the option).
struct WriteError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Where the outputs of dir go: absolute, normalized, every symbolic link followed (a dangling
// link to the place it names). "out/ball/" and "out/ball/." name "out/ball".
std::filesystem::path output_target(const std::filesystem::path& dir);

// True when target (an output_target) is the current directory or one that holds it.
bool holds_current_directory(const std::filesystem::path& target);

// Checks, before a run, that dir can receive its outputs, and creates nothing: an existing dir
// must be a directory this process may write into (and, unless it holds the current
// directory, whose parent it may write into: the set is moved in beside it); an absent one
// needs its nearest existing ancestor to be such a directory. Throws std::invalid_argument
// for an empty path or a place that cannot be created or written.
void check_output_dir(const std::filesystem::path& dir);

// A set of files written beside its directory and moved into place as one by commit().
// Nothing is created before the first add(); a set destroyed without commit() removes what it
// wrote, and the parent directories it made, so a failed or interrupted run leaves nothing
// behind.
class FileSet {
 public:
  explicit FileSet(std::filesystem::path dir);  // throws std::invalid_argument for ""
  ~FileSet();
  FileSet(const FileSet&) = delete;
  FileSet& operator=(const FileSet&) = delete;

  // Writes one file of the set, complete, into the staging directory (".<dir>.tmp-<pid>-<n>"
  // beside dir; inside dir when dir holds the current directory). Throws WriteError naming
  // dir/name, after which the set can only be dropped.
  void add(const std::string& name, const std::string& text);

  // Moves the set into place. A dir that is absent, or holds nothing but files of the set,
  // and does not hold the current directory, is replaced as a whole by two renames: a reader
  // sees the old set, no directory for an instant, then the new set; never a mix. Otherwise
  // (the user's own files are in dir, or it holds the current directory) the files move in
  // one by one, the last of the set removed first and moved last, so that the set is complete
  // exactly when its last file is present. Throws WriteError naming the path, and leaves the
  // previous set in place.
  void commit();

  const std::filesystem::path& target() const { return target_; }

 private:
  void stage();  // creates the staging directory (and dir's parents)
  void drop() noexcept;

  std::filesystem::path target_;
  std::filesystem::path staging_;  // empty until the first add()
  std::vector<std::filesystem::path> made_;  // the parents stage() created, deepest first
  std::vector<std::string> names_;
  bool in_place_ = false;  // target_ holds the current directory: files move in one by one
  bool committed_ = false;
};

// Writes a set of files (name, text) into dir as one (a FileSet).
void write_file_set(const std::filesystem::path& dir,
                    const std::vector<std::pair<std::string, std::string>>& files);

// Writes text to file via a hidden temporary beside it (".<name>.tmp<pid>-<n>") and rename.
// Throws WriteError naming file on failure, after removing the temporary.
void write_file_atomically(const std::filesystem::path& file, const std::string& text);

// The one writer every output goes through: opens path (creating or truncating it), writes
// the whole text, closes it, each step checked. Throws WriteError "cannot write '<shown>':
// <reason>" (shown: the path the user knows the file by; default path). It removes nothing:
// the callers write to temporary names and remove them.
void write_whole_file(const std::filesystem::path& path, const std::string& text,
                      const std::filesystem::path& shown = {});

}  // namespace nsb::io
