# Mends two of Debian 12's imported targets (../shared/DEPENDENCIES.md): included by this build's
# cmake/Dependencies.cmake after find_package(OpenImageIO), and by the installed svbrdfConfig.cmake after
# find_dependency(OpenImageIO), so a project linking svbrdf::textures configures as this one does.

# Pitfall 1: OpenImageIO's exported target names /usr/include/opencv4 even where OpenCV is absent;
# drop include directories that do not exist so the generate step cannot fail on them.
get_target_property(_oiio_inc OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
if(_oiio_inc)
  set(_oiio_kept "")
  foreach(_d IN LISTS _oiio_inc)
    if(EXISTS "${_d}" OR _d MATCHES "^\\$<")
      list(APPEND _oiio_kept "${_d}")
    endif()
  endforeach()
  set_target_properties(OpenImageIO::OpenImageIO PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_oiio_kept}")
endif()

# Pitfall 2: OpenColorIO's CMake config is off the search path and computes a wrong prefix when forced;
# build the imported target from the header and the library.
if(NOT TARGET OpenColorIO::OpenColorIO)
  find_path(OCIO_INCLUDE_DIR OpenColorIO/OpenColorIO.h REQUIRED)
  find_library(OCIO_LIBRARY OpenColorIO REQUIRED)
  add_library(OpenColorIO::OpenColorIO UNKNOWN IMPORTED)
  set_target_properties(OpenColorIO::OpenColorIO PROPERTIES
    IMPORTED_LOCATION "${OCIO_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${OCIO_INCLUDE_DIR}")
endif()
