#include "drvslam/tools/truth/evaluation_segmenter_factory.h"

#include "drvslam/core/error.h"
#include "drvslam/semantic/segmenter_factory.h"
#include "drvslam/tools/truth/ground_truth_segmenter.h"

namespace drvslam {

std::unique_ptr<Segmenter> CreateEvaluationSegmenter(const SegmentationOptions& options,
                                                     const std::string& dataset_dir,
                                                     std::vector<std::string> frame_names) {
  if (options.backend != SegmenterBackend::kGroundTruth) {
    return CreateSegmenter(options, dataset_dir, std::move(frame_names));
  }
  options.Check();
  if (dataset_dir.empty()) throw Error("the gt segmenter needs the sequence folder");
  return std::make_unique<GroundTruthSegmenter>(dataset_dir);
}

}  // namespace drvslam
