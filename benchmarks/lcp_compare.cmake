# Solver comparison on the bridge's own contact problems (docs/benchmarks/lcp-compare.md):
# the problems of excitations 1..7 under Moreau–Jean, harvested through the run pipeline's LCP
# dump, and Siconos's collection; every LCP solver at tolerances 1e-8 and 1e-12 (and Siconos's
# with Siconos Numerics); performance profiles (Dolan & Moré 2002) of time and residual.
# Run: build/benchmarks/lcp_compare_bench [--from DIR] [--harvest-into DIR] (see the source).
# Smoke run: --quick (excitation 3, every 8th problem, short timing): ~5 s.
nsb_add_library(bench_profile SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/performance_profile.cpp DEPS)
nsb_add_test(${CMAKE_CURRENT_SOURCE_DIR}/test/performance_profile_test.cpp DEPS nsb_bench_profile)
nsb_add_benchmark(lcp_compare_bench SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/lcp_compare_bench.cpp
                  DEPS nsb_bench_profile nsb_runs nsb_lcp
                  SMOKE --quick --csv lcp_compare.csv --profiles lcp_compare_profiles.csv
                  FIXTURES_REQUIRED verification)
if(NSB_HAVE_SICONOS)
  target_compile_definitions(lcp_compare_bench PRIVATE NSB_HAVE_SICONOS=1)
  # Siconos's headers include "SiconosConfig.h" from the folder above numerics/.
  target_include_directories(lcp_compare_bench SYSTEM PRIVATE ${SICONOS_INCLUDE_DIR}
                                                              ${SICONOS_INCLUDE_DIR}/siconos)
  target_link_libraries(lcp_compare_bench PRIVATE ${SICONOS_NUMERICS_LIB})
endif()
