# lookout_module(NAME DEPS <targets...> [TEST_DEPS ...] [EXCLUDE files...] [EXTRA_SOURCES ...])
#
# One library target per module folder: every *.cc in the folder except *_test.cc is the
# library; every *_test.cc beside it is a GoogleTest case linked into one test program per
# module (lookout_<NAME>_test). Globbing keeps "one concept per file pair, its test beside it"
# free of CMake edits; CONFIGURE_DEPENDS re-globs when files are added.

set(LOOKOUT_WARNINGS -Wall -Wextra -Wpedantic -Wconversion -Wsign-conversion -Wshadow
    -Wnon-virtual-dtor -Wold-style-cast -Wcast-align -Woverloaded-virtual -Wnull-dereference
    -Wdouble-promotion -Werror)

function(lookout_apply_flags target)
  target_compile_options(${target} PRIVATE ${LOOKOUT_WARNINGS})
  if(LOOKOUT_SANITIZE)
    target_compile_options(${target} PUBLIC -fsanitize=address,undefined -fno-sanitize-recover=all
                                            -fno-omit-frame-pointer)
    target_link_options(${target} PUBLIC -fsanitize=address,undefined)
  endif()
endfunction()

# One precompiled header for every test program. Parsing is most of a test file's compile
# (dead_reckoning_test.cc at -O3: 8.9 s, of which 5.6 s before code generation), and most of
# that is GoogleTest and Eigen, which every test includes; precompiled once, they load in a
# fraction of a second (8.9 s -> 5.8 s). The first test program builds it, the others reuse it:
# all test programs compile with the same flags. A test file must still include what it uses:
# the header only saves the parse. With ccache, set its sloppiness to pch_defines,time_macros
# (docs/testing.md).
option(LOOKOUT_TEST_PCH "Precompile GoogleTest and Eigen for the test programs" ON)
set(LOOKOUT_TEST_PCH_OWNER "" CACHE INTERNAL "The test program whose precompiled header the others reuse")
function(lookout_test_pch target)
  if(NOT LOOKOUT_TEST_PCH)
    return()
  endif()
  if(LOOKOUT_TEST_PCH_OWNER STREQUAL "" OR LOOKOUT_TEST_PCH_OWNER STREQUAL target)
    target_precompile_headers(${target} PRIVATE <gtest/gtest.h> <Eigen/Dense> <cmath> <limits>
                              <string> <vector> <algorithm>)
    set(LOOKOUT_TEST_PCH_OWNER ${target} CACHE INTERNAL "")
  else()
    target_precompile_headers(${target} REUSE_FROM ${LOOKOUT_TEST_PCH_OWNER})
  endif()
endfunction()

function(lookout_module name)
  cmake_parse_arguments(ARG "" "" "DEPS;TEST_DEPS;EXCLUDE;EXTRA_SOURCES" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cc)
  file(GLOB tests CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*_test.cc)
  foreach(item IN LISTS tests ARG_EXCLUDE)
    list(REMOVE_ITEM sources ${item})
  endforeach()
  add_library(lookout_${name} ${sources} ${ARG_EXTRA_SOURCES})
  add_library(lookout::${name} ALIAS lookout_${name})
  target_include_directories(lookout_${name} PUBLIC ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(lookout_${name} PUBLIC ${ARG_DEPS})
  lookout_apply_flags(lookout_${name})
  if(LOOKOUT_TESTS AND tests)
    add_executable(lookout_${name}_test ${tests})
    target_link_libraries(lookout_${name}_test PRIVATE lookout_${name} ${ARG_TEST_DEPS}
                          GTest::gtest GTest::gmock GTest::gtest_main)
    # The checkout's path only where a test reads files of the tree or ../shared/data: the
    # other test sources then compile to the same bytes in every checkout (a compiler cache
    # shares them between worktrees). A test that starts to read files needs cmake re-run.
    foreach(test_source IN LISTS tests)
      file(STRINGS ${test_source} reads_files REGEX "LOOKOUT_SOURCE_DIR" LIMIT_COUNT 1)
      if(reads_files)
        set_property(SOURCE ${test_source} APPEND PROPERTY COMPILE_DEFINITIONS
                     LOOKOUT_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
      endif()
    endforeach()
    lookout_apply_flags(lookout_${name}_test)
    lookout_test_pch(lookout_${name}_test)
    # Suites named Catalogue* run catalogue scenarios end to end: label `catalogue`, which the
    # sanitizer run of scripts/test leaves out.
    gtest_discover_tests(lookout_${name}_test DISCOVERY_TIMEOUT 60 TEST_FILTER "-Catalogue*"
                         PROPERTIES ENVIRONMENT "LOOKOUT_SOURCE_DIR=${PROJECT_SOURCE_DIR}")
    gtest_discover_tests(lookout_${name}_test DISCOVERY_TIMEOUT 60 TEST_FILTER "Catalogue*"
                         PROPERTIES ENVIRONMENT "LOOKOUT_SOURCE_DIR=${PROJECT_SOURCE_DIR}"
                                    LABELS catalogue)
  endif()
endfunction()
