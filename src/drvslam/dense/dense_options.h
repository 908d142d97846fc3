// DenseMapOptions: the DenseMap.* settings of the dense mapping thread (DESIGN.md): which depth
// is trusted, which pixels are left out, the coarse leaf of the global map and the fine leaf
// and frame count of the targeted enhancement of static key objects.
#pragma once

#include "drvslam/core/settings_file.h"

namespace drvslam {

struct DenseMapOptions {
  bool enabled = true;
  // Depth outside [min_depth, max_depth] (metres) is left out: Kinect-class sensors are noisy
  // beyond a few metres and invalid very close.
  double min_depth = 0.2;
  double max_depth = 4.0;
  // Global downsampling: one point per world voxel of this edge (metres).
  double leaf_size = 0.03;
  // Static key objects (books, laptops, keyboards, ...): one point per voxel of this edge.
  double object_leaf_size = 0.005;
  // Ordinary frames nearest in time to a keyframe whose key-object pixels are added too: the
  // ring buffer keeps this many of the latest frames.
  int enhancement_frames = 4;
  // Leave out the pixels of objects judged moving; off integrates everything (for comparison).
  bool remove_dynamic = true;
  // Leave out every potentially-moving object (people, animals, vehicles), moving or not.
  bool remove_all_potentially_moving = false;
  // An object judged moving once stays out (its earlier still points are dropped too): a
  // person who stops walking for a moment leaves no ghost.
  bool sticky_moving = true;
  // Masks of left-out objects grow by this many pixels: depth at mask borders belongs to
  // either side.
  int mask_dilation = 4;
  // Assembly drops points with fewer occupied neighbouring voxels (of the 26) than this;
  // 0 keeps all.
  int min_neighbours = 1;
  // Keyframes waiting for the dense thread before tracking blocks.
  int queue_capacity = 16;
  // The stored map is re-keyed with the current keyframe poses after this many keyframes, so
  // voxels that pose corrections made coincide merge and memory follows the explored volume.
  int compact_every = 10;

  // Throws Error naming the DenseMap.* key of a bad value.
  void Check() const;
};

// Reads DenseMap.* (defaults for absent keys) and checks them; errors name the file and key.
DenseMapOptions LoadDenseMapOptions(const SettingsFile& file);

}  // namespace drvslam
