# The Python module (python/): pybind11 from Debian (pybind11-dev) for Debian's Python 3 with numpy.
# On by default wherever pybind11 is found (tools/install-deps installs it); a machine without it
# builds everything else and says so. Off under the sanitizers and the fuzzing build: an instrumented
# extension needs its runtime preloaded into the interpreter, which none of their runs does.
# Whether pybind11 is there decides the default; its package is loaded only once the interpreter is
# chosen (it looks for Python itself when none is found yet).
find_file(SVBRDF_PYBIND11_CONFIG pybind11Config.cmake PATH_SUFFIXES lib/cmake/pybind11 share/cmake/pybind11
          DOC "pybind11's CMake package (Debian: pybind11-dev)")
set(_svbrdf_python_default OFF)
if(SVBRDF_PYBIND11_CONFIG AND NOT SVBRDF_SANITIZE AND NOT SVBRDF_FUZZ)
  set(_svbrdf_python_default ON)
endif()
option(SVBRDF_BUILD_PYTHON "Build the Python module svbrdf (pybind11, numpy)" ${_svbrdf_python_default})

if(SVBRDF_BUILD_PYTHON)
  # The interpreter the module is built for and its tests run under: the first python3 that imports
  # numpy, the one on PATH before the system's (a PATH may lead to an interpreter without numpy,
  # while Debian's python3-numpy belongs to /usr/bin/python3). -DPython3_EXECUTABLE=... overrides.
  if(NOT Python3_EXECUTABLE)
    find_program(_svbrdf_path_python NAMES python3 NO_CACHE)
    foreach(candidate IN ITEMS "${_svbrdf_path_python}" /usr/bin/python3)
      if(candidate AND EXISTS "${candidate}")
        execute_process(COMMAND "${candidate}" -c "import numpy" RESULT_VARIABLE _svbrdf_numpy OUTPUT_QUIET ERROR_QUIET)
        if(_svbrdf_numpy EQUAL 0)
          set(Python3_EXECUTABLE "${candidate}" CACHE FILEPATH "The Python 3 interpreter (with numpy)")
          break()
        endif()
      endif()
    endforeach()
  endif()
  find_package(Python3 REQUIRED COMPONENTS Interpreter Development.Module)
  execute_process(COMMAND "${Python3_EXECUTABLE}" -c "import numpy" RESULT_VARIABLE _svbrdf_numpy OUTPUT_QUIET ERROR_QUIET)
  if(NOT _svbrdf_numpy EQUAL 0)
    message(FATAL_ERROR "SVBRDF_BUILD_PYTHON: ${Python3_EXECUTABLE} cannot import numpy (Debian: python3-numpy; "
                        "tools/install-deps installs it), or configure with -DSVBRDF_BUILD_PYTHON=OFF")
  endif()
  find_package(pybind11 2.10 CONFIG REQUIRED)
  # The module is a shared object that links the module libraries, which are static: python/ compiles
  # them position-independent.
elseif(NOT SVBRDF_PYBIND11_CONFIG AND NOT SVBRDF_SANITIZE AND NOT SVBRDF_FUZZ)
  message(STATUS "svbrdf: pybind11 not found (Debian: pybind11-dev); the Python module is not built")
endif()
