# Writes the git revision of the source tree into a header, at build time (cmake -P), and
# touches the header only when the revision changes, so that a build without a new commit
# recompiles nothing.
#   cmake -DGIT=<git> -DSRC=<source dir> -DOUT=<header> -P git_revision.cmake
# io::build_info() reads it: nsbridge --version, the sweep manifest and the benchmarks.
set(revision "unknown")
if(GIT)
  execute_process(COMMAND ${GIT} -C ${SRC} rev-parse --short=12 HEAD
                  OUTPUT_VARIABLE rev RESULT_VARIABLE rc OUTPUT_STRIP_TRAILING_WHITESPACE
                  ERROR_QUIET)
  if(rc EQUAL 0 AND rev)
    set(revision "${rev}")
    # Uncommitted changes to tracked files: the binary is not exactly that revision.
    execute_process(COMMAND ${GIT} -C ${SRC} diff --quiet HEAD -- RESULT_VARIABLE dirty
                    ERROR_QUIET)
    if(NOT dirty EQUAL 0)
      string(APPEND revision "-dirty")
    endif()
  endif()
endif()
set(text "// Generated at build time by io/git_revision.cmake: do not edit.\n#pragma once\n#define NSB_GIT_REVISION \"${revision}\"\n")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
endif()
if(NOT "${old}" STREQUAL "${text}")
  file(WRITE ${OUT} "${text}")
endif()
