// BoW matching (match/bow_matcher.h) on views of a photographed plane related by a known
// homography: nine matches in ten must land where the homography says (the rest are
// repeated texture, which PnP RANSAC later rejects).
#include "drvslam/match/bow_matcher.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "drvslam/map/map_point.h"
#include "plane_views.h"
#include "test_support/missing_data.h"

namespace drvslam {
namespace {

class BowMatcherTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!scene_.LoadVocabulary()) DRVSLAM_MISSING_TEST_DATA() << "no default vocabulary was built";
    photo_ = test::LoadPhoto("graf1.png");
    if (photo_.empty())
      DRVSLAM_MISSING_TEST_DATA() << "graf1.png missing in " << DRVSLAM_OPENCV_DATA_DIR;
    keyframe_ = scene_.MakeKeyFrame(photo_, SE3::Identity());
    ASSERT_TRUE(keyframe_);
  }

  // Whether keyframe keypoint i maps (by H) within 3 pixels x its pyramid scale of keypoint j
  // of `features`.
  bool Consistent(const cv::Matx33d& H, std::size_t i, const FrameFeatures& features,
                  std::size_t j) const {
    const cv::KeyPoint& a = keyframe_->Features().KeypointsUn()[i];
    const cv::KeyPoint& b = features.KeypointsUn()[j];
    const cv::Point2d predicted = test::MapPixel(H, a.pt.x, a.pt.y);
    const double tolerance = 3.0 * features.Geometry().pyramid.scale[b.octave];
    return std::hypot(predicted.x - b.pt.x, predicted.y - b.pt.y) < tolerance;
  }

  test::PlaneScene scene_;
  cv::Mat photo_;
  std::shared_ptr<KeyFrame> keyframe_;
  const SE3 view_ = test::ViewPose(0.05, -0.1, 0.15, 0.1, -0.05, 0.2);
};

TEST_F(BowMatcherTest, KeyFrameToFrameMatchesFollowTheHomography) {
  Frame frame = scene_.MakeFrame(photo_, view_);
  scene_.ComputeBow(frame);
  std::vector<std::shared_ptr<MapPoint>> matches;
  const int count = SearchByBow(*keyframe_, frame, BowMatchOptions(), &matches);
  ASSERT_EQ(matches.size(), frame.Size());
  EXPECT_GE(count, 100);
  const cv::Matx33d H = test::PlaneHomography(scene_.settings.camera, view_);
  int non_null = 0, consistent = 0;
  for (std::size_t j = 0; j < matches.size(); ++j) {
    if (!matches[j]) continue;
    ++non_null;
    const int i = matches[j]->IndexIn(keyframe_->Id());
    ASSERT_GE(i, 0);
    if (Consistent(H, static_cast<std::size_t>(i), frame.Features(), j)) ++consistent;
  }
  EXPECT_EQ(non_null, count);
  EXPECT_GE(consistent, 0.9 * count) << consistent << " of " << count;
}

TEST_F(BowMatcherTest, KeyFrameToKeyFrameMatchesFollowTheHomography) {
  const auto other = scene_.MakeKeyFrame(photo_, view_);
  ASSERT_TRUE(other);
  std::vector<std::shared_ptr<MapPoint>> matches;
  const int count = SearchByBow(*keyframe_, *other, BowMatchOptions(), &matches);
  ASSERT_EQ(matches.size(), keyframe_->Features().Size());
  EXPECT_GE(count, 100);
  const cv::Matx33d H = test::PlaneHomography(scene_.settings.camera, view_);
  int consistent = 0;
  std::vector<int> used(other->Features().Size(), 0);
  for (std::size_t i = 0; i < matches.size(); ++i) {
    if (!matches[i]) continue;
    const int j = matches[i]->IndexIn(other->Id());
    ASSERT_GE(j, 0);
    ++used[j];
    if (Consistent(H, i, other->Features(), static_cast<std::size_t>(j))) ++consistent;
  }
  EXPECT_GE(consistent, 0.9 * count) << consistent << " of " << count;
  // Each keypoint of the second keyframe is taken once at most.
  for (const int uses : used) EXPECT_LE(uses, 1);
}

TEST_F(BowMatcherTest, StricterOptionsGiveFewerMatchesAndNoBowGivesNone) {
  Frame frame = scene_.MakeFrame(photo_, view_);
  std::vector<std::shared_ptr<MapPoint>> matches;
  EXPECT_EQ(SearchByBow(*keyframe_, frame, BowMatchOptions(), &matches), 0);  // frame has no BoW
  EXPECT_EQ(matches.size(), frame.Size());
  scene_.ComputeBow(frame);
  const int loose = SearchByBow(*keyframe_, frame, BowMatchOptions(), &matches);
  BowMatchOptions strict;
  strict.max_distance = 30;
  strict.nn_ratio = 0.6;
  const int tight = SearchByBow(*keyframe_, frame, strict, &matches);
  EXPECT_GT(tight, 0);
  EXPECT_LT(tight, loose);
}

}  // namespace
}  // namespace drvslam
