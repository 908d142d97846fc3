#include "drvslam/dynamic/depth_mask_completion.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

constexpr int kMinDepthPixels = 20;

bool ValidDepth(float z) { return z > 0.0f && std::isfinite(z); }

// Lower median of the valid depths under the mask inside `roi`; NaN when too few.
float MedianMaskDepth(const cv::Mat& mask, const cv::Mat& depth, const cv::Rect& roi) {
  std::vector<float> values;
  values.reserve(static_cast<std::size_t>(roi.area()));
  for (int y = roi.y; y < roi.y + roi.height; ++y) {
    const uint8_t* m = mask.ptr<uint8_t>(y);
    const float* d = depth.ptr<float>(y);
    for (int x = roi.x; x < roi.x + roi.width; ++x) {
      if (m[x] != 0 && ValidDepth(d[x])) values.push_back(d[x]);
    }
  }
  if (static_cast<int>(values.size()) < kMinDepthPixels) return std::nanf("");
  const auto middle = values.begin() + (values.size() - 1) / 2;
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

int CompleteMaskWithDepth(Instance& instance, const cv::Mat& depth,
                          const MaskCompletionOptions& options) {
  if (depth.type() != CV_32FC1 || instance.mask.type() != CV_8UC1 ||
      instance.mask.size() != depth.size()) {
    throw Error("CompleteMaskWithDepth: the mask must be CV_8UC1 of the depth's size (CV_32FC1)");
  }
  const cv::Rect whole(0, 0, depth.cols, depth.rows);
  const cv::Rect box = instance.box & whole;
  if (box.area() <= 0) return 0;
  const float median = MedianMaskDepth(instance.mask, depth, box);
  if (std::isnan(median)) return 0;
  const int grow_x = static_cast<int>(std::lround(options.margin * box.width));
  const int grow_y = static_cast<int>(std::lround(options.margin * box.height));
  const cv::Rect roi =
      cv::Rect(box.x - grow_x, box.y - grow_y, box.width + 2 * grow_x, box.height + 2 * grow_y) &
      whole;
  const float band = static_cast<float>(options.depth_band);
  const float step = static_cast<float>(options.depth_step);
  auto eligible = [&](int x, int y) {
    const float z = depth.at<float>(y, x);
    return ValidDepth(z) && std::abs(z - median) <= band;
  };

  // Breadth-first over the ROI from the mask's edge: the pixels in the band with a neighbour
  // outside the mask. An interior pixel's neighbours are all in the mask already, so starting
  // from every mask pixel reaches the same pixels (what is reached does not depend on the order)
  // and only costs a pass over the whole body.
  cv::Mat& mask = instance.mask;
  std::vector<cv::Point> frontier;
  const auto outside_mask = [&](int x, int y) {
    return roi.contains(cv::Point(x, y)) && mask.at<uint8_t>(y, x) == 0;
  };
  for (int y = roi.y; y < roi.y + roi.height; ++y) {
    const uint8_t* m = mask.ptr<uint8_t>(y);
    for (int x = roi.x; x < roi.x + roi.width; ++x) {
      if (m[x] == 0) continue;
      const bool on_edge = outside_mask(x - 1, y) || outside_mask(x + 1, y) ||
                           outside_mask(x, y - 1) || outside_mask(x, y + 1);
      if (on_edge && eligible(x, y)) frontier.emplace_back(x, y);
    }
  }
  static constexpr int kDx[4] = {1, -1, 0, 0};
  static constexpr int kDy[4] = {0, 0, 1, -1};
  int added = 0;
  int left = box.x, top = box.y, right = box.x + box.width, bottom = box.y + box.height;
  for (std::size_t head = 0; head < frontier.size(); ++head) {
    const cv::Point p = frontier[head];
    const float z = depth.at<float>(p);
    for (int k = 0; k < 4; ++k) {
      const cv::Point q(p.x + kDx[k], p.y + kDy[k]);
      if (!roi.contains(q) || mask.at<uint8_t>(q) != 0 || !eligible(q.x, q.y)) continue;
      if (std::abs(depth.at<float>(q) - z) >= step) continue;
      mask.at<uint8_t>(q) = 255;
      ++added;
      left = std::min(left, q.x);
      top = std::min(top, q.y);
      right = std::max(right, q.x + 1);
      bottom = std::max(bottom, q.y + 1);
      frontier.push_back(q);
    }
  }
  instance.box = cv::Rect(left, top, right - left, bottom - top);
  return added;
}

}  // namespace drvslam
