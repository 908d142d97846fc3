// LevelSkipMask: answers "is this pyramid-level position inside the caller's skip mask?" by
// looking the point up at its level-0 position, so one full-resolution mask serves every level.
#pragma once

#include <algorithm>
#include <opencv2/core.hpp>

namespace drvslam {

class LevelSkipMask {
 public:
  // mask: empty (nothing skipped) or CV_8UC1 at level-0 size, nonzero = skip. scale: the level's
  // scale factor (level-0 pixels per level pixel).
  LevelSkipMask(const cv::Mat& mask, float scale) : mask_(mask), scale_(scale) {}

  bool Empty() const { return mask_.empty(); }

  bool Skips(float x, float y) const {
    if (mask_.empty()) return false;
    const int u = std::clamp(cvRound(x * scale_), 0, mask_.cols - 1);
    const int v = std::clamp(cvRound(y * scale_), 0, mask_.rows - 1);
    return mask_.ptr<uint8_t>(v)[u] != 0;
  }

  // True when every level-0 pixel that a level position in `level_rect` can map to is masked,
  // i.e. no corner found there could survive.
  bool Covers(const cv::Rect& level_rect) const {
    if (mask_.empty() || level_rect.empty()) return false;
    const int u0 = std::clamp(cvRound(level_rect.x * scale_), 0, mask_.cols - 1);
    const int v0 = std::clamp(cvRound(level_rect.y * scale_), 0, mask_.rows - 1);
    const int u1 =
        std::clamp(cvRound((level_rect.x + level_rect.width - 1) * scale_), 0, mask_.cols - 1);
    const int v1 =
        std::clamp(cvRound((level_rect.y + level_rect.height - 1) * scale_), 0, mask_.rows - 1);
    const cv::Rect roi(u0, v0, u1 - u0 + 1, v1 - v0 + 1);
    return cv::countNonZero(mask_(roi)) == roi.area();
  }

 private:
  cv::Mat mask_;  // a header sharing the caller's pixels
  float scale_;
};

}  // namespace drvslam
