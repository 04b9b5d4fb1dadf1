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
# Compiled into libsss itself (an object library), so the package exports no loader target.
# sss_glad_headers gives the loader's header to libsss and to the white-box GL tests.
add_library(sss_glad_headers INTERFACE)
target_include_directories(sss_glad_headers INTERFACE "$<BUILD_INTERFACE:${SSS_GLAD_DIR}/include>")
add_library(sss_glad OBJECT "${SSS_GLAD_DIR}/src/gl.c")
# Hidden: a shared libsss keeps its GL loader to itself (the host application may have its own).
set_target_properties(sss_glad PROPERTIES POSITION_INDEPENDENT_CODE ON C_VISIBILITY_PRESET hidden)
target_link_libraries(sss_glad PRIVATE sss_glad_headers)
