# cmake -DEXE=<program> -DEXPECTED=<file> -DSOURCE_DIR=<repository root> [-DUPDATE=ON] -P check_output.cmake
# Runs a deliberately failing Catch2 program (fixed seeds, no colour) in the current directory and compares
# its output with EXPECTED, the text docs/testing.md shows: the program must fail, and its report must be the
# documented one. Catch2's banner (version, random seed) is dropped and the source paths are made relative to
# the repository. With UPDATE=ON the file is rewritten from this run instead.
cmake_minimum_required(VERSION 3.21)
execute_process(COMMAND "${EXE}" --colour-mode none --rng-seed 1
                OUTPUT_VARIABLE output ERROR_VARIABLE output RESULT_VARIABLE status)
if(status EQUAL 0)
  message(FATAL_ERROR "${EXE} passed, but it is the documented failing example")
endif()
string(FIND "${output}" "\n----" first_case)
if(first_case EQUAL -1)
  message(FATAL_ERROR "no test case in the output of ${EXE}:\n${output}")
endif()
math(EXPR first_case "${first_case} + 1")
string(SUBSTRING "${output}" ${first_case} -1 output)
string(REPLACE "${SOURCE_DIR}/" "" output "${output}")
if(UPDATE)
  file(WRITE "${EXPECTED}" "${output}")
  message(STATUS "wrote ${EXPECTED}")
  return()
endif()
file(READ "${EXPECTED}" expected)
if(NOT output STREQUAL expected)
  file(WRITE "${CMAKE_CURRENT_BINARY_DIR}/actual_output.txt" "${output}")
  message(FATAL_ERROR "the output differs from ${EXPECTED} (this run: ${CMAKE_CURRENT_BINARY_DIR}/actual_output.txt; "
                      "after a deliberate change, rerun this script with -DUPDATE=ON):\n${output}")
endif()
message(STATUS "the output equals ${EXPECTED}")
