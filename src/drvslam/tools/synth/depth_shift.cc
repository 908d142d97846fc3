#include "drvslam/tools/synth/depth_shift.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core/utility.hpp>

namespace drvslam::synth {

void ShiftDepth(double dx, double dy, RenderBuffers* buffers) {
  const cv::Mat& depth = buffers->depth;
  const cv::Mat& incidence = buffers->incidence;
  const int width = depth.cols, height = depth.rows;
  cv::Mat shifted_depth(height, width, CV_32FC1);
  cv::Mat shifted_incidence(height, width, CV_32FC1);
  // Whole-pixel shift for edges, rounded half away from zero.
  const int shift_x = static_cast<int>(std::lround(dx));
  const int shift_y = static_cast<int>(std::lround(dy));
  const auto inside = [width, height](int x, int y) {
    return x >= 0 && y >= 0 && x < width && y < height;
  };
  cv::parallel_for_(cv::Range(0, height), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      float* depth_row = shifted_depth.ptr<float>(y);
      float* incidence_row = shifted_incidence.ptr<float>(y);
      const double source_y = y - dy;
      const int y0 = static_cast<int>(std::floor(source_y));
      const int nearest_y = y - shift_y;
      const float fy = static_cast<float>(source_y - y0);
      for (int x = 0; x < width; ++x) {
        const double source_x = x - dx;
        const int nearest_x = x - shift_x;
        if (!inside(nearest_x, nearest_y)) {
          depth_row[x] = incidence_row[x] = 0.0f;
          continue;
        }
        float z = depth.ptr<float>(nearest_y)[nearest_x];
        incidence_row[x] = incidence.ptr<float>(nearest_y)[nearest_x];
        const int x0 = static_cast<int>(std::floor(source_x));
        const float fx = static_cast<float>(source_x - x0);
        if ((fx != 0.0f || fy != 0.0f) && inside(x0, y0) && inside(x0 + 1, y0 + 1)) {
          const float a = depth.ptr<float>(y0)[x0], b = depth.ptr<float>(y0)[x0 + 1];
          const float c = depth.ptr<float>(y0 + 1)[x0], d = depth.ptr<float>(y0 + 1)[x0 + 1];
          const float lo = std::min({a, b, c, d}), hi = std::max({a, b, c, d});
          if (lo > 0.0f && hi - lo <= static_cast<float>(kDepthContinuity) * lo) {
            const float top = a + fx * (b - a), bottom = c + fx * (d - c);
            z = top + fy * (bottom - top);
          }
        }
        depth_row[x] = z;
      }
    }
  });
  buffers->depth = shifted_depth;
  buffers->incidence = shifted_incidence;
}

}  // namespace drvslam::synth
