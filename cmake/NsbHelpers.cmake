# Helpers shared by every folder: one library per folder, one test file per module.

# Compile options every nsbridge target gets.
function(nsb_target_options target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow)
  if(NSB_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(NSB_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                             -fno-sanitize-recover=all)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()

# The doctest main, compiled once and linked into every test executable.
function(nsb_add_doctest_main)
  add_library(nsb_doctest_main STATIC ${PROJECT_SOURCE_DIR}/cmake/doctest_main.cpp)
  target_link_libraries(nsb_doctest_main PUBLIC doctest::doctest)
  nsb_target_options(nsb_doctest_main)
endfunction()

# nsb_add_library(<name> SOURCES <files...> DEPS <targets...>)
# Adds the static library nsb_<name> whose public headers live in the folder itself and are
# included as "<folder>/<header>.hpp" from the project root.
function(nsb_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(nsb_${name} STATIC ${ARG_SOURCES})
  target_include_directories(nsb_${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(nsb_${name} PUBLIC ${ARG_DEPS})
  nsb_target_options(nsb_${name})
  if(NSB_SANITIZE)
    target_link_options(nsb_${name} INTERFACE -fsanitize=address,undefined)
  endif()
endfunction()

# nsb_test_name(<out-var> <name>)
# The CTest name of a test of the current folder: "<folder>.<name>", e.g. lcp.lemke_test,
# verification.moreau_deck_check, benchmarks.moreau_bench (README, "Tests"). The prefix lets
# `ctest -R '^lcp\.'` select one module.
function(nsb_test_name out name)
  file(RELATIVE_PATH folder ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR})
  set(${out} "${folder}.${name}" PARENT_SCOPE)
endfunction()

# nsb_add_test(<file.cpp> DEPS <targets...> [LABELS <labels...>] [FIXTURES_SETUP <f>]
#              [FIXTURES_REQUIRED <f>] [TIMEOUT <s>])
# One doctest executable per test file, named after the file's stem and registered with CTest
# as "<folder>.<stem>". Every test gets the label "unit" unless LABELS says otherwise.
function(nsb_add_test file)
  cmake_parse_arguments(ARG "" "TIMEOUT" "DEPS;LABELS;FIXTURES_SETUP;FIXTURES_REQUIRED" ${ARGN})
  get_filename_component(stem ${file} NAME_WE)
  add_executable(${stem} ${file})
  target_link_libraries(${stem} PRIVATE ${ARG_DEPS} nsb_doctest_main doctest::doctest)
  target_compile_definitions(${stem} PRIVATE NSB_DATA_DIR="${NSB_DATA_DIR}"
                                             NSB_SCENES_DIR="${NSB_SCENES_DIR}")
  nsb_target_options(${stem})
  nsb_test_name(name ${stem})
  add_test(NAME ${name} COMMAND ${stem})
  if(NOT ARG_LABELS)
    set(ARG_LABELS unit)
  endif()
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 300)
  endif()
  set_tests_properties(${name} PROPERTIES LABELS "${ARG_LABELS}" TIMEOUT ${ARG_TIMEOUT})
  if("unit" IN_LIST ARG_LABELS)
    add_dependencies(nsb_unit_tests ${stem})
  endif()
  if(ARG_FIXTURES_SETUP)
    set_tests_properties(${name} PROPERTIES FIXTURES_SETUP "${ARG_FIXTURES_SETUP}")
  endif()
  if(ARG_FIXTURES_REQUIRED)
    set_tests_properties(${name} PROPERTIES FIXTURES_REQUIRED "${ARG_FIXTURES_REQUIRED}")
  endif()
endfunction()

# nsb_add_folder_tests(<library target> [<more targets...>])
# Registers every test/<module>_test.cpp of the current folder as a unit test linked to the
# folder's library (and the further targets, e.g. nsb_testsupport).
function(nsb_add_folder_tests lib)
  file(GLOB tests CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/test/*_test.cpp)
  foreach(t ${tests})
    nsb_add_test(${t} DEPS ${lib} ${ARGN})
  endforeach()
endfunction()

# nsb_include_fragments()
# Includes every *.cmake file of the current folder, so that each module adds its own
# executables and tests without editing a shared list. The order carries no meaning: tests
# that must run after others say so with the CTest fixture properties (FIXTURES_SETUP and
# FIXTURES_REQUIRED), never through the order of the fragments.
macro(nsb_include_fragments)
  file(GLOB _nsb_fragments CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cmake)
  list(SORT _nsb_fragments)
  foreach(_f ${_nsb_fragments})
    include(${_f})
  endforeach()
endmacro()
