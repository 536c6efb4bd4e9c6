# Work and precision of the three methods on four bridges, fixed steps and tolerances against
# solver.adapt (docs/benchmarks/work-precision-bridges.md). The full run (about 10 min of CPU
# on 2 cores):
#   /usr/bin/python3 benchmarks/work_precision_bridges.py build/app/nsbridge --out out/work_precision_bridges
# The smoke run: --quick (excitation 7 over 5 s, a short ladder, the 1e-1 target), about 2 s
# of CPU; it fails when a run fails or a reference is not converged.
nsb_test_name(work_precision_bridges work_precision_bridges)
add_test(NAME ${work_precision_bridges}
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/work_precision_bridges.py
                 $<TARGET_FILE:nsbridge> --quick --repeats 1 --jobs 1
                 --scenes ${NSB_SCENES_DIR}
                 --out ${CMAKE_CURRENT_BINARY_DIR}/smoke/work_precision_bridges)
set_tests_properties(${work_precision_bridges} PROPERTIES LABELS "benchmark" TIMEOUT 120)
