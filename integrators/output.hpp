// The files of one run: history.csv, events.csv and summary.json. Their columns and keys are
// a stable contract, documented in docs/outputs.md.
#pragma once

#include "integrators/recorder.hpp"

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace nsb::integrators {

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

// history.csv, events.csv and summary.json (last) into dir through write_file_set.
void write_outputs(const std::filesystem::path& dir, const std::string& scene_name,
                   const Recorder& recorder, const RunResult& stats);

// The text of each file, for tests and for callers that write elsewhere.
std::string history_csv(const Recorder& recorder);
std::string events_csv(const Recorder& recorder);
std::string summary_json(const std::string& scene_name, const Recorder& recorder,
                         const RunResult& stats);

}  // namespace nsb::integrators
