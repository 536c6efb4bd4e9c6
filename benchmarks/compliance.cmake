# Compliance (gap element) method on the bridge: cost and error against the contact stiffness.
nsb_add_benchmark(compliance_bench SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/compliance_bench.cpp
                  DEPS nsb_models nsb_integrators nsb_lcp CLI11::CLI11)
