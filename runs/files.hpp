// The files of one run: history.csv, events.csv and summary.json. Their columns and keys are
// a stable contract, documented in docs/outputs.md.
#pragma once

#include "integrators/recorder.hpp"
#include "runs/run.hpp"

#include <filesystem>
#include <string>

namespace nsb::runs {

// history.csv, events.csv and summary.json (last) into dir, as one set
// (io::write_file_set): dir never holds a mix of an old and a new set. Throws
// std::runtime_error naming the path on I/O failure.
void write_record(const std::filesystem::path& dir, const RunRecord& record);

// The text of each file, for tests and for callers that write elsewhere.
std::string history_csv(const integrators::Recorder& history);
std::string events_csv(const integrators::Recorder& history);
// summary.json formats the record: its result, its number of samples and its digest.
std::string summary_json(const RunRecord& record);

}  // namespace nsb::runs
