# cmake -DPREFIX=<installed libsss> -DSOURCE=<consumer project> -DWORK=<build dir>
#       [-DARGS=<configure arguments, separated by |>] [-DSANITIZE=ON] -P consumer.cmake:
# configures, builds and runs a consumer project against the installed package; fails on any step.
set(run_env "SSS_CONSUMER=1")
set(link_flags "")
if(SANITIZE)
  # A sanitized libsss needs the sanitizer runtimes in the consumer's link; GL processes run
  # without leak checking there (see cmake/sss_gl_process_asan_options.c).
  set(run_env "ASAN_OPTIONS=detect_leaks=0")
  set(link_flags "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined")
endif()
include("${CMAKE_CURRENT_LIST_DIR}/run_steps.cmake")
file(REMOVE_RECURSE "${WORK}")
sss_run_steps(
  "${CMAKE_COMMAND}|-S|${SOURCE}|-B|${WORK}|-DCMAKE_PREFIX_PATH=${PREFIX}|-DCMAKE_BUILD_TYPE=Release|${link_flags}|${ARGS}"
  "${CMAKE_COMMAND}|--build|${WORK}"
  "${CMAKE_COMMAND}|-E|env|${run_env}|${WORK}/consumer")
message("the consumer project configured, built and ran: ${sss_last_output}")
