# Finds what the Python module needs (python/): a Python 3 interpreter with its development
# files and pybind11 (Debian: python3-dev, pybind11-dev). Sets DRVSLAM_PYTHON_MODULE when both
# are there; otherwise warns and the module and its tests are left out (an error where
# DRVSLAM_REQUIRE_TEST_DATA is set, as in CI).
#
# Debian's interpreter is preferred: python3-numpy and python3-pytest are installed for it, while
# a pyenv or venv python3 first on PATH usually has neither. -DPython3_EXECUTABLE=... overrides.
if(NOT Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH
      "Python interpreter the drvslam module is built for and tested with")
endif()
find_package(Python3 COMPONENTS Interpreter Development.Module)
if(Python3_FOUND)
  # pybind11's CMake config uses the Python3 found above.
  find_package(pybind11 2.6 CONFIG)
endif()

if(Python3_FOUND AND pybind11_FOUND)
  set(DRVSLAM_PYTHON_MODULE ON)
  # Every module's static library is linked into the shared extension module.
  set(CMAKE_POSITION_INDEPENDENT_CODE ON)
  message(STATUS "drvslam Python module: Python ${Python3_VERSION} (${Python3_EXECUTABLE}), "
                 "pybind11 ${pybind11_VERSION}")
else()
  set(DRVSLAM_PYTHON_MODULE OFF)
  set(missing_text "the Python module drvslam needs Python 3 development files and pybind11 "
                   "(Debian: python3-dev pybind11-dev, see scripts/install-deps.sh)")
  if(DEFINED ENV{DRVSLAM_REQUIRE_TEST_DATA} AND NOT "$ENV{DRVSLAM_REQUIRE_TEST_DATA}" STREQUAL ""
     AND NOT "$ENV{DRVSLAM_REQUIRE_TEST_DATA}" STREQUAL "0")
    message(FATAL_ERROR "${missing_text}; DRVSLAM_REQUIRE_TEST_DATA is set")
  endif()
  message(WARNING "${missing_text}: it and its tests are not built")
endif()
