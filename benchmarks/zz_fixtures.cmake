# The bridge benchmarks as CTest tests (label "benchmark"): one repetition each, so that CI
# exercises them end to end. They require the verification fixture, so a failed cross-check
# stops them. Figures quoted in docs/benchmarks.md come from the full runs documented there.
add_test(NAME bridge_benchmark_moreau
         COMMAND moreau_bench 1 ${CMAKE_CURRENT_BINARY_DIR}/moreau_bench.csv)
set_tests_properties(bridge_benchmark_moreau PROPERTIES LABELS "benchmark"
                     FIXTURES_REQUIRED verification TIMEOUT 900)
