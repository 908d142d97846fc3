# Sanitizer builds (scripts/sanitizers.sh configures them in build-asan/ and build-tsan/).
#
# DRVSLAM_SANITIZE=address: AddressSanitizer + UndefinedBehaviorSanitizer (the checks ASan does
# not already make), undefined behaviour stops the program. DRVSLAM_SANITIZE=thread: ThreadSanitizer. Empty (the default): neither.
# Every target of the project, libraries and executables, gets the same flags, so a test binary
# and the CLI it runs are instrumented alike. Third-party libraries stay uninstrumented.
set(DRVSLAM_SANITIZE "" CACHE STRING "Sanitizers for every target: address, thread or empty")
set_property(CACHE DRVSLAM_SANITIZE PROPERTY STRINGS "" address thread)

if(DRVSLAM_SANITIZE STREQUAL "")
  return()
elseif(DRVSLAM_SANITIZE STREQUAL "address")
  # UBSan without the checks AddressSanitizer already makes (null, bounds, object-size and the
  # nonnull attributes: an access outside an object is a redzone hit) and without vptr. Those
  # checks made an Eigen-heavy unity batch 12-19 % slower to compile (drvslam_optim 99 CPU-s with
  # them, 80 without; drvslam_tracking 25 and 22), and CI builds this tree from scratch on every
  # run. Alignment, integer, shift, float-cast, enum, bool and return checks stay.
  set(drvslam_sanitizer_flags
      -fsanitize=address,undefined
      -fno-sanitize=null,bounds,object-size,nonnull-attribute,returns-nonnull-attribute,vptr
      -fno-sanitize-recover=undefined)
elseif(DRVSLAM_SANITIZE STREQUAL "thread")
  set(drvslam_sanitizer_flags -fsanitize=thread)
else()
  message(FATAL_ERROR "DRVSLAM_SANITIZE must be address, thread or empty, got "
                      "'${DRVSLAM_SANITIZE}'")
endif()
# Frame pointers keep the sanitizers' stack traces whole at -O1.
add_compile_options(${drvslam_sanitizer_flags} -fno-omit-frame-pointer)
add_link_options(${drvslam_sanitizer_flags})

# The targets a sanitizer job builds, as one target (drvslam_sanitizer_set): the Makefile
# generator builds the targets named on one command line one after the other (.NOTPARALLEL), so
# each one's last compile and its link would leave the second core idle; the dependencies of a
# single target are built in parallel.
set(DRVSLAM_SANITIZER_TARGETS "" CACHE STRING "Targets the drvslam_sanitizer_set target builds")
function(drvslam_sanitizer_set)
  add_custom_target(drvslam_sanitizer_set)
  foreach(target_name ${DRVSLAM_SANITIZER_TARGETS})
    if(NOT TARGET ${target_name})
      message(FATAL_ERROR "DRVSLAM_SANITIZER_TARGETS names '${target_name}', which is no target")
    endif()
    add_dependencies(drvslam_sanitizer_set ${target_name})
  endforeach()
endfunction()
cmake_language(DEFER DIRECTORY ${CMAKE_SOURCE_DIR} CALL drvslam_sanitizer_set)

# In a sanitizer tree, targets compiled at -O0 (the orchestration code: the runner, the viewer
# and the evaluation, and in the address tree the CLI). Instrumented and optimized at -O1 they
# cost clang 2-2.5 times as long to compile as at -O0, for code that runs for a small share of
# any test; the code the tests run for long (tracking, mapping, rendering) keeps -O1.
set(DRVSLAM_UNOPTIMIZED_TARGETS "" CACHE STRING "Targets compiled at -O0 (scripts/sanitizers.sh)")
function(drvslam_unoptimized_targets)
  foreach(target_name ${DRVSLAM_UNOPTIMIZED_TARGETS})
    if(NOT TARGET ${target_name})
      message(FATAL_ERROR "DRVSLAM_UNOPTIMIZED_TARGETS names '${target_name}', which is no target")
    endif()
    target_compile_options(${target_name} PRIVATE -O0)
  endforeach()
endfunction()
cmake_language(DEFER DIRECTORY ${CMAKE_SOURCE_DIR} CALL drvslam_unoptimized_targets)
