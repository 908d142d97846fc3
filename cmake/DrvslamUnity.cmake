# Unity builds. scripts/build.sh (the release build) and scripts/sanitizers.sh configure with
# CMAKE_UNITY_BUILD=ON: one compiler run per target (below), so the heavy Eigen, OpenCV, Ceres and
# GoogleTest headers are parsed once per target, not once per file. A plain `cmake -S . -B build`
# builds file by file, as before; both give the same program (tests/ and the sequential outputs
# give byte-identical --sequential outputs: docs/getting-started.md).
# One batch per target (UNITY_BUILD_BATCH_SIZE 0, where CMake's default is 8 files): every batch
# parses and instantiates the same Eigen, OpenCV and GoogleTest code again. Compiled as one batch,
# drvslam_dense took 29 CPU-s against 38 in three, drvslam_semantic 47 against 64. Two cores stay
# busy: there are more targets than cores from the start of the build.
if(NOT DEFINED CMAKE_UNITY_BUILD_BATCH_SIZE)
  set(CMAKE_UNITY_BUILD_BATCH_SIZE 0)
endif()
# Every source is in its target's batch, so helpers in the anonymous namespaces of files of one
# target share a scope: two of the same name are a compile error that names both files. Give
# the helpers names that say what they are for (compiling each such file on its own cost 98
# CPU-s in the release tree, 127 in the address tree and 61 in the thread tree).
