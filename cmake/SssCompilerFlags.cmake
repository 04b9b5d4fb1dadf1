# INTERFACE targets carrying compiler flags, instead of global CMAKE_CXX_FLAGS.
add_library(sss_warnings INTERFACE)
target_compile_options(sss_warnings INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion>
  # GCC 12 reports impossible memcpy overlaps inside std::string concatenation (GCC bug 105329).
  $<$<AND:$<CXX_COMPILER_ID:GNU>,$<VERSION_LESS:$<CXX_COMPILER_VERSION>,13>>:-Wno-restrict>
  $<$<AND:$<CXX_COMPILER_ID:GNU,Clang>,$<BOOL:${SSS_WARNINGS_AS_ERRORS}>>:-Werror>)

add_library(sss_sanitize INTERFACE)
if(SSS_SANITIZE)
  target_compile_options(sss_sanitize INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer
                                                -fno-sanitize-recover=undefined)
  target_link_options(sss_sanitize INTERFACE -fsanitize=address,undefined)
endif()

# sss_gl_process(<target>): marks an executable that creates GL contexts (see the comment in
# sss_gl_process_asan_options.c for why sanitized GL processes run without leak checking).
function(sss_gl_process target)
  if(SSS_SANITIZE)
    target_sources(${target} PRIVATE "${PROJECT_SOURCE_DIR}/cmake/sss_gl_process_asan_options.c")
  endif()
endfunction()
