# sss_run_steps(<step>...): runs each step (a ;-list command line) in order; fails naming the first
# that fails, with its output. Sets sss_last_output (stdout of the last step) in the caller.
function(sss_run_steps)
  foreach(step IN LISTS ARGN)
    string(REPLACE "|" ";" command "${step}")
    execute_process(COMMAND ${command} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "step failed (${rc}): ${command}\n${out}\n${err}")
    endif()
  endforeach()
  set(sss_last_output "${out}" PARENT_SCOPE)
endfunction()
