# Our code builds with zero warnings under -Wall -Wextra -Wpedantic; third-party headers are SYSTEM.
add_library(svbrdf_warnings INTERFACE)
target_compile_options(svbrdf_warnings INTERFACE -Wall -Wextra -Wpedantic)

if(SVBRDF_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()

# libFuzzer steers by the coverage of the code under test: every library is instrumented for it, and
# only the fuzz targets link libFuzzer itself (fuzz/CMakeLists.txt).
if(SVBRDF_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "SVBRDF_FUZZ needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++-14")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()

# svbrdf_module(NAME SOURCES... DEPS ...): a module library svbrdf_NAME with alias svbrdf::NAME,
# include root at the repository root so code writes #include "appearance/bsdf.h". Static, or shared
# under BUILD_SHARED_LIBS. A user's code writes <svbrdf/appearance/bsdf.h> against the build tree
# (<build>/include/svbrdf/FLOOR links to each floor) as against an installed one (docs/library.md).
function(svbrdf_module name)
  cmake_parse_arguments(M "" "" "SOURCES;DEPS" ${ARGN})
  add_library(svbrdf_${name} ${M_SOURCES})
  add_library(svbrdf::${name} ALIAS svbrdf_${name})
  target_include_directories(svbrdf_${name} PUBLIC
    "$<BUILD_INTERFACE:${PROJECT_SOURCE_DIR};${PROJECT_BINARY_DIR}/include>" "$<INSTALL_INTERFACE:include>")
  # The warning flags are this build's, not a user's: they stay out of the exported package.
  target_link_libraries(svbrdf_${name} PUBLIC ${M_DEPS} PRIVATE $<BUILD_INTERFACE:svbrdf_warnings>)
  set_target_properties(svbrdf_${name} PROPERTIES EXPORT_NAME ${name})
  if(NOT EXISTS "${PROJECT_BINARY_DIR}/include/svbrdf/${name}" AND EXISTS "${PROJECT_SOURCE_DIR}/${name}")
    file(MAKE_DIRECTORY "${PROJECT_BINARY_DIR}/include/svbrdf")
    file(CREATE_LINK "${PROJECT_SOURCE_DIR}/${name}" "${PROJECT_BINARY_DIR}/include/svbrdf/${name}" SYMBOLIC)
  endif()
endfunction()

# svbrdf_program(NAME SOURCES... DEPS ...): a thin main (CLI11) over a module library.
function(svbrdf_program name)
  cmake_parse_arguments(P "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${P_SOURCES})
  target_link_libraries(${name} PRIVATE ${P_DEPS} CLI11::CLI11 svbrdf_warnings)
  # Every program lands at the top of the build tree (build/svbrdf-bake, ...), where the README runs it.
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY "${PROJECT_BINARY_DIR}")
endfunction()
