#include "sweep/runner.hpp"

#include "integrators/recorder.hpp"
#include "io/build_info.hpp"
#include "io/csv.hpp"
#include "runs/files.hpp"
#include "runs/run.hpp"
#include "sweep/csv.hpp"
#include "sweep/mpi.hpp"

#include <toml++/toml.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <limits>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace nsb::sweep {

namespace fs = std::filesystem;

void SweepOptions::validate() const {
  if (out.empty()) throw std::invalid_argument("--out: required (the sweep's folder)");
  if (jobs < 0) throw std::invalid_argument("--jobs: must be >= 0 (0 = all cores)");
}

std::string code_revision() { return io::build_info().revision; }

bool mpi_built_in() {
#ifdef NSB_HAVE_MPI
  return true;
#else
  return false;
#endif
}

namespace {

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// A file's text; empty when there is none (a rejected run has no limit_states.csv).
std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// What io's atomic writes keep while they work, left behind by a process stopped meanwhile:
// ".<name>.tmp<pid>" (io::write_file_atomically) and ".<name>.<tmp|old|probe>-<pid>-<n>"
// (io::write_file_set, the folder of a run's outputs).
bool is_temporary(const std::string& name) {
  if (name.size() < 2 || name[0] != '.') return false;
  for (const std::string_view tag : {".tmp", ".old-", ".probe-"}) {
    const auto at = name.rfind(tag);
    if (at == std::string::npos || at == 0 || at + tag.size() == name.size()) continue;
    if (std::all_of(name.begin() + static_cast<std::ptrdiff_t>(at + tag.size()), name.end(),
                    [](unsigned char c) { return std::isdigit(c) != 0 || c == '-'; })) {
      return true;
    }
  }
  return false;
}

}  // namespace

RunOutcome run_one(const Design& d, std::size_t index, const fs::path& out,
                   const RecordSink& on_record, const std::atomic<bool>* stop) {
  const Run& run = d.runs.at(index);
  const fs::path dir = out / "runs" / run.id;
  const double start = now_s();
  RunOutcome outcome;
  try {
    runs::RunRequest request;
    request.scene = d.base;
    request.typed_overrides = run.overrides;
    request.stop = stop;
    request.cross_check = d.cross_check;
    const runs::RunRecord record = runs::execute(request);
    if (record.result.status == integrators::RunStatus::kInterrupted) {
      outcome.interrupted = true;
      return outcome;
    }
    runs::write_record(dir, record);
    // An unseated run is a result (the bridge collapsed), not a failed run.
    outcome.succeeded = integrators::is_result(record.result.status);
    outcome.row = make_row(d, index, record, now_s() - start);
    if (on_record) on_record(index, record);
  } catch (const std::invalid_argument& e) {
    // The design was validated factor by factor; a combination of values can still be one the
    // scene rejects (e.g. a step larger than a shortened end_time). That run is a row.
    fs::create_directories(dir);
    outcome.row = rejected_row(d, index, e.what(), now_s() - start);
  }
  if (outcome.row.status != "rejected")
    write_file_atomically(dir / "limit_states.csv", limit_states_csv(outcome.row.limit_states));
  write_file_atomically(dir / "row.csv", row_line(d, outcome.row) + "\n");
  return outcome;
}
Plan prepare(const Design& d, const SweepOptions& options) {
  Plan plan;
  const fs::path manifest = options.out / "manifest.toml";
  std::error_code ec;
  if (fs::exists(manifest) || fs::exists(options.out / "runs")) {
    std::string hash, revision;
    toml::table inputs;
    try {
      const toml::table m = toml::parse_file(manifest.string());
      hash = m["design_hash"].value_or(std::string());
      revision = m["revision"].value_or(std::string());
      if (const auto* t = m["inputs"].as_table()) inputs = *t;
    } catch (const toml::parse_error&) {
    }
    // An input whose content changed under the same name makes the rows in DIR those of
    // another input: refused, naming the file (docs/sweep.md, "Resume").
    for (const Input& input : d.inputs) {
      const auto before = inputs[input.name].value<std::string>();
      if (before && *before != input.hash && !options.restart) {
        throw std::invalid_argument(
            input.path.string() + ": changed since the runs in " + options.out.string() +
            " were made (content hash " + *before + ", now " + input.hash +
            "); use --restart to redo every run, or another --out");
      }
    }
    if (hash != d.hash && !options.restart) {
      throw std::invalid_argument(
          options.out.string() + ": holds the runs of a different design (design hash " +
          (hash.empty() ? std::string("unknown") : hash) + ", this design " + d.hash +
          "); use --restart to discard them, or another --out");
    }
    if (hash != d.hash || options.restart) {
      fs::remove_all(options.out / "runs", ec);
      fs::remove(options.out / "results.csv", ec);
      fs::remove_all(options.out / "plots", ec);
    } else if (revision != code_revision()) {
      plan.notes.push_back("the completed runs were made by revision " + revision + ", this is " +
                           code_revision() + "; use --restart to redo them");
    }
  }
  fs::create_directories(options.out / "runs", ec);
  if (ec) {
    throw std::invalid_argument("--out " + options.out.string() + ": cannot create the directory '" +
                                (options.out / "runs").string() + "': " + ec.message());
  }
  std::ostringstream m;
  m << "# The sweep in this folder (nsbridge sweep); a rerun resumes it.\n"
    << "design = " << toml::value<std::string>(d.file.string()) << '\n'
    << "design_hash = \"" << d.hash << "\"\n"
    << "revision = " << toml::value<std::string>(code_revision()) << '\n'
    << "runs = " << d.runs.size() << '\n'
    << "\n# The files the runs read, relative to the design's folder: content hash (64-bit\n"
    << "# FNV-1a of the bytes). A resume refuses a folder whose inputs changed.\n"
    << "[inputs]\n";
  for (const Input& input : d.inputs)
    m << toml::value<std::string>(input.name) << " = \"" << input.hash << "\"\n";
  try {
    write_file_atomically(manifest, m.str());
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument("--out " + options.out.string() + ": " + e.what());
  }
  plan.rows.resize(d.runs.size());
  for (std::size_t i = 0; i < d.runs.size(); ++i) {
    const fs::path dir = options.out / "runs" / d.runs[i].id;
    std::ifstream in(dir / "row.csv");
    std::string line;
    if (in && std::getline(in, line))
      plan.rows[i] = parse_row(d, i, line, read_text(dir / "limit_states.csv"));
    if (!plan.rows[i]) plan.pending.push_back(i);
  }
  // What a process that was stopped (a signal, a crash) left behind: the files of the runs it
  // had not finished, and its temporary files and folders.
  for (const std::size_t i : plan.pending) fs::remove_all(options.out / "runs" / d.runs[i].id, ec);
  for (const fs::path& folder : {options.out, options.out / "runs"}) {
    for (const auto& e : fs::directory_iterator(folder, ec)) {
      if (is_temporary(e.path().filename().string())) fs::remove_all(e.path(), ec);
    }
  }
  return plan;
}

Results write_results(const Design& d, const SweepOptions& options,
                      const std::vector<std::optional<Row>>& rows) {
  Results results = results_of(d, rows);
  write_file_atomically(options.out / "results.csv", results.csv());
  return results;
}

std::size_t run_threaded(const Design& d, const SweepOptions& options, Plan& plan, int threads,
                         const SweepProgress& progress, const RecordSink& on_record) {
  const std::size_t total = plan.rows.size();
  const std::size_t before = total - plan.pending.size();
  std::atomic<std::size_t> next{0}, done{0}, failed{0}, ticks{0};
  std::atomic<int> exited{0};
  std::atomic<bool> own_stop{false};
  std::atomic<bool>& stop = options.stop != nullptr ? *options.stop : own_stop;
  std::mutex error_mutex;
  std::exception_ptr error;
  const int workers = std::max(1, std::min<int>(threads, static_cast<int>(plan.pending.size())));
  {
    std::vector<std::jthread> pool;
    for (int w = 0; w < workers; ++w) {
      pool.emplace_back([&] {
        while (!stop.load()) {
          const std::size_t k = next.fetch_add(1);
          if (k >= plan.pending.size()) break;
          try {
            RunOutcome o = run_one(d, plan.pending[k], options.out, on_record, &stop);
            if (o.interrupted) break;
            plan.rows[plan.pending[k]] = std::move(o.row);
            if (!o.succeeded) failed.fetch_add(1);
            if (options.observer != nullptr)
              options.observer->finished(plan.pending[k], *plan.rows[plan.pending[k]]);
          } catch (...) {
            const std::lock_guard<std::mutex> lock(error_mutex);
            if (!error) error = std::current_exception();
            stop.store(true);
          }
          done.fetch_add(1);
          ticks.fetch_add(1);
          ticks.notify_one();
        }
        exited.fetch_add(1);
        ticks.fetch_add(1);
        ticks.notify_one();
      });
    }
    std::size_t seen = 0;
    // Without a progress display the workers are simply joined at the end of this scope.
    while (progress && exited.load() < workers) {
      ticks.wait(seen);
      seen = ticks.load();
      if (progress) progress(before + done.load(), failed.load(), total);
    }
  }
  if (error) std::rethrow_exception(error);
  return failed.load();
}

namespace {

int env_int(const char* name, int fallback) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' ? std::atoi(v) : fallback;
}

}  // namespace

std::size_t count_failed(const std::vector<std::optional<Row>>& rows) {
  return static_cast<std::size_t>(
      std::count_if(rows.begin(), rows.end(), [](const auto& r) { return r && !is_result(*r); }));
}

int launcher_rank() { return env_int("OMPI_COMM_WORLD_RANK", env_int("PMI_RANK", 0)); }
int launcher_size() { return env_int("OMPI_COMM_WORLD_SIZE", env_int("PMI_SIZE", 1)); }
int launcher_local_size() { return env_int("OMPI_COMM_WORLD_LOCAL_SIZE", 1); }

int default_jobs(int local_ranks) {
  const int cores = static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
  return std::max(1, cores / std::max(1, local_ranks));
}

SweepSummary run_sweep(const fs::path& design_file, const SweepOptions& options) {
  options.validate();
  if (launcher_size() > 1) {
#ifdef NSB_HAVE_MPI
    return run_sweep_mpi(design_file, options);
#else
    SweepSummary quiet;
    if (launcher_rank() != 0) {
      quiet.primary = false;
      return quiet;
    }
#endif
  }
  Design d = load_design(design_file, options.set);
  validate_design(d);
  SweepSummary s;
  if (!mpi_built_in() && launcher_size() > 1) {
    s.notes.push_back(
        "MPI is not built in: rank 0 runs the whole sweep on threads, the other "
        "ranks do nothing");
  }
  Plan plan = prepare(d, options);
  if (options.observer != nullptr) options.observer->prepared(d, plan.rows);
  s.notes.insert(s.notes.end(), plan.notes.begin(), plan.notes.end());
  s.runs = d.runs.size();
  s.already_done = s.runs - plan.pending.size();
  s.ran = plan.pending.size();
  s.workers = options.jobs > 0 ? options.jobs : default_jobs(1);
  {
    ProgressBar bar(options.progress, s.already_done);
    SweepProgress progress;
    if (bar.enabled()) {
      progress = [&bar](std::size_t done, std::size_t failed, std::size_t total) {
        bar.update(done, failed, total);
      };
    }
    run_threaded(d, options, plan, s.workers, progress);
  }
  s.complete = static_cast<std::size_t>(
      std::count_if(plan.rows.begin(), plan.rows.end(), [](const auto& r) { return r.has_value(); }));
  if (options.stop != nullptr && options.stop->load()) {
    s.interrupted = true;
    return s;
  }
  s.table = write_results(d, options, plan.rows);
  if (options.observer != nullptr) options.observer->completed(s.table);
  s.failed = count_failed(plan.rows);
  s.results = options.out / "results.csv";
  s.design = std::move(d);
  return s;
}

ProgressBar::ProgressBar(bool enabled, std::size_t already)
    : enabled_(enabled && ::isatty(STDERR_FILENO) == 1), already_(already), start_(now_s()) {}

ProgressBar::~ProgressBar() {
  if (drawn_) std::fputs("\n", stderr);
}

void ProgressBar::update(std::size_t done, std::size_t failed, std::size_t total) {
  if (!enabled_ || total == 0) return;
  const double t = now_s();
  // Redraw at most ten times a second, and always at the end.
  if (done < total && last_ >= 0.0 && t - last_ < 0.1) return;
  last_ = t;
  const double elapsed = t - start_;
  const std::size_t now_done = done - std::min(done, already_);
  const double left =
      now_done > 0 ? elapsed / static_cast<double>(now_done) * static_cast<double>(total - done)
                   : 0.0;
  constexpr int kWidth = 30;
  const int filled =
      static_cast<int>(kWidth * static_cast<double>(done) / static_cast<double>(total));
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(kWidth, ' ');
  std::fprintf(stderr, "\r[%s] %zu/%zu runs, %zu failed, %.0f s left ", bar.c_str(), done, total,
               failed, left);
  std::fflush(stderr);
  drawn_ = true;
}

}  // namespace nsb::sweep
