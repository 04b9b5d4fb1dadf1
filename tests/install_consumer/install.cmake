# cmake -DBUILD=<build tree> -DPREFIX=<dir> -DSOURCE_DIR=<repo> -P install.cmake: installs the
# build tree into PREFIX, then checks the exported package: no absolute path of this machine, no
# build-only target (the glad loader, the warning and sanitizer flags), and a core export set
# that names no package of the optional components.
file(REMOVE_RECURSE "${PREFIX}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD}" --prefix "${PREFIX}"
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc}):\n${err}")
endif()
file(GLOB exports "${PREFIX}/lib*/cmake/sss/*Targets*.cmake")
if(NOT exports)
  message(FATAL_ERROR "no exported targets under ${PREFIX}/lib*/cmake/sss")
endif()
set(problems "")
# Adds "<file> <what> \"<needle>\"" to problems for every needle found in text.
function(forbid file text what)
  foreach(needle IN LISTS ARGN)
    string(FIND "${text}" "${needle}" at)
    if(NOT at EQUAL -1)
      list(APPEND problems "${file} ${what} \"${needle}\"")
    endif()
  endforeach()
  set(problems "${problems}" PARENT_SCOPE)
endfunction()
foreach(file IN LISTS exports)
  file(READ "${file}" text)
  get_filename_component(name "${file}" NAME)
  forbid("${name}" "${text}" "holds" "${SOURCE_DIR}" "${BUILD}" "/usr/" "sss_glad" "sss_warnings"
         "sss_sanitize" "-fsanitize")
  if(name MATCHES "^sssTargets")  # the renderers: no package of another component
    forbid("${name}" "${text}" "links" "VTK::" "assimp::" "OpenEXR::" "tinyobjloader::" "nlohmann_json::" "Teem::"
           "PkgConfig::" "glfw")
  endif()
endforeach()
if(problems)
  string(REPLACE ";" "\n  " text "${problems}")
  message(FATAL_ERROR "the exported package is not relocatable or leaks build-only targets:\n  ${text}")
endif()
list(LENGTH exports count)
message("installed into ${PREFIX}; ${count} export files, relocatable, no build-only targets")
