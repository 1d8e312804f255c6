# Third-party code comes only from Debian 12 packages through find_package
# (../shared/DEPENDENCIES.md lists the packages and the pitfalls worked around here).

find_package(glm CONFIG REQUIRED)
find_package(TBB CONFIG REQUIRED)
find_package(OpenImageIO CONFIG REQUIRED)
find_package(embree 3 CONFIG REQUIRED)
find_package(TinyGLTF CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(nlohmann_json 3 CONFIG REQUIRED)
# KHR_draco_mesh_compression and EXT_meshopt_compression (Debian libdraco-dev, libmeshoptimizer-dev;
# both ship CMake configs in /usr/lib/x86_64-linux-gnu/cmake).
find_package(draco CONFIG REQUIRED)
find_package(meshoptimizer CONFIG REQUIRED)
# Debian's libdraco 1.5.5 carries its own copy of tinygltf (another version, for Draco's glTF
# transcoder) and of stb, and exports both: wherever libdraco.so or the archive member holding them
# comes into a link, the reader's tinygltf calls can bind to that copy, whose Model has another layout
# (a double free at the first file loaded; the static archive is pulled in for libtinygltf's stbi_*
# symbols). So Draco lives only inside gltf/'s svbrdf_draco, a shared library linked with the static
# archive and every archive symbol kept local (gltf/CMakeLists.txt).
find_package(Threads REQUIRED)

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

# Third-party headers are SYSTEM so their warnings never mix with ours.
foreach(_t glm::glm TBB::tbb OpenImageIO::OpenImageIO OpenImageIO::OpenImageIO_Util embree
           TinyGLTF::TinyGLTF CLI11::CLI11 OpenColorIO::OpenColorIO nlohmann_json::nlohmann_json
           draco::draco_static meshoptimizer::meshoptimizer)
  if(TARGET ${_t})
    get_target_property(_inc ${_t} INTERFACE_INCLUDE_DIRECTORIES)
    if(_inc)
      set_target_properties(${_t} PROPERTIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${_inc}")
    endif()
  endif()
endforeach()

if(SVBRDF_BUILD_TESTS)
  find_package(GTest CONFIG REQUIRED)
endif()
if(SVBRDF_BUILD_BENCH)
  find_package(benchmark CONFIG REQUIRED)
endif()
