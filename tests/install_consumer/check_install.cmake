# install_consumer_test (cmake -P): installs the build tree into a scratch prefix, then
# configures, builds and runs the consumer project beside this file against that prefix alone.
# It fails when the install lacks a header, a library, a dependency or the package files.
# -D inputs: BUILD_DIR, CONSUMER_DIR, WORK_DIR, GENERATOR, CXX_COMPILER, LAUNCHER (may be
# empty), SETTINGS (a settings file for the consumer).
foreach(input BUILD_DIR CONSUMER_DIR WORK_DIR GENERATOR CXX_COMPILER SETTINGS)
  if(NOT DEFINED ${input})
    message(FATAL_ERROR "check_install.cmake: -D${input}=... is required")
  endif()
endforeach()

function(run_step name)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE output
                  ERROR_VARIABLE output)
  if(NOT status EQUAL 0)
    string(REPLACE ";" " " command "${ARGN}")
    message(FATAL_ERROR "${name} failed (${status}): ${command}\n${output}")
  endif()
  set(step_output "${output}" PARENT_SCOPE)
endfunction()

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
run_step(install ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

set(launcher)
if(LAUNCHER)
  set(launcher -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
# Only the scratch prefix may provide drvslam: no package registry, no system copy first.
run_step(configure ${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${WORK_DIR}/build -G ${GENERATOR}
         -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX_COMPILER} ${launcher}
         -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
file(STRINGS ${WORK_DIR}/build/CMakeCache.txt found REGEX "^drvslam_DIR:")
string(FIND "${found}" "${prefix}/" at)
if(NOT at GREATER -1)
  message(FATAL_ERROR "the consumer found drvslam outside ${prefix}: ${found}")
endif()
run_step(build ${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run_step(run ${WORK_DIR}/build/drvslam_consumer ${SETTINGS})
message(STATUS "drvslam_consumer:\n${step_output}")
foreach(expected "frame 2: ok, pose_valid 1" "tracked 3 of 3 frames")
  string(FIND "${step_output}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "drvslam_consumer did not print \"${expected}\"")
  endif()
endforeach()
