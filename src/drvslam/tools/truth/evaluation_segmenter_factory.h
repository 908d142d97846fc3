// CreateEvaluationSegmenter: CreateSegmenter plus the backends only an evaluation has. The
// runtime factory builds what runs on a robot (yolo, masks, none); this one adds gt, the exact
// masks of a synthetic sequence, which needs the synth file formats the runtime does not link.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "drvslam/semantic/segmentation_options.h"
#include "drvslam/semantic/segmenter.h"

namespace drvslam {

// gt: the synthetic sequence in `dataset_dir` (Error when it is empty or holds no
// instances.txt); every other backend as CreateSegmenter builds it.
std::unique_ptr<Segmenter> CreateEvaluationSegmenter(const SegmentationOptions& options,
                                                     const std::string& dataset_dir = "",
                                                     std::vector<std::string> frame_names = {});

}  // namespace drvslam
