# The libraries Debian ships without a CMake package file (OpenCV's core module: its package file comes
# only with all of libopencv-dev; ARM's astcenc, whose file names a versioned library; xxHash, libdeflate, Zstandard), as imported targets found where this
# machine has them. heightpack's own build and its installed package both include this file, so the
# exported targets name heightpack_dep::<name>, never a path: an installed heightpack can be moved, and
# the machine that uses it finds these libraries again.
#   heightpack_import_library(NAME LIBRARY HEADER [PATH_SUFFIX suffix])
function(heightpack_import_library name library header)
  cmake_parse_arguments(PARSE_ARGV 3 ARG "" "PATH_SUFFIX" "")
  if(TARGET heightpack_dep::${name})
    return()
  endif()
  string(TOUPPER "${name}" upper)
  find_library(HEIGHTPACK_${upper}_LIBRARY NAMES ${library})
  find_path(HEIGHTPACK_${upper}_INCLUDE_DIR NAMES ${header} PATH_SUFFIXES ${ARG_PATH_SUFFIX})
  if(NOT HEIGHTPACK_${upper}_LIBRARY OR NOT HEIGHTPACK_${upper}_INCLUDE_DIR)
    message(FATAL_ERROR "heightpack needs ${library} (${header}): install its Debian -dev package "
                        "(scripts/install-deps.sh lists them)")
  endif()
  add_library(heightpack_dep::${name} UNKNOWN IMPORTED)
  set_target_properties(heightpack_dep::${name} PROPERTIES IMPORTED_LOCATION "${HEIGHTPACK_${upper}_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${HEIGHTPACK_${upper}_INCLUDE_DIR}")
endfunction()

# Which floor needs which (see libpack/CMakeLists.txt).
macro(heightpack_import_core_libraries)
  heightpack_import_library(opencv_core opencv_core opencv2/core.hpp PATH_SUFFIX opencv4)
  heightpack_import_library(astcenc astcenc astcenc.h)
endmacro()
macro(heightpack_import_io_libraries)
  heightpack_import_library(xxhash xxhash xxhash.h)
  heightpack_import_library(deflate deflate libdeflate.h)
  heightpack_import_library(zstd zstd zstd.h)
endmacro()
