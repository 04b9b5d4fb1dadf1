# cmake -P: installs the build tree BUILD into PREFIX, then configures, builds and runs the
# consumer project against it. Fails on any step.
# The consumer inherits the sanitizer flags of a sanitized libsss; GL processes run without leak
# checking there (see cmake/sss_gl_process_asan_options.c).
set(run_env "SSS_CONSUMER=1")
if(SANITIZE)
  set(run_env "ASAN_OPTIONS=detect_leaks=0")
endif()
foreach(step
    "${CMAKE_COMMAND};--install;${BUILD};--prefix;${PREFIX}"
    "${CMAKE_COMMAND};-S;${SOURCE};-B;${WORK};-DCMAKE_PREFIX_PATH=${PREFIX};-DCMAKE_BUILD_TYPE=Release"
    "${CMAKE_COMMAND};--build;${WORK}"
    "${CMAKE_COMMAND};-E;env;${run_env};${WORK}/consumer")
  execute_process(COMMAND ${step} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${step}\n${out}\n${err}")
  endif()
endforeach()
message("installed libsss found with find_package(sss), linked and ran: ${out}")
