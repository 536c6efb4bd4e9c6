# Moreau–Jean on two bridges assembled from parts, h = 1e-4: the benchmark bridge of
# excitation 7 and the two-frame bridge (scenes/bridge-two-frame.toml), alternating. Run:
# build/benchmarks/parts_bench [repeats] [csv file] [end time]. Smoke run: one repetition of
# 2 s of each: ~1 s.
nsb_add_benchmark(parts_bench SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/parts_bench.cpp
                  DEPS nsb_scene nsb_models nsb_integrators nsb_lcp
                  SMOKE 1 parts_bench.csv 2.0
                  FIXTURES_REQUIRED verification)
