# Compliance (gap element) method on the bridge: cost and error against the contact stiffness.
# Smoke run: one stiffness factor, one repetition, the first 8 s of the scene (its first
# pounding at 2.3 s): ~3 s.
nsb_add_benchmark(compliance_bench SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/compliance_bench.cpp
                  DEPS nsb_scene nsb_models nsb_integrators nsb_lcp CLI11::CLI11
                  SMOKE --end-time 8 --factors 1 --repeat 1 --csv compliance_bench.csv
                  FIXTURES_REQUIRED verification)
