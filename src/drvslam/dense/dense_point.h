// DensePoint: one point of the dense map - position, colour, class label and the track of the
// potentially-moving object it lies on - the unit every dense-mapping step passes around.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace drvslam {

struct DensePoint {
  Eigen::Vector3f position = Eigen::Vector3f::Zero();  // metres, in the frame its cloud names
  uint8_t r = 0, g = 0, b = 0;
  int16_t label = -1;  // segmenter class id; -1 = unlabelled background
  int32_t track = -1;  // object ID of a still potentially-moving object; -1 = none
};

using DenseCloud = std::vector<DensePoint>;

// The point a pixel sees: its camera ray (x/z, y/z) at depth z, with the pixel's colour (BGR),
// label and track.
inline DensePoint PixelPoint(const cv::Vec2f& ray, float z, const cv::Vec3b& bgr, int16_t label,
                             int32_t track) {
  DensePoint p;
  p.position = {ray[0] * z, ray[1] * z, z};
  p.b = bgr[0];
  p.g = bgr[1];
  p.r = bgr[2];
  p.label = label;
  p.track = track;
  return p;
}

}  // namespace drvslam
