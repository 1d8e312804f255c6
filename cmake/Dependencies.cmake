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

# Two of Debian's packages need their imported targets mended before use; the installed package's
# config (svbrdfConfig.cmake) applies the same mending for a user's project.
include("${CMAKE_CURRENT_LIST_DIR}/DebianTargetFixes.cmake")

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
