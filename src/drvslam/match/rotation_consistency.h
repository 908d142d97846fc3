// RotationConsistency: ORB-SLAM's orientation check. Matches vote with the change of keypoint
// angle into a 30-bin histogram; only matches in the three most populated bins survive, since a
// rigid scene rotates every feature by about the same angle.
#pragma once

#include <array>
#include <vector>

namespace drvslam {

class RotationConsistency {
 public:
  static constexpr int kBins = 30;

  // angle_change in degrees (any range); `match` is an opaque id returned by Rejected().
  void Add(float angle_change, int match);
  // Matches outside the dominant bins. A second or third bin is dominant only with at least a
  // tenth of the first bin's votes.
  std::vector<int> Rejected() const;

 private:
  std::array<std::vector<int>, kBins> bins_;
};

}  // namespace drvslam
