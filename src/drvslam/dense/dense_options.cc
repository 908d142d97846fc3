#include "drvslam/dense/dense_options.h"

#include <cmath>

#include "drvslam/core/error.h"
#include "drvslam/core/option_check.h"

namespace drvslam {

void DenseMapOptions::Check() const {
  RequireOption(std::isfinite(min_depth) && min_depth >= 0.0, "DenseMap.minDepth", min_depth,
                "must be >= 0");
  RequireOption(std::isfinite(max_depth) && max_depth > min_depth, "DenseMap.maxDepth", max_depth,
                "must be finite and above DenseMap.minDepth");
  RequireOption(std::isfinite(leaf_size) && leaf_size >= 0.001 && leaf_size <= 1.0,
                "DenseMap.leafSize", leaf_size, "must be in [0.001, 1] m");
  RequireOption(
      std::isfinite(object_leaf_size) && object_leaf_size >= 0.001 && object_leaf_size <= leaf_size,
      "DenseMap.objectLeafSize", object_leaf_size, "must be in [0.001 m, DenseMap.leafSize]");
  RequireOption(enhancement_frames >= 0 && enhancement_frames <= 64, "DenseMap.enhancementFrames",
                enhancement_frames, "must be in [0, 64]");
  RequireOption(mask_dilation >= 0 && mask_dilation <= 50, "DenseMap.maskDilation", mask_dilation,
                "must be in [0, 50] pixels");
  RequireOption(min_neighbours >= 0 && min_neighbours <= 26, "DenseMap.minNeighbours",
                min_neighbours, "must be in [0, 26]");
  RequireOption(queue_capacity >= 1, "DenseMap.queueCapacity", queue_capacity,
                "must be at least 1");
  RequireOption(compact_every >= 1, "DenseMap.compactEvery", compact_every, "must be at least 1");
}

DenseMapOptions LoadDenseMapOptions(const SettingsFile& file) {
  DenseMapOptions o;
  o.enabled = file.GetBool("DenseMap.enabled", o.enabled);
  o.min_depth = file.GetDouble("DenseMap.minDepth", o.min_depth);
  o.max_depth = file.GetDouble("DenseMap.maxDepth", o.max_depth);
  o.leaf_size = file.GetDouble("DenseMap.leafSize", o.leaf_size);
  o.object_leaf_size = file.GetDouble("DenseMap.objectLeafSize", o.object_leaf_size);
  o.enhancement_frames = file.GetInt("DenseMap.enhancementFrames", o.enhancement_frames);
  o.remove_dynamic = file.GetBool("DenseMap.removeDynamic", o.remove_dynamic);
  o.remove_all_potentially_moving =
      file.GetBool("DenseMap.removeAllPotentiallyMoving", o.remove_all_potentially_moving);
  o.sticky_moving = file.GetBool("DenseMap.stickyMoving", o.sticky_moving);
  o.mask_dilation = file.GetInt("DenseMap.maskDilation", o.mask_dilation);
  o.min_neighbours = file.GetInt("DenseMap.minNeighbours", o.min_neighbours);
  o.queue_capacity = file.GetInt("DenseMap.queueCapacity", o.queue_capacity);
  o.compact_every = file.GetInt("DenseMap.compactEvery", o.compact_every);
  return CheckedOptions(file.Path(), o);
}

}  // namespace drvslam
