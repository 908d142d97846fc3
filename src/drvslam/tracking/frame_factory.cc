#include "drvslam/tracking/frame_factory.h"

#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"

namespace drvslam {

FrameFactory::FrameFactory(const Settings& settings)
    : geometry_(std::make_shared<SensorGeometry>(
          settings.camera, ScalePyramid(settings.orb.n_levels, settings.orb.scale_factor),
          settings.depth.CloseDepth(settings.camera))),
      extractor_(settings.orb) {}

Frame FrameFactory::Build(double timestamp, const cv::Mat& bgr, const cv::Mat& depth,
                          const cv::Mat& skip_mask, int target_features) {
  const CameraOptions& camera = geometry_->camera.Options();
  if (bgr.cols != camera.width || bgr.rows != camera.height) {
    throw Error("image of " + std::to_string(bgr.cols) + "x" + std::to_string(bgr.rows) +
                " does not match Camera.width/height " + std::to_string(camera.width) + "x" +
                std::to_string(camera.height));
  }
  if (!depth.empty() && (depth.size() != bgr.size() || depth.type() != CV_32FC1)) {
    throw Error("depth image must be CV_32FC1 metres of the colour image's size");
  }
  if (bgr.type() == CV_8UC3) {
    cv::cvtColor(bgr, gray_, cv::COLOR_BGR2GRAY);
  } else if (bgr.type() == CV_8UC1) {
    gray_ = bgr;
  } else {
    throw Error("colour image must be 8-bit BGR or grey");
  }
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  extractor_.Extract(gray_, skip_mask, target_features, &keypoints, &descriptors);
  auto features = std::make_shared<const FrameFeatures>(geometry_, std::move(keypoints),
                                                        std::move(descriptors), depth);
  return Frame(next_frame_id_++, timestamp, std::move(features));
}

}  // namespace drvslam
