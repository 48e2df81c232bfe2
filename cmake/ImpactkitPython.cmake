# The Python module (python/) is built when pybind11 and a Python with its
# development files are found. The interpreter is pinned to the system's
# /usr/bin/python3 (Debian's, where python3-numpy and python3-pytest are
# installed) unless Python3_EXECUTABLE is given: a pyenv or virtualenv python3
# earlier on PATH would otherwise be picked, and the module would not import
# in the interpreter the tests and the docs use.
if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "Python interpreter for the impactkit module")
endif()
find_package(Python3 COMPONENTS Interpreter Development.Module)
if(Python3_FOUND)
  # pybind11 uses the Python3 found above (its FindPython mode).
  find_package(pybind11 2.6 CONFIG)
endif()
if(Python3_FOUND AND pybind11_FOUND)
  message(STATUS "impactkit: Python module for ${Python3_EXECUTABLE} (${Python3_VERSION})")
  add_subdirectory(python)
else()
  message(STATUS "impactkit: no Python module (needs pybind11-dev and python3-dev)")
endif()
