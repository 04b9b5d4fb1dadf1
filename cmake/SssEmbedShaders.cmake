# sss_embed_shaders(<target> <shader root> <files...>)
# Turns each shader file into an entry of a generated C++ table (path relative to the root ->
# contents), compiled into <target>. The generated file is rebuilt when any shader changes.
function(sss_embed_shaders target root)
  set(out "${CMAKE_CURRENT_BINARY_DIR}/embedded_shaders.cpp")
  set(abs_files "")
  foreach(f IN LISTS ARGN)
    list(APPEND abs_files "${root}/${f}")
  endforeach()
  add_custom_command(
    OUTPUT "${out}"
    COMMAND ${CMAKE_COMMAND} -DROOT=${root} "-DFILES=${ARGN}" -DOUT=${out}
            -P "${PROJECT_SOURCE_DIR}/cmake/SssEmbedShadersScript.cmake"
    DEPENDS ${abs_files} "${PROJECT_SOURCE_DIR}/cmake/SssEmbedShadersScript.cmake"
    COMMENT "Embedding ${target} shaders"
    VERBATIM)
  target_sources(${target} PRIVATE "${out}")
endfunction()
