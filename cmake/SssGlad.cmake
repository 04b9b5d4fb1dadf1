# Generates the glad 2 loader for OpenGL 4.5 core (no extensions beyond core) at build time.
# --reproducible uses the Khronos XML bundled with python3-glad, so no network is needed.
find_program(SSS_GLAD_EXECUTABLE glad REQUIRED
  DOC "glad 2 generator (Debian package python3-glad)")
set(SSS_GLAD_DIR "${PROJECT_BINARY_DIR}/glad")
add_custom_command(
  OUTPUT "${SSS_GLAD_DIR}/src/gl.c" "${SSS_GLAD_DIR}/include/glad/gl.h"
  COMMAND "${SSS_GLAD_EXECUTABLE}" --quiet --reproducible --api gl:core=4.5 --extensions=
          --out-path "${SSS_GLAD_DIR}" c
  COMMENT "Generating the glad OpenGL 4.5 core loader"
  VERBATIM)
add_library(sss_glad STATIC "${SSS_GLAD_DIR}/src/gl.c")
set_target_properties(sss_glad PROPERTIES POSITION_INDEPENDENT_CODE ON)
target_include_directories(sss_glad PUBLIC "$<BUILD_INTERFACE:${SSS_GLAD_DIR}/include>")
install(TARGETS sss_glad EXPORT sssTargets)
