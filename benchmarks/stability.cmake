# Stability maps of every method (docs/benchmarks/stability.md). The full maps are
#   benchmarks/stability/run.sh build/app/nsbridge out/stability
# (1134 runs of `nsbridge sweep`, about 4 min on 2 cores); CI runs the reduced grid of benchmarks/stability/ci/
# and checks that every untrustworthy point of the maps carries its trust warning, and that
# the check fails when its thresholds differ from the code's (runs::TrustLimits).
find_program(NSB_PYTHON3 python3)
if(NSB_PYTHON3)
  nsb_test_name(stability_check stability_check)
  add_test(NAME ${stability_check}
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/stability/run.sh $<TARGET_FILE:nsbridge>
                   ${CMAKE_CURRENT_BINARY_DIR}/smoke/stability 2 ci)
  set_tests_properties(${stability_check} PROPERTIES LABELS "cli" TIMEOUT 300
                       FIXTURES_SETUP stability_maps)
  # A check whose maps trust energy errors up to 10 % (the code: 1 %) must report the runs that
  # warn but sit inside the raised map, as it would for a broken runs::TrustLimits: the test
  # passes when the check names such a run.
  nsb_test_name(stability_check_break stability_check_break)
  add_test(NAME ${stability_check_break}
           COMMAND ${NSB_PYTHON3} ${CMAKE_CURRENT_SOURCE_DIR}/stability/maps.py check
                   ${CMAKE_CURRENT_BINARY_DIR}/smoke/stability --energy-threshold 0.1
                   --penetration-threshold 0.1)
  set_tests_properties(${stability_check_break} PROPERTIES LABELS "cli"
                       PASS_REGULAR_EXPRESSION "map says energy=no, summary warnings [[][^]]*energy_balance"
                       FIXTURES_REQUIRED stability_maps)
endif()
