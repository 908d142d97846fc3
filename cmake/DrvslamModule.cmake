# drvslam_module(NAME SOURCES ... DEPS ...)
# One static library per module folder: target drvslam_<NAME>. DEPS lists what it links publicly;
# modules may only depend on modules above them in DESIGN.md's layout table.
function(drvslam_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(drvslam_${name} STATIC ${ARG_SOURCES})
  target_include_directories(drvslam_${name} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/src>
                                                    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_options(drvslam_${name} PRIVATE -Wall -Wextra)
  target_link_libraries(drvslam_${name} PUBLIC ${ARG_DEPS})
  set_property(GLOBAL APPEND PROPERTY DRVSLAM_MODULES drvslam_${name})
endfunction()

# drvslam_test(NAME SOURCES ... DEPS ...): one GoogleTest executable registered with CTest.
function(drvslam_test name)
  cmake_parse_arguments(ARG "" "TIMEOUT" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_compile_options(${name} PRIVATE -Wall -Wextra)
  # Shared test helpers (tests/test_support/) are included as "test_support/...".
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests)
  target_compile_definitions(${name} PRIVATE
    DRVSLAM_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    DRVSLAM_SHARED_DIR="${DRVSLAM_SHARED_DIR}"
    DRVSLAM_OPENCV_DATA_DIR="${DRVSLAM_OPENCV_DATA_DIR}"
    DRVSLAM_CLI="$<TARGET_FILE:drvslam_cli>")
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main)
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 600)
  endif()
  include(GoogleTest)
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT ${ARG_TIMEOUT})
endfunction()
