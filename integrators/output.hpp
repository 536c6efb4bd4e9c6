// The files of one run: history.csv, events.csv and summary.json. Their columns and keys are
// a stable contract, documented in docs/outputs.md.
#pragma once

#include "integrators/recorder.hpp"

#include <filesystem>
#include <string>

namespace nsb::integrators {

// Writes history.csv, events.csv and summary.json into dir (created if needed), each via a
// temporary name and rename. Throws std::runtime_error naming the path on I/O failure.
// All three files are written under temporary names before any is renamed, so a failure
// leaves no partial file (earlier complete outputs of the same names are left untouched).
void write_outputs(const std::filesystem::path& dir, const std::string& scene_name,
                   const Recorder& recorder, const RunResult& stats);

// The text of each file, for tests and for callers that write elsewhere.
std::string history_csv(const Recorder& recorder);
std::string events_csv(const Recorder& recorder);
std::string summary_json(const std::string& scene_name, const Recorder& recorder,
                         const RunResult& stats);

}  // namespace nsb::integrators
