# cmake -DBUILD_DIR=<consumer build dir> -P check_no_own_targets.cmake
# emcv as a sub-project must not build its own executables: asking the consumer's build for each one must
# fail with the generator's "unknown target" message (any other failure is not this property).
foreach(target emcv-test-unit emcv-toy emcv-bench emcv-glinfo)
  execute_process(COMMAND "${CMAKE_COMMAND}" --build "${BUILD_DIR}" --target ${target}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc EQUAL 0)
    message(FATAL_ERROR "emcv built ${target} as a sub-project: its options must default OFF there")
  endif()
  if(NOT "${out}${err}" MATCHES "unknown target|No rule to make target")
    message(FATAL_ERROR "building ${target} failed for another reason than an unknown target:\n${out}${err}")
  endif()
endforeach()
message(STATUS "no emcv executable in ${BUILD_DIR}")
