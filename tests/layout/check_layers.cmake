# cmake -DSOURCE=<repo> -P check_layers.cmake: the include graph points down only.
#   include/sss  -> include/sss only (the public API never reaches into src/)
#   src/gl       -> gl/
#   src/lighting -> gl/, lighting/
#   src/mesh     -> gl/, lighting/, mesh/        (never volume/ or hybrid/)
#   src/volume   -> gl/, lighting/, volume/      (never mesh/ or hybrid/)
#   src/hybrid   -> anything below it
# Every layer may include sss/ (public headers) and the top-level helpers of src/.
set(rules
  "include/sss|src/|gl/|lighting/|mesh/|volume/|hybrid/"
  "src/gl|lighting/|mesh/|volume/|hybrid/"
  "src/lighting|mesh/|volume/|hybrid/"
  "src/mesh|volume/|hybrid/"
  "src/volume|mesh/|hybrid/")
set(violations "")
foreach(rule IN LISTS rules)
  string(REPLACE "|" ";" parts "${rule}")
  list(POP_FRONT parts dir)
  file(GLOB files "${SOURCE}/${dir}/*.h" "${SOURCE}/${dir}/*.cpp")
  foreach(file IN LISTS files)
    file(STRINGS "${file}" includes REGEX "^#include \"")
    foreach(line IN LISTS includes)
      foreach(forbidden IN LISTS parts)
        if(line MATCHES "^#include \"(\\.\\./)*${forbidden}")
          file(RELATIVE_PATH rel "${SOURCE}" "${file}")
          list(APPEND violations "${rel}: ${line}")
        endif()
      endforeach()
    endforeach()
  endforeach()
endforeach()
if(violations)
  string(REPLACE ";" "\n  " text "${violations}")
  message(FATAL_ERROR "includes that point up or sideways:\n  ${text}")
endif()
message("layers: every include points down")
