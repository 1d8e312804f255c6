# The fuzz targets' code as a library, for the libFuzzer executables (fuzz/CMakeLists.txt) and for the
# replay program the default test suite runs on the regression inputs (tests/fuzz/CMakeLists.txt).
if(NOT TARGET svbrdf_fuzz_targets)
  add_library(svbrdf_fuzz_targets STATIC
    "${PROJECT_SOURCE_DIR}/fuzz/file_targets.cpp"
    "${PROJECT_SOURCE_DIR}/fuzz/memory_targets.cpp"
    "${PROJECT_SOURCE_DIR}/fuzz/scratch_file.cpp")
  target_include_directories(svbrdf_fuzz_targets PUBLIC "${PROJECT_SOURCE_DIR}")
  target_link_libraries(svbrdf_fuzz_targets PUBLIC svbrdf::gltf svbrdf::mip svbrdf::textures svbrdf::scenes
    svbrdf::plots svbrdf::appearance PRIVATE svbrdf_warnings)
endif()
