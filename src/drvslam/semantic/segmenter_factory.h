// CreateSegmenter: builds the backend a settings file (or the --segmenter option) names, so the
// system and the CLI never construct backends themselves.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "drvslam/semantic/segmentation_options.h"
#include "drvslam/semantic/segmenter.h"

namespace drvslam {

// yolo: options.model; masks: options.masks_dir (relative paths under `dataset_dir`), with
// `frame_names` (each frame's colour image file) when known; none and auto: nullptr. Throws
// drvslam::Error from the backend's constructor, and for gt: ground-truth masks are an
// evaluation backend (tools/truth/evaluation_segmenter_factory.h builds it).
std::unique_ptr<Segmenter> CreateSegmenter(const SegmentationOptions& options,
                                           const std::string& dataset_dir = "",
                                           std::vector<std::string> frame_names = {});

}  // namespace drvslam
