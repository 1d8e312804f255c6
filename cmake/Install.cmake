# `cmake --install` (`make install PREFIX=...`): the libraries a user links, their public headers, the
# programs, and the CMake package svbrdf (find_package(svbrdf CONFIG); docs/library.md).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# The floors a user links, each with its dependencies below it, and the Draco decoder gltf/ loads.
set(SVBRDF_EXPORTED_MODULES base appearance textures gltf mip render)

# The public headers: what a user of each floor includes. Whatever these include comes with them
# (cmake/InstallHeaders.cmake) but is not the interface; mip/'s are its facade (docs/design.md).
set(SVBRDF_PUBLIC_HEADERS
  base/error.h base/math.h
  appearance/bsdf.h appearance/registry.h appearance/frame.h appearance/fresnel.h appearance/albedo.h
  appearance/lambert.h appearance/phong.h appearance/blinn_phong.h appearance/lafortune.h
  appearance/microfacet.h appearance/cook_torrance.h appearance/oren_nayar.h appearance/eon.h
  appearance/gltf.h appearance/gltf_bsdf.h appearance/gltf_surface_bsdf.h appearance/measured.h
  appearance/mirror.h appearance/dielectric.h appearance/conductor_mirror.h appearance/mixture.h
  appearance/sheen.h appearance/thin_film.h appearance/microfacet_normal_mapping.h
  textures/image.h textures/color.h textures/sampler.h textures/material_texels.h
  textures/material_loader.h textures/material_family.h
  gltf/scene.h gltf/scene_reader.h
  mip/mip.h mip/texture_filter.h mip/mip_file.h mip/metrics.h mip/gltf_material.h
  render/render_setup.h render/renderer.h render/output.h render/mip_cache.h)

# Installed programs and libraries find the project's shared libraries (svbrdf_draco; every module
# under BUILD_SHARED_LIBS) beside them.
set(_svbrdf_rpath "$ORIGIN/../${CMAKE_INSTALL_LIBDIR}")
set(_svbrdf_installed svbrdf-render svbrdf-bake svbrdf-brdf svbrdf-lod-report svbrdf_draco)
foreach(_m IN LISTS SVBRDF_EXPORTED_MODULES)
  list(APPEND _svbrdf_installed svbrdf_${_m})
endforeach()
set_target_properties(${_svbrdf_installed} PROPERTIES INSTALL_RPATH "${_svbrdf_rpath}")
set_target_properties(svbrdf_draco PROPERTIES EXPORT_NAME draco_decoder)
if(BUILD_SHARED_LIBS)
  # The modules the programs alone link are shared too; they install beside the exported ones.
  set(_svbrdf_program_modules scenes lod plots compare random_family render_command)
  foreach(_m IN LISTS _svbrdf_program_modules)
    set_target_properties(svbrdf_${_m} PROPERTIES INSTALL_RPATH "${_svbrdf_rpath}")
    install(TARGETS svbrdf_${_m} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  endforeach()
endif()

install(TARGETS svbrdf-render svbrdf-bake svbrdf-brdf svbrdf-lod-report RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The scenes the build bakes, where the installed svbrdf-render and svbrdf-lod-report look for them
# (apps/baked_scenes.h).
install(DIRECTORY "${PROJECT_BINARY_DIR}/scenes/showcase" "${PROJECT_BINARY_DIR}/scenes/lod"
  DESTINATION ${CMAKE_INSTALL_DATADIR}/svbrdf/scenes)
list(TRANSFORM SVBRDF_EXPORTED_MODULES PREPEND svbrdf_ OUTPUT_VARIABLE _svbrdf_export_targets)
install(TARGETS ${_svbrdf_export_targets} svbrdf_draco EXPORT svbrdfTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

string(JOIN "|" _svbrdf_floors ${SVBRDF_EXPORTED_MODULES})
install(CODE "
  set(HEADERS \"${SVBRDF_PUBLIC_HEADERS}\")
  set(FLOORS \"${_svbrdf_floors}\")
  set(SOURCE \"${PROJECT_SOURCE_DIR}\")
  set(DEST \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_INCLUDEDIR}\")
  include(\"${PROJECT_SOURCE_DIR}/cmake/InstallHeaders.cmake\")")

set(_svbrdf_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/svbrdf)
install(EXPORT svbrdfTargets NAMESPACE svbrdf:: DESTINATION ${_svbrdf_cmake_dir})
configure_package_config_file(cmake/svbrdfConfig.cmake.in "${PROJECT_BINARY_DIR}/svbrdfConfig.cmake"
  INSTALL_DESTINATION ${_svbrdf_cmake_dir})
# While the major version is 0, a minor release may change the interface (Semantic Versioning 2.0.0,
# item 4): a request for 0.1 accepts 0.1.x only (docs/design-notes.md).
write_basic_package_version_file("${PROJECT_BINARY_DIR}/svbrdfConfigVersion.cmake" COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/svbrdfConfig.cmake" "${PROJECT_BINARY_DIR}/svbrdfConfigVersion.cmake"
  cmake/DebianTargetFixes.cmake DESTINATION ${_svbrdf_cmake_dir})
