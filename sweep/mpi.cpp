// The sweep over MPI ranks (built only when MPI is found). Dynamic distribution: every worker
// asks rank 0 for the next run index when it is free, so runs of unequal cost balance
// themselves; its request carries the row of the run it just finished (as its resume files
// say it: sweep/results.hpp), so the rows gather on rank 0 without a shared file system.
#include "sweep/mpi.hpp"

#include "sweep/csv.hpp"

#include <mpi.h>

#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace nsb::sweep {

namespace {

namespace fs = std::filesystem;

constexpr int kRequestTag = 1;      // worker -> rank 0: "<thread> <index> <state>\n<row>\0
                                    //   <limit_states.csv>" (a message may span lines)
constexpr int kReplyTagBase = 100;  // rank 0 -> worker thread t: the next index, tag base + t

// What a finished run reports with its request (the first request reports none).
enum class Report : int { kNone = 0, kSucceeded = 1, kFailed = 2, kError = 3 };

class Session {
 public:
  Session() {
    int provided = MPI_THREAD_SINGLE;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_MULTIPLE, &provided);
    multiple_ = provided >= MPI_THREAD_MULTIPLE;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  ~Session() { MPI_Finalize(); }
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool multiple() const { return multiple_; }

 private:
  int rank_ = 0, size_ = 1;
  bool multiple_ = false;
};

std::string message(int thread, long long index, Report r, const std::string& text) {
  return std::to_string(thread) + " " + std::to_string(index) + " " +
         std::to_string(static_cast<int>(r)) + "\n" + text;
}

// A worker on a rank other than 0: ask, run, report, until rank 0 answers -1.
void remote_worker(const Design& d, const SweepOptions& options, int thread) {
  std::string out = message(thread, -1, Report::kNone, "");
  for (;;) {
    MPI_Send(out.data(), static_cast<int>(out.size()), MPI_CHAR, 0, kRequestTag, MPI_COMM_WORLD);
    long long index = -1;
    MPI_Recv(&index, 1, MPI_LONG_LONG, 0, kReplyTagBase + thread, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    if (index < 0) return;
    try {
      const RunOutcome o = run_one(d, static_cast<std::size_t>(index), options.out);
      out = message(thread, index, o.succeeded ? Report::kSucceeded : Report::kFailed,
                    row_line(d, o.row) + '\0' + limit_states_csv(o.row.limit_states));
    } catch (const std::exception& e) {
      out = message(thread, index, Report::kError, e.what());
    }
  }
}

// Every rank reads the design; rank 0 alone validates it and prepares DIR. A failure anywhere
// stops every rank before any run: rank 0 throws it, the others return false.
bool load_everywhere(const Session& mpi, const fs::path& design_file, const SweepOptions& options,
                     Design& d, Plan& plan) {
  const bool primary = mpi.rank() == 0;
  std::exception_ptr error;
  int code = 0;
  try {
    d = load_design(design_file, options.set);
    if (primary) {
      validate_design(d);
      plan = prepare(d, options);
      if (options.observer != nullptr) options.observer->prepared(d, plan.rows);
    }
  } catch (...) {
    error = std::current_exception();
    code = 1;
  }
  int any = 0;
  MPI_Allreduce(&code, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  if (any == 0) return true;
  if (!primary) return false;
  if (error) std::rethrow_exception(error);
  throw std::invalid_argument(design_file.string() + ": another MPI rank could not read it");
}

// Rank 0 while the runs go on: the pending indices handed out one at a time to its own
// workers and to the other ranks', the rows gathered, the first error kept.
struct Dispatch {
  Dispatch(Plan& p, SweepObserver* o) : plan(p), observer(o) {}
  Plan& plan;
  SweepObserver* observer;
  std::atomic<std::size_t> next{0}, done{0}, failed{0};
  std::atomic<int> local_exited{0};
  std::atomic<bool> stop{false};
  std::mutex error_mutex;
  std::exception_ptr error;   // of a run on rank 0
  std::string remote_error;   // of a run on another rank
  std::size_t ran_elsewhere = 0;

  // The next pending run index, or -1 when none is left or a run threw.
  long long take() {
    if (stop.load()) return -1;
    const std::size_t k = next.fetch_add(1);
    return k < plan.pending.size() ? static_cast<long long>(plan.pending[k]) : -1;
  }
};

// A worker thread of rank 0: takes indices from the same counter as the other ranks.
void local_worker(Dispatch& work, const Design& d, const SweepOptions& options) {
  for (long long index = work.take(); index >= 0; index = work.take()) {
    try {
      RunOutcome o = run_one(d, static_cast<std::size_t>(index), options.out);
      work.plan.rows[static_cast<std::size_t>(index)] = std::move(o.row);
      if (!o.succeeded) work.failed.fetch_add(1);
      if (options.observer != nullptr)
        options.observer->finished(static_cast<std::size_t>(index),
                                   *work.plan.rows[static_cast<std::size_t>(index)]);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(work.error_mutex);
      if (!work.error) work.error = std::current_exception();
      work.stop.store(true);
    }
    work.done.fetch_add(1);
  }
  work.local_exited.fetch_add(1);
}

// Answers one request of a remote worker (status: its probe): records the row of the run it
// reports, and replies with the next index (-1: stop, and the worker counts as gone).
void serve(Dispatch& work, const Design& d, const MPI_Status& status, int& remote_active) {
  int size = 0;
  MPI_Get_count(&status, MPI_CHAR, &size);
  std::string in(static_cast<std::size_t>(size), '\0');
  MPI_Recv(in.data(), size, MPI_CHAR, status.MPI_SOURCE, kRequestTag, MPI_COMM_WORLD,
           MPI_STATUS_IGNORE);
  std::istringstream head(in.substr(0, in.find('\n')));
  int thread = 0, report = 0;
  long long index = -1;
  head >> thread >> index >> report;
  const std::string text = in.substr(in.find('\n') + 1);
  if (index >= 0) {
    if (static_cast<Report>(report) == Report::kError) {
      const std::lock_guard<std::mutex> lock(work.error_mutex);
      if (work.remote_error.empty())
        work.remote_error = "rank " + std::to_string(status.MPI_SOURCE) + ": " + text;
      work.stop.store(true);
    } else {
      const std::size_t at = text.find('\0');
      auto& row = work.plan.rows[static_cast<std::size_t>(index)];
      row = parse_row(d, static_cast<std::size_t>(index), text.substr(0, at), text.substr(at + 1));
      ++work.ran_elsewhere;
      if (static_cast<Report>(report) == Report::kFailed) work.failed.fetch_add(1);
      // The run's outputs are on the file system all ranks share (docs/sweep.md, "Workers").
      if (work.observer != nullptr && row) {
        try {
          work.observer->finished(static_cast<std::size_t>(index), *row);
        } catch (...) {
          const std::lock_guard<std::mutex> lock(work.error_mutex);
          if (!work.error) work.error = std::current_exception();
          work.stop.store(true);
        }
      }
    }
    work.done.fetch_add(1);
  }
  long long reply = work.take();
  if (reply < 0) --remote_active;
  MPI_Send(&reply, 1, MPI_LONG_LONG, status.MPI_SOURCE, kReplyTagBase + thread, MPI_COMM_WORLD);
}

// Rank 0: its own workers run while this thread serves the other ranks, until every worker
// is done. Rethrows the first error of a run.
void dispatch(Dispatch& work, const Design& d, const SweepOptions& options, int jobs,
              int remote_workers, SweepSummary& s) {
  ProgressBar bar(options.progress, s.already_done);
  {
    // Only this thread calls MPI.
    std::vector<std::jthread> pool;
    for (int t = 0; t < jobs; ++t) pool.emplace_back([&] { local_worker(work, d, options); });
    int remote_active = remote_workers;
    while (remote_active > 0 || work.local_exited.load() < jobs) {
      int flag = 0;
      MPI_Status status;
      if (remote_active > 0)
        MPI_Iprobe(MPI_ANY_SOURCE, kRequestTag, MPI_COMM_WORLD, &flag, &status);
      if (flag == 0) {
        bar.update(s.already_done + work.done.load(), work.failed.load(), s.runs);
        // Poll, rather than block in MPI_Recv, whose busy wait would take a core from the
        // workers of this rank.
        std::this_thread::sleep_for(std::chrono::microseconds(remote_active > 0 ? 500 : 20000));
        continue;
      }
      serve(work, d, status, remote_active);
    }
    bar.update(s.already_done + work.done.load(), work.failed.load(), s.runs);
  }
  s.ran_elsewhere = work.ran_elsewhere;
  if (work.error) std::rethrow_exception(work.error);
  if (!work.remote_error.empty()) throw std::runtime_error(work.remote_error);
}

}  // namespace

SweepSummary run_sweep_mpi(const fs::path& design_file, const SweepOptions& options) {
  Session mpi;
  const bool primary = mpi.rank() == 0;
  Design d;
  Plan plan;
  SweepSummary s;
  s.primary = primary;
  s.ranks = mpi.size();
  if (!load_everywhere(mpi, design_file, options, d, plan)) return s;
  int jobs = options.jobs > 0 ? options.jobs : default_jobs(launcher_local_size());
  // Without MPI_THREAD_MULTIPLE only one thread of a worker rank may talk to rank 0.
  if (!primary && !mpi.multiple()) jobs = 1;
  const int remote_jobs = primary ? 0 : jobs;
  int remote_workers = 0;
  MPI_Allreduce(&remote_jobs, &remote_workers, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  if (!primary) {
    if (jobs == 1) {
      remote_worker(d, options, 0);
    } else {
      std::vector<std::jthread> pool;
      for (int t = 0; t < jobs; ++t) pool.emplace_back([&, t] { remote_worker(d, options, t); });
    }
    return s;
  }
  s.runs = d.runs.size();
  s.already_done = s.runs - plan.pending.size();
  s.ran = plan.pending.size();
  s.workers = jobs + remote_workers;
  s.notes = plan.notes;
  Dispatch work(plan, options.observer);
  dispatch(work, d, options, jobs, remote_workers, s);
  s.table = write_results(d, options, plan.rows);
  if (options.observer != nullptr) options.observer->completed(s.table);
  s.failed = count_failed(plan.rows);
  s.results = options.out / "results.csv";
  s.design = std::move(d);
  return s;
}

}  // namespace nsb::sweep
