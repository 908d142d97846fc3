# The linker. mold (Debian's package, which scripts/install-deps.sh installs) when the compiler
# takes -fuse-ld=mold: it linked dynamic_test in 0.3 s where GNU ld took 3.1 s, and a build from
# scratch links some 80 executables (every test binary and benchmark) in each of its trees.
# The program is the same: the linker only lays out the same compiled code. DRVSLAM_LINKER=default
# keeps the compiler's own choice.
set(DRVSLAM_LINKER "mold" CACHE STRING "Linker for -fuse-ld= when the compiler takes it, or default")
if(NOT DRVSLAM_LINKER STREQUAL "default")
  include(CheckLinkerFlag)
  check_linker_flag(CXX "-fuse-ld=${DRVSLAM_LINKER}" DRVSLAM_LINKER_WORKS)
  if(DRVSLAM_LINKER_WORKS)
    add_link_options("-fuse-ld=${DRVSLAM_LINKER}")
  else()
    message(STATUS "drvslam: -fuse-ld=${DRVSLAM_LINKER} does not work here; the default linker links")
  endif()
endif()
