# cmake -DSOURCE=<repo> -P check_layers.cmake: the include graph of src/ points down only, and
# every file of src/ is in a layer (none directly in src/, none in an unknown folder).
#
# The layers, from the bottom; a folder may include the folders listed for it (and itself).
# Every folder may include the public headers (sss/...), and include/sss may include only those.
#   util       -                                      formatting, logging, threads
#   core       util                                   meshes, volumes, images, cameras, lights
#   gl         util core                              RAII GL objects, the shader preprocessor
#   platform   util core gl                           contexts
#   frame      util core gl platform                  render targets, display, accumulation, timers
#   lighting   util core gl frame                     light and shadow uniforms shared by passes
#   mesh       util core gl frame lighting            the mesh passes (Dal Corso 2017)
#   volume     util core gl frame lighting            the volume passes (Ropinski 2010)
#   hybrid     util core gl frame lighting mesh volume
#   io         util core                              file readers and writers (component io)
#   reference  util core mesh volume                  CPU ground truths (component reference)
#   scene      util core io                           scene files (component scene)
cmake_minimum_required(VERSION 3.25)
set(layers
  "util|"
  "core|util"
  "gl|util,core"
  "platform|util,core,gl"
  "frame|util,core,gl,platform"
  "lighting|util,core,gl,frame"
  "mesh|util,core,gl,frame,lighting"
  "volume|util,core,gl,frame,lighting"
  "hybrid|util,core,gl,frame,lighting,mesh,volume"
  "io|util,core"
  "reference|util,core,mesh,volume"
  "scene|util,core,io")
set(names "")
foreach(layer IN LISTS layers)
  string(REPLACE "|" ";" parts "${layer}")
  string(REPLACE "," ";" parts "${parts}")
  list(GET parts 0 name)
  list(APPEND names "${name}")
endforeach()

set(violations "")
# What a quoted include names: "dir/file" -> dir, "../" prefixes dropped (shader texts).
function(check_file file allowed)
  file(STRINGS "${file}" includes REGEX "^#include \"")
  file(RELATIVE_PATH rel "${SOURCE}" "${file}")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^#include \"((\\.\\./)*)([^\"]*)\".*" "\\3" target "${line}")
    # Shader texts (one dipole text for GLSL and C++) and tables beside the file.
    if(target MATCHES "^shaders/")
      continue()
    endif()
    if(target MATCHES "\\.inc$" AND NOT target MATCHES "/")
      continue()
    endif()
    string(REGEX MATCH "^[^/]+" top "${target}")
    if(top STREQUAL target)
      list(APPEND violations "${rel}: ${line} (includes must name their folder)")
    elseif(NOT top IN_LIST allowed)
      list(APPEND violations "${rel}: ${line}")
    endif()
  endforeach()
  set(violations "${violations}" PARENT_SCOPE)
endfunction()

foreach(layer IN LISTS layers)
  string(REPLACE "|" ";" parts "${layer}")
  string(REPLACE "," ";" parts "${parts}")
  list(POP_FRONT parts name)
  set(allowed sss ${name} ${parts})
  file(GLOB_RECURSE files "${SOURCE}/src/${name}/*")
  foreach(file IN LISTS files)
    if(file MATCHES "\\.(h|cpp|inc)$")
      check_file("${file}" "${allowed}")
    endif()
  endforeach()
endforeach()

file(GLOB_RECURSE headers "${SOURCE}/include/sss/*")
foreach(file IN LISTS headers)
  check_file("${file}" "sss")
endforeach()

# Every source file of src/ sits in a layer folder.
file(GLOB_RECURSE all RELATIVE "${SOURCE}/src" "${SOURCE}/src/*")
foreach(rel IN LISTS all)
  if(rel STREQUAL "CMakeLists.txt")
    continue()
  endif()
  string(REGEX MATCH "^[^/]+" top "${rel}")
  if(top STREQUAL rel)
    list(APPEND violations "src/${rel}: a file directly in src/, outside every layer")
  elseif(NOT top IN_LIST names)
    list(APPEND violations "src/${rel}: folder ${top}/ is not a layer of tests/layout/check_layers.cmake")
  endif()
endforeach()

if(violations)
  string(REPLACE ";" "\n  " text "${violations}")
  message(FATAL_ERROR "includes that point up or sideways, or files outside the layers:\n  ${text}")
endif()
message("layers: every include of src/ points down, and every file is in a layer")
