# Parallel efficiency of sweeps: threads (sweep_bench) and MPI ranks (sweep_mpi_bench.sh),
# docs/benchmarks/sweep.md. Run: build/benchmarks/sweep_bench [repeats] [csv] [end_time].
# Smoke run: one repetition with every run cut to 1 s of simulated time.
nsb_add_benchmark(sweep_bench SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/sweep_bench.cpp DEPS nsb_sweep
                  SMOKE 1 sweep_bench.csv 1
                  FIXTURES_REQUIRED verification)
