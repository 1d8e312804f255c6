# The install test: installs the build into a fresh prefix, renders the installed showcase with the
# installed svbrdf-render (its RPATH, its scene lookup), then configures, builds and runs the consumer
# project (tests/install/consumer) against that prefix alone.
#   cmake -DBUILD=<build tree> -DWORK=<scratch folder> -DCONSUMER=<consumer source>
#         -DCXX=<compiler> -DFLAGS=<compile flags> -DLAUNCHER=<ccache or empty> -P run-consumer.cmake
function(step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}")
  endif()
  message(STATUS "${what}: done")
  set(output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE "${WORK}")
step("cmake --install" "${CMAKE_COMMAND}" --install "${BUILD}" --prefix "${WORK}/prefix")
step("render the installed showcase" "${WORK}/prefix/bin/svbrdf-render" --res 16x9 --spp 1 --filter level0 --quiet
  --out "${WORK}/showcase.exr")
if(NOT EXISTS "${WORK}/showcase.exr")
  message(FATAL_ERROR "the installed svbrdf-render wrote no ${WORK}/showcase.exr")
endif()
step("configure the consumer" "${CMAKE_COMMAND}" -S "${CONSUMER}" -B "${WORK}/build" -G Ninja
  -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_COMPILER=${CXX} "-DCMAKE_CXX_FLAGS=${FLAGS}"
  -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER} "-DCMAKE_PREFIX_PATH=${WORK}/prefix"
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
step("build the consumer" "${CMAKE_COMMAND}" --build "${WORK}/build")
step("run the consumer" "${WORK}/build/consumer")
message(STATUS "${output}")
