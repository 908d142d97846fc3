// Dense mapping of a synthetic sequence with its ground truth - exact poses, masks and moving
// flags - instead of tracking: the reference the dense map of a SLAM run is compared with, and
// the way to measure the dense module apart from tracking and detection errors.
#pragma once

#include <functional>
#include <string>

#include "drvslam/dense/dense_mapper.h"
#include "drvslam/dense/dense_options.h"

namespace drvslam {

struct GroundTruthMappingOptions {
  DenseMapOptions dense;
  int keyframe_every = 10;     // every n-th frame is a keyframe, the rest ordinary frames
  std::size_t max_frames = 0;  // 0 = all
};

struct GroundTruthMapping {
  DenseCloud cloud;  // world (ground-truth) frame
  DenseMapStats stats;
};

// Reads `dataset` (a `drvslam synth` folder: settings.yaml, groundtruth.txt, masks/,
// instances.txt) and maps it in order. Throws Error naming the file at fault.
GroundTruthMapping MapWithGroundTruth(
    const std::string& dataset, const GroundTruthMappingOptions& options,
    const std::function<void(std::size_t, std::size_t)>& progress = nullptr);

}  // namespace drvslam
