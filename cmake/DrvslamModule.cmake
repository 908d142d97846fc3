# The module graph, enforced at configure time.
#
# drvslam_declare_module(NAME LAYER runtime|tools MAY_USE module...) states, before any module is
# built, which layer a module belongs to and which other modules it may link. A runtime module may
# use runtime modules only; a tools module may use both layers. drvslam_module() then builds the
# module and refuses (FATAL_ERROR) any drvslam module in its DEPS that its declaration does not
# allow, and drvslam_check_module_graph() checks every module's final link interface the same way,
# so a target_link_libraries() written beside drvslam_module() cannot get round the rule.
# docs/architecture.md explains the graph.

function(drvslam_declare_module name)
  cmake_parse_arguments(ARG "" "LAYER" "MAY_USE" ${ARGN})
  if(NOT ARG_LAYER STREQUAL "runtime" AND NOT ARG_LAYER STREQUAL "tools")
    message(FATAL_ERROR "drvslam module '${name}': LAYER must be runtime or tools, "
                        "got '${ARG_LAYER}'")
  endif()
  get_property(known GLOBAL PROPERTY DRVSLAM_DECLARED_MODULES)
  if(name IN_LIST known)
    message(FATAL_ERROR "drvslam module '${name}' is declared twice")
  endif()
  foreach(used ${ARG_MAY_USE})
    if(NOT used IN_LIST known)
      message(FATAL_ERROR "drvslam module '${name}' may use '${used}', which is not declared "
                          "before it: declare modules bottom-up")
    endif()
    get_property(used_layer GLOBAL PROPERTY DRVSLAM_LAYER_${used})
    if(ARG_LAYER STREQUAL "runtime" AND NOT used_layer STREQUAL "runtime")
      message(FATAL_ERROR "drvslam runtime module '${name}' may not use the ${used_layer} "
                          "module '${used}': the runtime library links no tools")
    endif()
  endforeach()
  set_property(GLOBAL APPEND PROPERTY DRVSLAM_DECLARED_MODULES ${name})
  set_property(GLOBAL PROPERTY DRVSLAM_LAYER_${name} ${ARG_LAYER})
  set_property(GLOBAL PROPERTY DRVSLAM_MAY_USE_${name} ${ARG_MAY_USE})
endfunction()

# The drvslam modules a list of link items names: "drvslam_map" and "$<LINK_ONLY:drvslam_map>"
# both name map; targets that are not declared modules (drvslam_octomap) are left out.
function(drvslam_modules_named out)
  get_property(known GLOBAL PROPERTY DRVSLAM_DECLARED_MODULES)
  set(found)
  foreach(item ${ARGN})
    string(REGEX MATCHALL "drvslam_[a-z_]+" names "${item}")
    foreach(target_name ${names})
      string(REGEX REPLACE "^drvslam_" "" module "${target_name}")
      if(module IN_LIST known)
        list(APPEND found ${module})
      endif()
    endforeach()
  endforeach()
  list(REMOVE_DUPLICATES found)
  set(${out} ${found} PARENT_SCOPE)
endfunction()

function(drvslam_require_allowed name)
  get_property(allowed GLOBAL PROPERTY DRVSLAM_MAY_USE_${name})
  get_property(layer GLOBAL PROPERTY DRVSLAM_LAYER_${name})
  drvslam_modules_named(used ${ARGN})
  foreach(module ${used})
    if(NOT module STREQUAL name AND NOT module IN_LIST allowed)
      get_property(used_layer GLOBAL PROPERTY DRVSLAM_LAYER_${module})
      message(FATAL_ERROR "drvslam ${layer} module '${name}' links the ${used_layer} module "
                          "'${module}', which its declaration does not allow (may use: "
                          "${allowed}). Move the code, or change the declaration in "
                          "src/drvslam/CMakeLists.txt and docs/architecture.md together.")
    endif()
  endforeach()
endfunction()

# drvslam_module(NAME SOURCES ... DEPS ...)
# One static library per module folder: target drvslam_<NAME>. DEPS lists what it links publicly.
# The module must have been declared; its DEPS may name only the modules the declaration allows.
function(drvslam_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  get_property(layer GLOBAL PROPERTY DRVSLAM_LAYER_${name})
  if(NOT layer)
    message(FATAL_ERROR "drvslam module '${name}' is built but not declared with "
                        "drvslam_declare_module() in src/drvslam/CMakeLists.txt")
  endif()
  drvslam_require_allowed(${name} ${ARG_DEPS})
  add_library(drvslam_${name} STATIC ${ARG_SOURCES})
  target_include_directories(drvslam_${name} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/src>
                                                    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_options(drvslam_${name} PRIVATE -Wall -Wextra)
  target_link_libraries(drvslam_${name} PUBLIC ${ARG_DEPS})
  set_property(GLOBAL APPEND PROPERTY DRVSLAM_MODULES drvslam_${name})
  if(layer STREQUAL "runtime")
    set_property(GLOBAL APPEND PROPERTY DRVSLAM_RUNTIME_MODULES drvslam_${name})
  else()
    set_property(GLOBAL APPEND PROPERTY DRVSLAM_TOOLS_MODULES drvslam_${name})
  endif()
endfunction()

# After every module exists: each module's links, private ones included, obey its declaration.
function(drvslam_check_module_graph)
  get_property(modules GLOBAL PROPERTY DRVSLAM_MODULES)
  foreach(target_name ${modules})
    string(REGEX REPLACE "^drvslam_" "" name "${target_name}")
    get_target_property(links ${target_name} LINK_LIBRARIES)
    get_target_property(interface_links ${target_name} INTERFACE_LINK_LIBRARIES)
    set(all_links)
    foreach(list_name links interface_links)
      if(${list_name})
        list(APPEND all_links ${${list_name}})
      endif()
    endforeach()
    drvslam_require_allowed(${name} ${all_links})
  endforeach()
endfunction()

# drvslam_test(NAME SOURCES ... DEPS ... [TIMEOUT s] [EACH_TEST] [OPTIMIZED]): one GoogleTest
# executable registered with CTest as one test, the whole binary in one process. EACH_TEST
# registers each of its GoogleTest tests as a CTest test of its own instead (gtest_discover_tests),
# so that CTest spreads a binary of long runs (the integration tests) over the cores. A unit-test
# binary holds many short tests: one process each cost 0.1-0.5 s of start-up apiece (loading
# OpenCV, Open3D, Ceres), 200 CPU-s of the 1,000 a CTest run took, and a listing run of every
# binary at build time.
#
# OPTIMIZED: the binary's own code computes for long (simulations, scenes built point by point),
# so it is compiled at -O1 even where DRVSLAM_TEST_OPTIMIZATION is -O0 (the address job): there,
# at -O0, occupancy_grid_test took 138 s against 9, tracking_causal_pose_filter_test 80 against 3.
function(drvslam_test name)
  cmake_parse_arguments(ARG "EACH_TEST;OPTIMIZED" "TIMEOUT" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  drvslam_test_compile_settings(${name})
  if(ARG_OPTIMIZED)
    target_compile_options(${name} PRIVATE -O1)
  endif()
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main)
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 600)
  endif()
  # Rendered synthetic sequences are shared by the test processes
  # (tests/integration/synth_render_cache.h).
  set(test_environment "DRVSLAM_TEST_SYNTH_CACHE=${CMAKE_BINARY_DIR}/test-synth-cache")
  if(ARG_EACH_TEST)
    # Long runs first (a CTest COST; a fresh build has no timings of earlier runs to order by),
    # so that the short unit-test binaries fill the cores at the end rather than one long run
    # holding the last core alone. The time limit stands for the cost.
    include(GoogleTest)
    gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT ${ARG_TIMEOUT}
      COST ${ARG_TIMEOUT} ENVIRONMENT "${test_environment}")
  else()
    add_test(NAME ${name} COMMAND ${name})
    set_tests_properties(${name} PROPERTIES TIMEOUT ${ARG_TIMEOUT}
      ENVIRONMENT "${test_environment}")
  endif()
endfunction()

# drvslam_test_compile_settings(TARGET): what every test source is compiled with: warnings, the
# shared test helpers (tests/test_support/, included as "test_support/..."), the paths the tests
# resolve their inputs against. Test code is compiled at -O1 whatever the build type: it drives
# the libraries (compiled as the build type says) and does little work of its own, and -O3 made
# the test sources a third slower to compile (tests/tools/eval: 34 CPU-s at -O3, 26 at -O1).
# Optimization levels do not change floating-point results here (no -ffast-math, no FMA).
# The address job compiles them at -O0 (DRVSLAM_TEST_OPTIMIZATION, scripts/sanitizers.sh): clang's
# ASan+UBSan instrumentation optimized at -O1 took 2.4 times as long (dynamic_test's first batch:
# 39 CPU-s at -O1, 16 at -O0), and ASan checks every access at -O0 as well.
set(DRVSLAM_TEST_OPTIMIZATION "-O1" CACHE STRING "Optimization flag of the test sources")
function(drvslam_test_compile_settings name)
  target_compile_options(${name} PRIVATE -Wall -Wextra ${DRVSLAM_TEST_OPTIMIZATION})
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests)
  target_compile_definitions(${name} PRIVATE
    DRVSLAM_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    DRVSLAM_SHARED_DIR="${DRVSLAM_SHARED_DIR}"
    DRVSLAM_OPENCV_DATA_DIR="${DRVSLAM_OPENCV_DATA_DIR}"
    DRVSLAM_CLI="$<TARGET_FILE:drvslam_cli>")
endfunction()

# drvslam_test_uses_cli(NAME): the test runs the built CLI (DRVSLAM_CLI), at least to render its
# synthetic sequences, so the CLI is built first. With DRVSLAM_TESTS_WITHOUT_CLI the tests render
# with another build's CLI (DRVSLAM_TEST_SYNTH_CLI) and run none of the CLI's own code: the TSan
# job (scripts/sanitizers.sh) then does not build an instrumented CLI, nor the ROS 2 node and
# apps/ that only the CLI links.
option(DRVSLAM_TESTS_WITHOUT_CLI
       "Tests do not build the CLI: they render with DRVSLAM_TEST_SYNTH_CLI (the TSan job)" OFF)
function(drvslam_test_uses_cli name)
  if(NOT DRVSLAM_TESTS_WITHOUT_CLI)
    add_dependencies(${name} drvslam_cli)
  endif()
endfunction()
