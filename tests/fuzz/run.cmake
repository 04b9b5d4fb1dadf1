# cmake -P, run by the "fuzz: <target>" tests (tests/CMakeLists.txt): runs the libFuzzer
# binary FUZZER for SECONDS with random seed SEED (0: a new one each run) on a fresh copy of the
# seed corpus CORPUS (the repository's corpus is never written), in WORK. Fails, with the report
# and the saved reproducer, if the fuzzer finds a crash, an oracle violation, a timeout (> 10 s
# for one input) or an out-of-memory (> 2 GiB). The reproducer's bytes are printed in hex too, so
# a failure on a machine whose build directory is gone (CI) can be rebuilt from its log:
#   xxd -r -p reproducer.hex > crash && <FUZZER> crash
foreach(var FUZZER CORPUS WORK SECONDS SEED)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run.cmake: -D${var}=... is required")
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK}/corpus" "${WORK}/tmp")
file(MAKE_DIRECTORY "${WORK}/corpus" "${WORK}/tmp" "${WORK}/artifacts")
file(COPY "${CORPUS}/" DESTINATION "${WORK}/corpus")

execute_process(
  COMMAND ${CMAKE_COMMAND} -E env "TMPDIR=${WORK}/tmp" "UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1"
          "${FUZZER}" -max_total_time=${SECONDS} -seed=${SEED} -timeout=10 -rss_limit_mb=2048 -print_final_stats=1
          "-artifact_prefix=${WORK}/artifacts/" "${WORK}/corpus"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
file(WRITE "${WORK}/fuzz.log" "${out}")
if(NOT rc EQUAL 0)
  string(LENGTH "${out}" length)
  if(length GREATER 12000)
    math(EXPR start "${length} - 12000")
    string(SUBSTRING "${out}" ${start} -1 out)
  endif()
  file(GLOB artifacts "${WORK}/artifacts/*")
  set(hex "")
  foreach(artifact IN LISTS artifacts)
    file(READ "${artifact}" bytes LIMIT 8192 HEX)
    string(APPEND hex "${artifact} (hex, first 8 KiB):\n${bytes}\n")
  endforeach()
  message(FATAL_ERROR "${FUZZER} failed (exit ${rc}); full log: ${WORK}/fuzz.log\n"
                      "reproducers: ${artifacts}\n${hex}...\n${out}")
endif()
string(REGEX MATCHALL "stat::[a-z_]+: *[0-9]+" stats "${out}")
string(REGEX MATCH "INFO: seed corpus: files: [0-9]+" seeds "${out}")
string(REPLACE ";" ", " stats "${stats}")
string(REGEX REPLACE ": +" ": " stats "${stats}")
message("${FUZZER}: ${SECONDS} s without a failure; ${seeds}; ${stats}")
