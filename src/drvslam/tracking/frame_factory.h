// FrameFactory: turns an RGB-D image pair into a Frame (grey conversion, ORB extraction,
// undistortion, depth lookup). One per tracking thread: the extractor keeps per-image buffers.
#pragma once

#include <memory>
#include <opencv2/core.hpp>

#include "drvslam/core/settings.h"
#include "drvslam/feature/orb_extractor.h"
#include "drvslam/map/frame.h"

namespace drvslam {

class FrameFactory {
 public:
  explicit FrameFactory(const Settings& settings);

  // bgr: CV_8UC3 (or CV_8UC1 grey); depth: CV_32FC1 metres, same size. skip_mask: empty or
  // CV_8UC1 (nonzero = extract no features there); target_features <= 0: the configured count.
  // Throws Error when the sizes disagree with the camera settings.
  Frame Build(double timestamp, const cv::Mat& bgr, const cv::Mat& depth,
              const cv::Mat& skip_mask = cv::Mat(), int target_features = 0);

  const std::shared_ptr<const SensorGeometry>& Geometry() const { return geometry_; }

 private:
  std::shared_ptr<const SensorGeometry> geometry_;
  OrbExtractor extractor_;
  long next_frame_id_ = 0;
  cv::Mat gray_;
};

}  // namespace drvslam
