# Work–precision study of the event-driven scheme against Moreau–Jean (docs/benchmarks/event.md).
# Smoke run: the --quick grid (6 s of the bridge), one repetition: ~3 s.
nsb_add_benchmark(work_precision_bench SOURCES work_precision_bench.cpp
                  DEPS nsb_scene nsb_models nsb_integrators nsb_lcp
                  SMOKE --quick --repeats 1 --out work_precision
                  FIXTURES_REQUIRED verification)

# Allocations of the event-driven integrator per event after warm-up (docs/benchmarks/event.md).
# Smoke run: the bridge under excitation 7, windows of 6 s and 12 s.
nsb_add_benchmark(event_alloc_bench SOURCES event_alloc_bench.cpp
                  DEPS nsb_scene nsb_models nsb_integrators nsb_lcp
                  SMOKE ${NSB_SCENES_DIR}/bridge-exc7.toml 6
                  FIXTURES_REQUIRED verification)
