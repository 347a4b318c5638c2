# Shared by the package tests' cmake -P scripts (shader_consumer, shader_files, budget_consumer):
#   emcv_require_vars(<script> <var>...)  each -D<var>=... given, else a fatal error naming the script and var
#   run(<step> <command>...)              runs the command; a non-zero exit is a fatal error with its output, a
#                                         zero one prints "<step>: ok" and leaves its stdout in run_output
function(emcv_require_vars script)
  foreach(var IN LISTS ARGN)
    if(NOT DEFINED ${var})
      message(FATAL_ERROR "${script}: -D${var}=... is required")
    endif()
  endforeach()
endfunction()

function(run step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${step} failed (exit ${rc}):\n${out}${err}")
  endif()
  message(STATUS "${step}: ok")
  set(run_output "${out}" PARENT_SCOPE)
endfunction()
