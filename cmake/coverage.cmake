# OLCB_COVERAGE: gcc's --coverage on every target, so a test run leaves the .gcda files gcovr
# reads for ci/test's line-coverage floor (docs/benchmarks.md, "Line coverage"). Directory-wide
# options, included before the libraries, so the libraries and the suites that link them agree.
option(OLCB_COVERAGE "Instrument every target for gcov line coverage (g++ only; ci/test's floor)" OFF)
if(OLCB_COVERAGE)
    # clang's --coverage writes a .gcda gcovr's gcc gcov cannot read; the floor is measured on gcc.
    if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
        message(FATAL_ERROR "OLCB_COVERAGE needs g++ (its gcov format is what gcovr reads here)")
    endif()
    add_compile_options(--coverage)
    add_link_options(--coverage)
endif()
