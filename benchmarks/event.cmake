# Work–precision study of the event-driven scheme against Moreau–Jean (docs/benchmarks/event.md).
nsb_add_benchmark(work_precision_bench SOURCES work_precision_bench.cpp
                  DEPS nsb_models nsb_integrators nsb_lcp)
