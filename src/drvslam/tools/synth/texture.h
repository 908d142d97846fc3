// Texture: one surface image with its mip pyramid, as the rasterizer samples it. Trilinear
// filtering (bilinear within the two nearest pyramid levels) keeps far and grazing surfaces free
// of aliasing, so the same texture detail gives the same features from frame to frame.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace drvslam::synth {

class Texture {
 public:
  // `image` is CV_8UC3 (BGR) or CV_8UC4 (BGRA; alpha < 128 is transparent). Throws Error when
  // it is empty or of another type.
  explicit Texture(const cv::Mat& image);

  int Width() const { return levels_[0].cols; }
  int Height() const { return levels_[0].rows; }
  int LevelCount() const { return static_cast<int>(levels_.size()); }
  const cv::Mat& Level(int level) const { return levels_[level]; }  // CV_8UC4
  // True when some texel is transparent (the rasterizer then alpha-tests it).
  bool HasTransparency() const { return has_transparency_; }

  // Colour (B, G, R in 0..255) at normalized coordinates (u, v) in [0, 1] (clamped at the
  // border); `lod` is log2 of level-0 texels per screen pixel. Inline: the rasterizer calls it
  // once per pixel.
  void Sample(float u, float v, float lod, float bgr[3]) const {
    bgr[0] = bgr[1] = bgr[2] = 0.0f;
    const int last = static_cast<int>(levels_.size()) - 1;
    if (!(lod > 0.0f)) {  // also catches NaN
      SampleBilinear(levels_[0], u, v, 1.0f, bgr);
      return;
    }
    if (lod >= static_cast<float>(last)) {
      SampleBilinear(levels_[last], u, v, 1.0f, bgr);
      return;
    }
    const int level = static_cast<int>(lod);
    const float fraction = lod - static_cast<float>(level);
    // Close to one level the other one's share is invisible; skipping it saves a quarter of
    // the lookups.
    if (fraction < 0.05f) {
      SampleBilinear(levels_[level], u, v, 1.0f, bgr);
    } else if (fraction > 0.95f) {
      SampleBilinear(levels_[level + 1], u, v, 1.0f, bgr);
    } else {
      SampleBilinear(levels_[level], u, v, 1.0f - fraction, bgr);
      SampleBilinear(levels_[level + 1], u, v, fraction, bgr);
    }
  }
  // Whether the nearest level-0 texel is opaque (alpha >= 128).
  bool Opaque(float u, float v) const;

 private:
  // Adds weight * the bilinear colour at (u, v) of one level to bgr.
  static void SampleBilinear(const cv::Mat& level, float u, float v, float weight, float bgr[3]) {
    // Written so that a NaN coordinate clamps to 0 instead of reaching the integer conversion.
    float x = u * level.cols - 0.5f;
    float y = v * level.rows - 0.5f;
    x = x > 0.0f ? x : 0.0f;
    y = y > 0.0f ? y : 0.0f;
    x = x < level.cols - 1.0f ? x : level.cols - 1.0f;
    y = y < level.rows - 1.0f ? y : level.rows - 1.0f;
    const int x0 = static_cast<int>(x);
    const int y0 = static_cast<int>(y);
    const int x1 = x0 + 1 < level.cols ? x0 + 1 : x0;
    const int y1 = y0 + 1 < level.rows ? y0 + 1 : y0;
    const float fx = x - x0;
    const float fy = y - y0;
    const uint8_t* row0 = level.ptr<uint8_t>(y0);
    const uint8_t* row1 = level.ptr<uint8_t>(y1);
    const uint8_t* a = row0 + 4 * x0;
    const uint8_t* b = row0 + 4 * x1;
    const uint8_t* c = row1 + 4 * x0;
    const uint8_t* d = row1 + 4 * x1;
    const float wa = (1.0f - fx) * (1.0f - fy) * weight;
    const float wb = fx * (1.0f - fy) * weight;
    const float wc = (1.0f - fx) * fy * weight;
    const float wd = fx * fy * weight;
    for (int k = 0; k < 3; ++k) bgr[k] += wa * a[k] + wb * b[k] + wc * c[k] + wd * d[k];
  }

  std::vector<cv::Mat> levels_;
  bool has_transparency_ = false;
};

}  // namespace drvslam::synth
