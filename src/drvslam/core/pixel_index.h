// PixelIndex: the pixel a float image point (an optical-flow track, a keypoint) falls in, as
// static_cast<int> truncates it, without the cast's undefined behaviour when the point is NaN,
// infinite or beyond int's range (tracks lost by the flow can carry such values).
#pragma once

#include <cmath>
#include <opencv2/core.hpp>

namespace drvslam {

// False, leaving `pixel` untouched, when a coordinate is not finite or does not fit an int;
// else the truncated coordinates, exactly as static_cast<int> gives them.
inline bool PixelIndex(const cv::Point2f& p, cv::Point* pixel) {
  // Inside (-2^31, 2^31) the truncated value fits an int, so the cast is defined.
  constexpr float kLimit = 2147483648.0f;
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) return false;
  if (!(p.x > -kLimit && p.x < kLimit && p.y > -kLimit && p.y < kLimit)) return false;
  *pixel = cv::Point(static_cast<int>(p.x), static_cast<int>(p.y));
  return true;
}

}  // namespace drvslam
