#include "drvslam/tools/synth/texture.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"

namespace drvslam::synth {
namespace {

// Levels stop once the smaller side would drop below this many texels.
constexpr int kSmallestLevelSide = 4;

}  // namespace

Texture::Texture(const cv::Mat& image) {
  if (image.empty()) throw Error("texture: empty image");
  cv::Mat base;
  if (image.type() == CV_8UC3) {
    cv::cvtColor(image, base, cv::COLOR_BGR2BGRA);
  } else if (image.type() == CV_8UC4) {
    base = image.clone();
    for (int y = 0; y < base.rows && !has_transparency_; ++y) {
      const uint8_t* row = base.ptr<uint8_t>(y);
      for (int x = 0; x < base.cols; ++x) {
        if (row[4 * x + 3] < 128) {
          has_transparency_ = true;
          break;
        }
      }
    }
  } else {
    throw Error("texture: expected an 8-bit BGR or BGRA image");
  }
  levels_.push_back(base);
  while (std::min(levels_.back().cols, levels_.back().rows) >= 2 * kSmallestLevelSide) {
    cv::Mat next;
    cv::pyrDown(levels_.back(), next);
    levels_.push_back(next);
  }
}

bool Texture::Opaque(float u, float v) const {
  const cv::Mat& level = levels_[0];
  float fx = u * level.cols;
  float fy = v * level.rows;
  fx = fx > 0.0f ? fx : 0.0f;
  fy = fy > 0.0f ? fy : 0.0f;
  const int x = std::min(static_cast<int>(std::min(fx, 1e9f)), level.cols - 1);
  const int y = std::min(static_cast<int>(std::min(fy, 1e9f)), level.rows - 1);
  return level.ptr<uint8_t>(y)[4 * x + 3] >= 128;
}

}  // namespace drvslam::synth
