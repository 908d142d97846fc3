// ChoosePlace: hypotheses are grouped into places by pose, a place's support is the keypoints
// any of its hypotheses explains, and a place is taken only when the runner-up explains clearly
// fewer keypoints.
#include "drvslam/loop/place_hypotheses.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "drvslam/map/map_point.h"

namespace drvslam {
namespace {

constexpr std::size_t kKeypoints = 200;

// A hypothesis at camera centre x (metres) whose inliers are keypoints [first, last).
PlaceHypothesis At(double x, std::size_t first, std::size_t last) {
  static const auto point = std::make_shared<MapPoint>(0, Eigen::Vector3d(0, 0, 2), nullptr);
  PlaceHypothesis hypothesis;
  hypothesis.T_cw = SE3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-x, 0, 0));
  hypothesis.matches.assign(kKeypoints, nullptr);
  for (std::size_t i = first; i < last; ++i) hypothesis.matches[i] = point;
  hypothesis.inliers = static_cast<int>(last - first);
  return hypothesis;
}

TEST(PlaceHypothesesTest, TwoPlacesExplainingTheFrameEquallyAreAmbiguous) {
  // A period of 1.2 m: both explain all 100 keypoints.
  const PlaceChoice choice = ChoosePlace({At(0.0, 0, 100), At(1.2, 0, 100)}, 50);
  EXPECT_TRUE(choice.ambiguous);
  EXPECT_EQ(choice.best, -1);
  EXPECT_EQ(choice.places, 2);
  EXPECT_EQ(choice.best_support, 100);
  EXPECT_EQ(choice.runner_up_support, 100);
}

TEST(PlaceHypothesesTest, HypothesesOfOnePlaceAddTheirKeypoints) {
  // Two keyframes of the true place explain the two halves; the shifted place only one.
  const PlaceChoice choice =
      ChoosePlace({At(1.2, 100, 200), At(0.0, 0, 100), At(0.01, 100, 200)}, 50);
  EXPECT_FALSE(choice.ambiguous);
  EXPECT_EQ(choice.places, 2);
  EXPECT_EQ(choice.best_support, 200);
  EXPECT_EQ(choice.runner_up_support, 100);
  EXPECT_EQ(choice.best, 1);  // the first of the true place's hypotheses with the most inliers
}

TEST(PlaceHypothesesTest, TheRatioDecides) {
  // 85 of 100: refused; 70 of 100: taken.
  EXPECT_TRUE(ChoosePlace({At(0.0, 0, 100), At(0.5, 0, 85)}, 50).ambiguous);
  const PlaceChoice clear = ChoosePlace({At(0.0, 0, 100), At(0.5, 0, 70)}, 50);
  EXPECT_FALSE(clear.ambiguous);
  EXPECT_EQ(clear.best, 0);
  // A pose 3 cm and no degree away is the same place, not a rival.
  const PlaceChoice same = ChoosePlace({At(0.0, 0, 100), At(0.03, 0, 100)}, 50);
  EXPECT_EQ(same.places, 1);
  EXPECT_EQ(same.best, 0);
}

TEST(PlaceHypothesesTest, TooFewInliersOrNoHypothesisTakesNothing) {
  const PlaceChoice few = ChoosePlace({At(0.0, 0, 40)}, 50);
  EXPECT_FALSE(few.ambiguous);
  EXPECT_EQ(few.best, -1);
  EXPECT_EQ(few.best_support, 40);
  const PlaceChoice none = ChoosePlace({}, 50);
  EXPECT_EQ(none.best, -1);
  EXPECT_EQ(none.places, 0);
}

}  // namespace
}  // namespace drvslam
