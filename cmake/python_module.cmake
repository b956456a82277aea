# Finds what the Python module needs (Python's headers and pybind11) and sets CAUSTICA_WITH_PYTHON
# and, then, CMAKE_POSITION_INDEPENDENT_CODE for every library. Prints why when it is off.
set(CAUSTICA_WITH_PYTHON OFF)
if(NOT CAUSTICA_PYTHON)
  message(STATUS "caustica: Python module disabled (CAUSTICA_PYTHON=OFF)")
  return()
endif()
find_package(Python 3.8 COMPONENTS Interpreter Development.Module)
if(Python_FOUND)
  find_package(pybind11 2.10 CONFIG QUIET)
endif()
if(Python_FOUND AND pybind11_FOUND)
  set(CAUSTICA_WITH_PYTHON ON)
  set(CMAKE_POSITION_INDEPENDENT_CODE ON)
  message(STATUS "caustica: Python module enabled (Python ${Python_VERSION}, ${Python_EXECUTABLE}; "
                 "pybind11 ${pybind11_VERSION})")
elseif(NOT Python_FOUND)
  message(STATUS "caustica: Python module disabled (no Python 3 interpreter with headers found: "
                 "install python3-dev, scripts/install-deps does)")
else()
  message(STATUS "caustica: Python module disabled (pybind11 >= 2.10 not found: install pybind11-dev, "
                 "scripts/install-deps does)")
endif()
