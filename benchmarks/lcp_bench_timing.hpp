// Timing of the LCP benchmark: the thread's CPU clock, the median time of one call
// over batches, and the silencing of a library that prints on stdout and stderr.
#pragma once

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <functional>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

namespace nsb::bench {

// CPU time of this thread: on a machine shared with other jobs, wall time counts the time the
// thread waits for a core, which is noise for a ratio of two solvers' work.
inline double now() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Median over `batches` of the mean CPU time of one call, each batch long enough (>= min_time)
// for the clock's resolution not to matter.
inline double median_time(const std::function<void()>& f, int batches, double min_time) {
  f();  // warm up (page in code and data)
  int reps = 1;
  for (double t = 0.0; reps < (1 << 24);) {
    const double t0 = now();
    for (int i = 0; i < reps; ++i) f();
    t = now() - t0;
    if (t >= min_time) break;
    reps *= 2;
  }
  std::vector<double> times;
  for (int b = 0; b < batches; ++b) {
    const double t0 = now();
    for (int i = 0; i < reps; ++i) f();
    times.push_back((now() - t0) / reps);
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// Siconos prints diagnostics (e.g. each failed LU of its Newton–FB) on stdout and stderr;
// while one of its solvers runs, both go to /dev/null.
class Silence {
 public:
  Silence() {
    std::fflush(stdout);
    std::fflush(stderr);
    out_ = dup(1);
    err_ = dup(2);
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, 1);
    dup2(null, 2);
    close(null);
  }
  ~Silence() {
    std::fflush(stdout);
    std::fflush(stderr);
    dup2(out_, 1);
    dup2(err_, 2);
    close(out_);
    close(err_);
  }
  Silence(const Silence&) = delete;
  Silence& operator=(const Silence&) = delete;

 private:
  int out_ = -1;
  int err_ = -1;
};

}  // namespace nsb::bench
