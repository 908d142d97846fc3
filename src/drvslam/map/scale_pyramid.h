// ScalePyramid: the per-level scale factors and measurement uncertainties of an ORB pyramid,
// shared by frames, keyframes, map points and the matchers (which predict a point's level from
// its distance).
#pragma once

#include <cmath>
#include <vector>

namespace drvslam {

struct ScalePyramid {
  int levels = 8;
  double scale_factor = 1.2;
  double log_scale_factor = std::log(1.2);
  std::vector<double> scale;       // scale[i] = scale_factor^i
  std::vector<double> inv_scale;   // 1 / scale[i]
  std::vector<double> sigma2;      // scale[i]^2: variance of a keypoint position at level i
  std::vector<double> inv_sigma2;  // 1 / sigma2[i]

  ScalePyramid() : ScalePyramid(8, 1.2) {}
  ScalePyramid(int n_levels, double factor) : levels(n_levels), scale_factor(factor) {
    log_scale_factor = std::log(factor);
    double s = 1.0;
    for (int i = 0; i < n_levels; ++i) {
      scale.push_back(s);
      inv_scale.push_back(1.0 / s);
      sigma2.push_back(s * s);
      inv_sigma2.push_back(1.0 / (s * s));
      s *= factor;
    }
  }

  // Level at which a point at `distance` is expected, given the distance range where it was
  // created at level 0 (max_distance): ORB-SLAM's scale prediction.
  int PredictLevel(double max_distance, double distance) const {
    const double ratio = max_distance / distance;
    int level = static_cast<int>(std::ceil(std::log(ratio) / log_scale_factor));
    if (level < 0) level = 0;
    if (level >= levels) level = levels - 1;
    return level;
  }
};

}  // namespace drvslam
