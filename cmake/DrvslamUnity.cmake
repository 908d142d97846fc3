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
# Files that define a helper of the same name as a sibling's in their anonymous namespaces would
# clash in one batch: they are compiled on their own (a new clash is a compile error naming both
# files; add one of them here).
set(DRVSLAM_NO_UNITY_FILES
  src/drvslam/loop/vocabulary_io.cc            # kDescriptorBytes (bow_vocabulary.cc)
  src/drvslam/tools/synth/camera_path.cc       # kTwoPi (actors.cc)
  src/drvslam/tools/synth/sensor_model.cc      # InRange, Require (real_camera_options.cc), kBands
  src/drvslam/tools/synth/synth_sequence.cc    # CocoName (synth_options.cc)
  tests/dense/dense_evidence_test.cc           # kPersonClass (dense_mapper_test.cc)
  tests/feature/orb_invariance_test.cc         # Extract, Features (orb_extractor_test.cc)
  tests/feature/steered_brief_test.cc          # Noise (gaussian_smoothing_test.cc)
  tests/integration/reset_when_lost_test.cc    # kFrames (frame_faults_test.cc)
  tests/loop/vocabulary_io_test.cc             # TrainedVocabulary (bow_transform_test.cc)
  tests/optim/se3_manifold_test.cc             # Ambient, PlusJacobian (pose_costs_test.cc)
  tests/tools/synth/lens_distortion_test.cc    # Centroid (scene_test.cc), SmallOptions
  tests/tools/synth/real_camera_test.cc)       # SmallOptions (synth_sequence_test.cc)
function(drvslam_unity_exceptions)
  # Each file's folder is where its target is made, so that is the scope of its property. A
  # source with compile definitions of its own is left out of the unity batches (CMake's
  # UNITY_BUILD); SKIP_UNITY_BUILD_INCLUDE would be read too early, when the target is made.
  foreach(file ${DRVSLAM_NO_UNITY_FILES})
    get_filename_component(folder ${PROJECT_SOURCE_DIR}/${file} DIRECTORY)
    if(EXISTS ${PROJECT_SOURCE_DIR}/${file})
      set_source_files_properties(${PROJECT_SOURCE_DIR}/${file} DIRECTORY ${folder}
                                  PROPERTIES COMPILE_DEFINITIONS DRVSLAM_OUTSIDE_UNITY_BATCH)
    endif()
  endforeach()
endfunction()
# Once every target exists.
cmake_language(DEFER DIRECTORY ${CMAKE_SOURCE_DIR} CALL drvslam_unity_exceptions)
