# FindChipmunk: Chipmunk2D 7 as Debian's libchipmunk-dev installs it
# (/usr/include/chipmunk/chipmunk.h, libchipmunk.so). The package ships no
# pkg-config file and no CMake config, so the header and the library are
# found directly.
#
# Defines Chipmunk_FOUND, Chipmunk_VERSION (from chipmunk.h's CP_VERSION_*)
# and the imported target Chipmunk::Chipmunk, whose include directory is the
# folder holding chipmunk/ (sources write #include <chipmunk/chipmunk.h>).

find_path(Chipmunk_INCLUDE_DIR NAMES chipmunk/chipmunk.h)
find_library(Chipmunk_LIBRARY NAMES chipmunk)

if(Chipmunk_INCLUDE_DIR AND EXISTS "${Chipmunk_INCLUDE_DIR}/chipmunk/chipmunk.h")
  file(STRINGS "${Chipmunk_INCLUDE_DIR}/chipmunk/chipmunk.h" chipmunk_version_lines
       REGEX "^#define CP_VERSION_(MAJOR|MINOR|RELEASE) [0-9]+")
  foreach(part MAJOR MINOR RELEASE)
    string(REGEX REPLACE ".*#define CP_VERSION_${part} ([0-9]+).*" "\\1"
           chipmunk_version_${part} "${chipmunk_version_lines}")
  endforeach()
  set(Chipmunk_VERSION
      "${chipmunk_version_MAJOR}.${chipmunk_version_MINOR}.${chipmunk_version_RELEASE}")
endif()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(Chipmunk
  REQUIRED_VARS Chipmunk_LIBRARY Chipmunk_INCLUDE_DIR
  VERSION_VAR Chipmunk_VERSION)

if(Chipmunk_FOUND AND NOT TARGET Chipmunk::Chipmunk)
  add_library(Chipmunk::Chipmunk UNKNOWN IMPORTED)
  set_target_properties(Chipmunk::Chipmunk PROPERTIES
    IMPORTED_LOCATION "${Chipmunk_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${Chipmunk_INCLUDE_DIR}")
endif()
mark_as_advanced(Chipmunk_INCLUDE_DIR Chipmunk_LIBRARY)
