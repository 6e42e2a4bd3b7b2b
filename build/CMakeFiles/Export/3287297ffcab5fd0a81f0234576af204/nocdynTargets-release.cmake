#----------------------------------------------------------------
# Generated CMake target import file for configuration "Release".
#----------------------------------------------------------------

# Commands may need to know the format version.
set(CMAKE_IMPORT_FILE_VERSION 1)

# Import target "nocdyn::nocdyn" for configuration "Release"
set_property(TARGET nocdyn::nocdyn APPEND PROPERTY IMPORTED_CONFIGURATIONS RELEASE)
set_target_properties(nocdyn::nocdyn PROPERTIES
  IMPORTED_LINK_INTERFACE_LANGUAGES_RELEASE "CXX"
  IMPORTED_LOCATION_RELEASE "${_IMPORT_PREFIX}/lib/libnocdyn.a"
  )

list(APPEND _cmake_import_check_targets nocdyn::nocdyn )
list(APPEND _cmake_import_check_files_for_nocdyn::nocdyn "${_IMPORT_PREFIX}/lib/libnocdyn.a" )

# Commands beyond this point should not need to know the version.
set(CMAKE_IMPORT_FILE_VERSION)
