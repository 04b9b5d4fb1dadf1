# Finds teem (Debian: libteem-dev), which ships no CMake package, as the imported target
# Teem::Teem. Installed with libsss so that sssConfig.cmake finds it the same way on the
# consumer's machine: no absolute path is written into the exported targets.
find_path(Teem_INCLUDE_DIR teem/nrrd.h)
find_library(Teem_LIBRARY teem)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(Teem REQUIRED_VARS Teem_LIBRARY Teem_INCLUDE_DIR)
if(Teem_FOUND AND NOT TARGET Teem::Teem)
  add_library(Teem::Teem UNKNOWN IMPORTED)
  set_target_properties(Teem::Teem PROPERTIES IMPORTED_LOCATION "${Teem_LIBRARY}"
                                              INTERFACE_INCLUDE_DIRECTORIES "${Teem_INCLUDE_DIR}")
endif()
mark_as_advanced(Teem_INCLUDE_DIR Teem_LIBRARY)
