// One file per study: DIR/sweep.h5, an HDF5 file (the HDF5 C library) holding every run's
// history, events, summary and row, and the results table, written as the runs finish by the
// process that writes results.csv (docs/outputs.md, "sweep.h5").
//
//   store::StudyStore h5(options.out);        // DIR; the file is opened once DIR is prepared
//   options.observer = &h5;                   // sweep::run_sweep tells it of every run
//   sweep::run_sweep(design_file, options);
//
// Each run's group is made from the files of its folder DIR/runs/<id>/ once they are complete,
// so every number in sweep.h5 is the double its CSV text reads back to (io::csv_number's
// shortest round-trip form). The group is marked done (its attribute `done`, written last) and
// the file flushed before the next run's group is started: a process killed at any moment
// leaves the groups of earlier runs complete. A resume deletes the groups not marked done and
// writes those of the completed runs that lack one; a file that cannot be opened at all (killed
// inside a write) is made again from the run folders.
#pragma once

#include "sweep/runner.hpp"

#include <cstdint>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace nsb::store {

struct RunFiles;  // a run's files, read for its group (study_store.cpp)

// The name of the file in DIR, and the version of its layout (attribute `format_version`).
inline constexpr const char* kFileName = "sweep.h5";
inline constexpr std::int64_t kFormatVersion = 1;

class StudyStore final : public sweep::SweepObserver {
 public:
  // dir: the sweep's folder DIR; restart: the sweep discards the runs of an earlier design
  // (sweep::SweepOptions::restart), and so does the store.
  StudyStore(std::filesystem::path dir, bool restart);
  ~StudyStore() override;
  StudyStore(const StudyStore&) = delete;
  StudyStore& operator=(const StudyStore&) = delete;

  // Opens DIR/sweep.h5, or creates it, and brings it level with the completed runs. Throws
  // std::invalid_argument naming the file when it cannot be created or holds another design's
  // runs (without restart), or when a history column of output.hdf5_history is absent.
  void prepared(const sweep::Design& design,
                const std::vector<std::optional<sweep::Row>>& rows) override;
  // Writes the run's group, marks it done and flushes the file. Thread-safe. Throws
  // io::WriteError naming the file when HDF5 cannot write it (a full disk).
  void finished(std::size_t index, const sweep::Row& row) override;
  // Writes /results, the table results.csv holds.
  void completed(const sweep::Results& table) override;

  std::filesystem::path file() const { return dir_ / kFileName; }
  // Things to tell the user: the file was made again (unreadable, damaged, another history
  // selection).
  const std::vector<std::string>& notes() const { return notes_; }

 private:
  void write_run(std::size_t index, const sweep::Row& row, const RunFiles& files);
  // In an existing file: deletes /results and the group of every run not finished (no "done"
  // flag) or not finished now (no row); kept[i] says whether run i's group stays. False when
  // HDF5 cannot delete one (a group a killed process left half written).
  bool keep_finished_groups(const sweep::Design& design,
                            const std::vector<std::optional<sweep::Row>>& rows,
                            std::vector<bool>& kept);

  std::filesystem::path dir_;
  bool restart_ = false;
  const sweep::Design* design_ = nullptr;
  std::int64_t file_ = -1;  // hid_t of the open file; -1: none
  std::mutex mutex_;        // one HDF5 call at a time, from any worker thread
  std::vector<std::string> notes_;
};

// What output.hdf5_history says, as the file's attribute `hdf5_history` records it: "all",
// "none", or the kept columns joined by commas.
std::string history_selection(const sweep::OutputSpec& output);

}  // namespace nsb::store
