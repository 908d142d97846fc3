// LocalMappingOptions: the local mapping thread's settings ("LocalMapping.*" keys beside the
// ORB-SLAM2 ones). Defaults follow ORB-SLAM2's RGB-D configuration.
#pragma once

#include <cstddef>

#include "drvslam/core/option_table.h"
#include "drvslam/core/settings_file.h"

namespace drvslam {

struct LocalMappingOptions {
  // false: keyframes only get their bookkeeping (observations, normals, descriptors,
  // covisibility), done at once on the tracking thread: tracking alone, as a baseline.
  bool enabled = true;
  // Covisible keyframes searched for new points and for duplicates (ORB-SLAM2 RGB-D: 10).
  int triangulation_neighbours = 10;
  int fusion_neighbours = 10;
  // Recent points: culled when found in fewer than this share of the frames that should have
  // seen them, or when observed by fewer than min_point_observations keyframes two keyframes
  // after their creation.
  double min_found_ratio = 0.25;
  int min_point_observations = 3;
  bool bundle_adjustment = true;
  // Keyframes local BA moves at most (the new one and its strongest covisibles; 0 = all
  // covisibles, as ORB-SLAM2). Bounds its cost where the camera keeps revisiting a place: on the
  // fr2_desk replay (600 frames, --sequential) 10 cut the median local BA from 30 moving
  // keyframes and 14k observations to 10 and 9.5k and its CPU time from 152 to 64 ms, and ATE
  // did not suffer there or on the static_xyz, fr1_xyz and fr3_long_office_household runs.
  int ba_max_local_keyframes = 10;
  int ba_first_pass_iterations = 5;
  int ba_second_pass_iterations = 10;
  // A keyframe is redundant when this share of its close map points is seen by at least
  // redundant_observers other keyframes at the same or a finer scale.
  bool keyframe_culling = true;
  double redundant_ratio = 0.9;
  int redundant_observers = 3;
  // Keyframes waiting for local mapping; tracking blocks when the queue is full.
  int queue_capacity = 8;

  void Check() const;  // throws Error naming the bad key
};

// Every LocalMapping.* key: name, type, bounds and doc, bound to its field (core/option_table.h).
const OptionTable<LocalMappingOptions>& LocalMappingOptionTable();

// Reads LocalMapping.enabled, .triangulationNeighbours, .fusionNeighbours, .minFoundRatio,
// .minPointObservations, .bundleAdjustment, .baMaxLocalKeyFrames, .baFirstPassIterations,
// .baSecondPassIterations,
// .keyFrameCulling, .redundantRatio, .redundantObservers and .queueCapacity.
LocalMappingOptions LoadLocalMappingOptions(const SettingsFile& file);

}  // namespace drvslam
