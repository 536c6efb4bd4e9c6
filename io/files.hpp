// Files written so that a reader never sees a partial one: a single file through a temporary
// name and rename, a set of files (one run's outputs) so that its directory never holds a mix
// of an old and a new set.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace nsb::io {

// Checks, before a run, that dir can receive its outputs: creates it (and its parents) and
// probes that a directory can be made beside it and files written into it. Throws
// std::invalid_argument for an empty path or a place that cannot be created or written.
void prepare_output_dir(const std::filesystem::path& dir);

// Writes a set of files (name, text) into dir so that dir never holds a mixed set of old and
// new files. The files are written, complete, into a new hidden directory beside dir
// (".<dir>.tmp-<pid>-<n>"), which then replaces dir by rename when dir is absent or holds
// nothing but files of the set. When dir holds other files too, they are kept: the files of
// the set are moved in one by one, the last of the list removed first and moved last, so that
// the set is complete exactly when its last file is present. Throws std::runtime_error naming
// the path on I/O failure, and leaves the previous set in place.
void write_file_set(const std::filesystem::path& dir,
                    const std::vector<std::pair<std::string, std::string>>& files);

// Writes text to file via ".<name>.tmp<pid>" beside it and rename. Throws std::runtime_error
// naming the path on failure, after removing the temporary.
void write_file_atomically(const std::filesystem::path& file, const std::string& text);

}  // namespace nsb::io
