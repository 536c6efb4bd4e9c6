# Moreau–Jean on the benchmark bridge under the 7 excitations at h = 1e-4 and 1e-3
# (docs/benchmarks/moreau.md). Run: build/benchmarks/moreau_bench [repeats] [csv file]
# [excitation]. Smoke run: one repetition of every excitation at both step sizes: ~5 s.
nsb_add_benchmark(moreau_bench SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/moreau_bench.cpp
                  DEPS nsb_scene nsb_models nsb_integrators nsb_lcp
                  SMOKE 1 moreau_bench.csv
                  FIXTURES_REQUIRED verification)
