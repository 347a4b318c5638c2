# Shared by the package tests' cmake -P scripts (shader_consumer, shader_files, budget_consumer):
#   emcv_require_vars(<script> <var>...)  each -D<var>=... given, else a fatal error naming the script and var
#   run(<step> <command>...)              runs the command; a non-zero exit is a fatal error with its output, a
#                                         zero one prints "<step>: ok" and leaves its stdout in run_output
#   emcv_require_same_files(<what> <source dir> <installed dir> <glob> <out var>)
#                                         the installed dir's files matching glob are the source dir's, by name (a
#                                         fatal error naming <what> otherwise, or when there are none); their
#                                         names, sorted, in <out var>
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

function(emcv_require_same_files what source_dir installed_dir glob out_var)
  file(GLOB source_files RELATIVE "${source_dir}" "${source_dir}/${glob}")
  file(GLOB installed_files RELATIVE "${installed_dir}" "${installed_dir}/${glob}")
  list(SORT source_files)
  list(SORT installed_files)
  if(source_files STREQUAL "")
    message(FATAL_ERROR "no ${what} under ${source_dir}")
  endif()
  if(NOT source_files STREQUAL installed_files)
    message(FATAL_ERROR "installed ${what} (${installed_files}) differ from the source tree's (${source_files})")
  endif()
  set(${out_var} "${installed_files}" PARENT_SCOPE)
endfunction()
