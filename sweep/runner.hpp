// Running a sweep: every run of a design is an ordinary runs::execute() call with its own
// outputs under DIR/runs/<id>/ (runs::write_record), on a pool of threads or on MPI ranks;
// DIR/results.csv gathers one row per run, sorted by run id, and does not depend on how the
// runs were distributed (docs/sweep.md).
#pragma once

#include "sweep/design.hpp"
#include "sweep/results.hpp"

#include <atomic>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace nsb::sweep {

// What a sweep tells a store of its runs (store/, DIR/sweep.h5), on the one process that
// writes results.csv (MPI rank 0). An exception it throws ends the sweep as a failed write
// does (run_threaded); the runs complete so far stay and a rerun resumes.
class SweepObserver {
 public:
  virtual ~SweepObserver() = default;
  // DIR is prepared (sweep::prepare), before any run: rows[i] is set for each run whose
  // outputs are complete in DIR. May throw std::invalid_argument (exit 2, nothing run).
  virtual void prepared(const Design& design, const std::vector<std::optional<Row>>& rows) = 0;
  // Run `index` is finished: its outputs and resume files are complete in DIR/runs/<id>/.
  // Called from any worker thread, possibly from several at once.
  virtual void finished(std::size_t index, const Row& row) = 0;
  // results.csv was written from `table`, after every run.
  virtual void completed(const Results& table) = 0;
};

struct SweepOptions {
  std::filesystem::path out;     // the sweep's folder DIR (created if needed)
  int jobs = 0;                  // worker threads per process, >= 0; 0 = all cores (under MPI:
                                 //   the cores divided among the ranks of one machine)
  bool restart = false;          // discard the runs of an earlier, different design in DIR
  bool progress = true;          // draw a progress bar on stderr when it is a terminal
  std::vector<std::string> set;  // overrides added to the design's `set` for every run
  std::atomic<bool>* stop = nullptr;  // a stop request (Ctrl-C), read by every run
                                      //   (runs::RunRequest::stop); the runs then under way
                                      //   end as interrupted and write nothing, no new run
                                      //   starts. The sweep sets it itself when a run cannot
                                      //   write its outputs. Not owned; nullptr: none
  SweepObserver* observer = nullptr;  // told of the runs as they finish (rank 0 only); not
                                      //   owned; nullptr: none
  void validate() const;         // throws std::invalid_argument naming the field
};

// What a sweep did. Counts refer to the runs of the design.
struct SweepSummary {
  std::size_t runs = 0;            // runs in the design
  std::size_t already_done = 0;    // found complete in DIR and skipped
  std::size_t ran = 0;             // run now
  std::size_t failed = 0;          // rows whose status is not a completed one (all rows)
  int workers = 0;                 // threads over all processes
  int ranks = 1;                   // MPI processes (1 without MPI)
  std::size_t ran_elsewhere = 0;   // of `ran`, the runs made by MPI ranks other than 0
  bool primary = true;             // false on MPI ranks other than 0: they print nothing
  std::vector<std::string> notes;  // things to tell the user (revision changed, MPI absent)
  std::filesystem::path results;   // DIR/results.csv
  bool interrupted = false;        // a stop request ended the sweep: results.csv was not
                                   //   written, a rerun resumes
  std::size_t complete = 0;        // runs complete in DIR (those of earlier sweeps included)
  Results table;                   // what results.csv holds (empty on ranks other than 0)
  Design design;                   // the design as loaded, its base scene read once
};

// One run: runs::execute with the run's overrides, its outputs (runs::write_record, the same
// files and warnings as `nsbridge run`) into DIR/runs/<id>/, and its typed row, whose resume
// files row.csv and limit_states.csv (sweep/results.hpp) go beside them (each atomically). A
// numerical failure is a row with its status; a scene that rejects the run's combination of
// values is a row with status "rejected". Throws std::runtime_error only when the outputs
// cannot be written (io::WriteError). on_record, when given, sees the run's record (not for a
// rejected run) before it is dropped, from the worker thread that made it. A run that stop
// (RunRequest::stop) interrupted writes nothing and has no row: `interrupted`.
using RecordSink = std::function<void(std::size_t index, const runs::RunRecord& record)>;
struct RunOutcome {
  Row row;
  bool succeeded = false;  // a completed or unseated status (integrators::is_result)
  bool interrupted = false;  // stopped by a stop request: no row, nothing written
};
RunOutcome run_one(const Design& design, std::size_t index, const std::filesystem::path& out,
                   const RecordSink& on_record = {}, const std::atomic<bool>* stop = nullptr);

// The state of DIR before the runs: which are already complete (their rows), which remain.
struct Plan {
  std::vector<std::optional<Row>> rows;  // one per run; set for completed runs
  std::vector<std::size_t> pending;      // indices still to run, ascending
  std::vector<std::string> notes;
};
// Prepares DIR for a design: records the design's hash, the code revision and the content hash
// of every input in DIR/manifest.toml, and reads the rows of completed runs from their resume
// files (the only files of a sweep it reads back). A DIR holding a different design, or made
// from an input whose content has changed since (the message names the file), is refused
// (std::invalid_argument) before anything is written, unless options.restart, which removes
// its runs first.
Plan prepare(const Design& design, const SweepOptions& options);

// Writes DIR/results.csv from every row (sorted by run id), via a temporary file and rename,
// and returns the table it was written from.
Results write_results(const Design& design, const SweepOptions& options,
                      const std::vector<std::optional<Row>>& rows);

// Reports progress: runs done and failed so far (of the total). Called from one thread at a
// time; may be empty.
using SweepProgress = std::function<void(std::size_t done, std::size_t failed, std::size_t total)>;

// Runs the pending runs of plan on `threads` workers that take the next index from one
// atomic counter, filling plan.rows (on_record: as run_one). Returns the number of failed
// runs among them. options.stop ends it early (an interrupted run leaves its row empty); the
// first exception of a run (io::WriteError) stops the others the same way and is rethrown.
std::size_t run_threaded(const Design& design, const SweepOptions& options, Plan& plan, int threads,
                         const SweepProgress& progress, const RecordSink& on_record = {});

// The whole sweep: validate, prepare, run (threaded, or over MPI when the process was started
// by mpirun and MPI is built in), write results.csv. Throws std::invalid_argument for a bad
// design or options, before any run.
SweepSummary run_sweep(const std::filesystem::path& design_file, const SweepOptions& options);

// True when nsbridge was built with MPI.
bool mpi_built_in();

// The code revision recorded in manifest.toml: io::build_info().revision, taken at build time.
std::string code_revision();

// Rows whose status is not a result (integrators::is_result), "rejected" included.
std::size_t count_failed(const std::vector<std::optional<Row>>& rows);

// A progress bar on stderr (terminal only): runs done, failed, estimated time left.
class ProgressBar {
 public:
  // already: runs complete before this session, left out of the rate that estimates the time.
  ProgressBar(bool enabled, std::size_t already);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  void update(std::size_t done, std::size_t failed, std::size_t total);
  bool enabled() const { return enabled_; }

 private:
  bool enabled_;
  bool drawn_ = false;
  std::size_t already_;
  double start_;
  double last_ = -1.0;
};

}  // namespace nsb::sweep
