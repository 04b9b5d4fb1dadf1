# cmake -DSOURCE_DIR=<repo> -DWORK=<dir> [-DJOBS=n] -P check.cmake: builds the renderers alone as a
# shared library (BUILD_SHARED_LIBS=ON, every other component, program and test off), installs
# it, checks what libsss.so exports (the public API; no GL loader, no sss::gl or pass internals),
# then builds and runs the renderers-only consumer against it.
if(NOT DEFINED JOBS)
  set(JOBS 2)
endif()
set(build "${WORK}/build")
set(prefix "${WORK}/prefix")
file(REMOVE_RECURSE "${WORK}")
include("${CMAKE_CURRENT_LIST_DIR}/../install_consumer/run_steps.cmake")
sss_run_steps(
  "${CMAKE_COMMAND}|-S|${SOURCE_DIR}|-B|${build}|-DCMAKE_BUILD_TYPE=Release|-DBUILD_SHARED_LIBS=ON|-DSSS_BUILD_IO=OFF|-DSSS_BUILD_REFERENCE=OFF|-DSSS_BUILD_SCENE=OFF|-DSSS_BUILD_EXAMPLES=OFF|-DSSS_BUILD_PYTHON=OFF|-DSSS_WITH_GLFW=OFF"
  "${CMAKE_COMMAND}|--build|${build}|-j|${JOBS}"
  "${CMAKE_COMMAND}|--install|${build}|--prefix|${prefix}")

file(GLOB library "${prefix}/lib*/libsss.so.*.*.*")
if(NOT library)
  message(FATAL_ERROR "no shared libsss under ${prefix}")
endif()
execute_process(COMMAND nm -D --defined-only -C "${library}" RESULT_VARIABLE rc OUTPUT_VARIABLE symbols)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "nm -D failed on ${library}")
endif()
string(REGEX MATCHALL "[^\n]+" lines "${symbols}")
list(LENGTH lines exported)
set(problems "")
foreach(line IN LISTS lines)
  # The GL loader, the GL wrappers and the passes stay inside (std:: instantiations may show).
  if(line MATCHES " glad_| gladLoad|sss::gl::|sss::detail::[A-Za-z]*(Pass|RendererAccess)")
    list(APPEND problems "${line}")
  endif()
endforeach()
foreach(needed "sss::VolumeScatteringRenderer::render" "sss::MeshScatteringRenderer::render"
               "sss::HybridCompositor::render" "sss::EglContext::create" "sss::validate")
  string(FIND "${symbols}" "${needed}" at)
  if(at EQUAL -1)
    list(APPEND problems "missing: ${needed}")
  endif()
endforeach()
if(problems)
  string(REPLACE ";" "\n  " text "${problems}")
  message(FATAL_ERROR "${library} exports what it should not, or lacks the public API:\n  ${text}")
endif()
message("${library}: ${exported} exported symbols, no GL loader or internals")

execute_process(COMMAND "${CMAKE_COMMAND}" -DPREFIX=${prefix} -DSOURCE=${CMAKE_CURRENT_LIST_DIR}/../install_consumer/core
                        -DWORK=${WORK}/consumer -P ${CMAKE_CURRENT_LIST_DIR}/../install_consumer/consumer.cmake
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the renderers-only consumer failed against the shared libsss:\n${out}\n${err}")
endif()
message("${err}")
