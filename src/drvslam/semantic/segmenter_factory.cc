#include "drvslam/semantic/segmenter_factory.h"

#include <filesystem>

#include "drvslam/core/error.h"
#include "drvslam/semantic/mask_file_segmenter.h"
#include "drvslam/semantic/yolo_segmenter.h"

namespace drvslam {

std::unique_ptr<Segmenter> CreateSegmenter(const SegmentationOptions& options,
                                           const std::string& dataset_dir,
                                           std::vector<std::string> frame_names) {
  options.Check();
  switch (options.backend) {
    case SegmenterBackend::kYolo:
      return std::make_unique<YoloSegmenter>(options);
    case SegmenterBackend::kMaskFiles: {
      std::filesystem::path dir(options.masks_dir);
      if (dir.is_relative() && !dataset_dir.empty()) dir = std::filesystem::path(dataset_dir) / dir;
      return std::make_unique<MaskFileSegmenter>(dir.string(), options, std::move(frame_names));
    }
    case SegmenterBackend::kGroundTruth:
      // Ground-truth masks exist only for synthetic sequences: an evaluation oracle, built by
      // the tools library so that the runtime never links the renderer's file formats.
      throw Error(
          "Segmentation.backend gt: the ground-truth segmenter is an evaluation tool, not part "
          "of the runtime library; build it with CreateEvaluationSegmenter (drvslam_tools)");
    case SegmenterBackend::kNone:
    case SegmenterBackend::kAuto:  // no dataset to take a default from: no segmenter
      return nullptr;
  }
  return nullptr;
}

}  // namespace drvslam
