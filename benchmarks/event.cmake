# Work–precision study of the event-driven scheme against Moreau–Jean (docs/benchmarks/event.md).
# Smoke run: the --quick grid (6 s of the bridge), one repetition: ~3 s.
nsb_add_benchmark(work_precision_bench SOURCES work_precision_bench.cpp
                  DEPS nsb_models nsb_integrators nsb_lcp
                  SMOKE --quick --repeats 1 --out work_precision
                  FIXTURES_REQUIRED verification)
