# LCP solver benchmark: eq. (6) problems, dense SPD problems and Siconos's LCP collection;
# with Siconos Numerics installed, the same problems through its solvers, and the time ratios.
# Smoke run: --quick (fewer sizes and repetitions): ~6 s on 2 shared cores.
nsb_add_benchmark(lcp_bench SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/lcp_bench.cpp DEPS nsb_lcp
                  SMOKE --quick --csv lcp_bench.csv)
if(NSB_HAVE_SICONOS)
  target_compile_definitions(lcp_bench PRIVATE NSB_HAVE_SICONOS=1)
  # Siconos's headers include "SiconosConfig.h" from the folder above numerics/.
  target_include_directories(lcp_bench SYSTEM PRIVATE ${SICONOS_INCLUDE_DIR}
                                                      ${SICONOS_INCLUDE_DIR}/siconos)
  target_link_libraries(lcp_bench PRIVATE ${SICONOS_NUMERICS_LIB})
endif()
