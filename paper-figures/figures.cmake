# The paper's figures as one CTest test. It requires the verification fixture: a failed
# cross-check stops the figures.
nsb_test_name(figures paper_figures)
add_test(NAME ${figures}
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/make-figures.sh $<TARGET_FILE:nsbridge>
                 ${CMAKE_BINARY_DIR}/paper-figures)
set_tests_properties(${figures} PROPERTIES LABELS "figures" FIXTURES_REQUIRED verification
                                           TIMEOUT 900)
