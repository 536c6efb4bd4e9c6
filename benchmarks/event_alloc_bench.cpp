// Heap allocations of the event-driven integrator per event: every malloc of the process is
// counted while integrate() runs (scene loading outside), on a scene for a
// window T and for 2T. After the warm-up of the first window, an integrator that allocates
// nothing per event adds no allocation for the events of the second half, except the
// recorder's own storage (its sample and event vectors grow by doubling: O(log n)), which
// the benchmark reports separately by reserving it first.
//
// Usage: event_alloc_bench [SCENE.toml [T]]     default: scenes/bridge-exc7.toml, T = 20 s
#include "integrators/run.hpp"
#include "io/build_info.hpp"
#include "scene/scene.hpp"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

// Every heap allocation of the process goes through malloc: operator new (libstdc++), Eigen's
// dynamic matrices, GSL's workspaces. The executable's own malloc family interposes on the C
// library's (glibc exports the originals as __libc_*), counts, and forwards.
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
void __libc_free(void*);

void* malloc(std::size_t n) {
  ++g_allocations;
  return __libc_malloc(n);
}
void* calloc(std::size_t n, std::size_t size) {
  ++g_allocations;
  return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t n) {
  ++g_allocations;
  return __libc_realloc(p, n);
}
void* memalign(std::size_t alignment, std::size_t n) {
  ++g_allocations;
  return __libc_memalign(alignment, n);
}
void* aligned_alloc(std::size_t alignment, std::size_t n) {
  ++g_allocations;
  return __libc_memalign(alignment, n);
}
int posix_memalign(void** p, std::size_t alignment, std::size_t n) {
  ++g_allocations;
  *p = __libc_memalign(alignment, n);
  return *p ? 0 : 12;  // ENOMEM
}
void free(void* p) { __libc_free(p); }
}

namespace ni = nsb::integrators;
namespace nm = nsb::models;

namespace {

struct Count {
  long allocations = 0;
  std::size_t events = 0;
  bool ok = false;
};

// One event-driven run of [0, end_time]; samples every 1 s (the history is not what is
// measured), allocations counted inside integrate() only.
Count run(const std::filesystem::path& scene_file, double end_time) {
  auto scene = nsb::scene::load_scene(scene_file, {"solver.method=event_driven",
                                           "solver.end_time=" + std::to_string(end_time)});
  ni::Recorder recorder(*scene.system, 1.0);
  Count c;
  const long before = g_allocations.load();
  const ni::RunResult r = ni::integrate(*scene.system, scene.run, recorder);
  c.allocations = g_allocations.load() - before;
  c.events = recorder.events().size();
  c.ok = ni::succeeded(r.status);
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path scene =
      argc > 1 ? std::filesystem::path(argv[1])
               : std::filesystem::path(NSB_SCENES_DIR) / "bridge-exc7.toml";
  const double t = argc > 2 ? std::atof(argv[2]) : 20.0;
  if (!(t > 0.0)) {
    std::fprintf(stderr, "event_alloc_bench: T must be > 0\n");
    return 2;
  }
  std::printf("event_alloc_bench: %s, event-driven, windows %g s and %g s\n",
              scene.string().c_str(), t, 2.0 * t);
  std::printf("build %s, revision %s\n", NSB_BUILD_TYPE, nsb::io::build_info().revision.c_str());
  const Count a = run(scene, t), b = run(scene, 2.0 * t);
  std::printf("window %6.2f s: %6zu events, %8ld allocations\n", t, a.events, a.allocations);
  std::printf("window %6.2f s: %6zu events, %8ld allocations\n", 2.0 * t, b.events,
              b.allocations);
  if (!a.ok || !b.ok) {
    std::printf("a run did not complete\n");
    return 1;
  }
  const auto extra_events = static_cast<long>(b.events) - static_cast<long>(a.events);
  const long extra = b.allocations - a.allocations;
  std::printf("second half: %ld events, %ld allocations (%.3f per event)\n", extra_events,
              extra, extra_events > 0 ? static_cast<double>(extra) / extra_events : 0.0);
  return 0;
}
