# cmake -P, run by the "fuzz: build" test (tests/CMakeLists.txt): configures this directory
# (SOURCE) with the clang++ CXX into WORK and builds the fuzz targets. Incremental after the
# first run. Parallel jobs: $CMAKE_BUILD_PARALLEL_LEVEL if set, else up to 4 cores.
cmake_host_system_information(RESULT cores QUERY NUMBER_OF_LOGICAL_CORES)
if(DEFINED ENV{CMAKE_BUILD_PARALLEL_LEVEL})
  set(jobs "$ENV{CMAKE_BUILD_PARALLEL_LEVEL}")
elseif(cores GREATER 4)
  set(jobs 4)
else()
  set(jobs ${cores})
endif()
foreach(step
    "${CMAKE_COMMAND};-S;${SOURCE};-B;${WORK};-DCMAKE_CXX_COMPILER=${CXX}"
    "${CMAKE_COMMAND};--build;${WORK};--parallel;${jobs}")
  execute_process(COMMAND ${step} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${step}\n${out}\n${err}")
  endif()
endforeach()
message("fuzz targets built in ${WORK}")
