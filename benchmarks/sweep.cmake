# Parallel efficiency of sweeps: threads (sweep_bench) and MPI ranks (sweep_mpi_bench.sh),
# docs/benchmarks/sweep.md. Run: build/benchmarks/sweep_bench [repeats] [csv] [end_time].
nsb_add_benchmark(sweep_bench SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/sweep_bench.cpp DEPS nsb_sweep)
