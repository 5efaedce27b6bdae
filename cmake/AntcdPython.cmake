# Finds what the Python bindings need: Debian's interpreter (python3-dev), pybind11 (pybind11-dev)
# and numpy (python3-numpy). Sets ANTCD_PYTHON_AVAILABLE and, when true, the pybind11 targets.
#
# The interpreter defaults to /usr/bin/python3 when it exists: a machine may have another python3
# earlier on PATH (a virtualenv, a toolchain's own) without Debian's numpy and pybind11.
# Pass -DPython3_EXECUTABLE=... to choose another one.
set(ANTCD_PYTHON_AVAILABLE OFF)
if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "Python interpreter of the antcd bindings")
endif()
find_package(Python3 COMPONENTS Interpreter Development.Module QUIET)
if(Python3_FOUND)
  find_package(pybind11 2.6 CONFIG QUIET)
  execute_process(COMMAND ${Python3_EXECUTABLE} -c "import numpy"
                  RESULT_VARIABLE _antcd_numpy_status OUTPUT_QUIET ERROR_QUIET)
  if(pybind11_FOUND AND _antcd_numpy_status EQUAL 0)
    set(ANTCD_PYTHON_AVAILABLE ON)
  endif()
endif()
if(NOT ANTCD_PYTHON_AVAILABLE)
  message(STATUS "antcd: Python bindings need python3-dev, pybind11-dev and python3-numpy "
                 "(interpreter: ${Python3_EXECUTABLE}); not all found")
endif()
