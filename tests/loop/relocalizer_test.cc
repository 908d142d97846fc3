// Relocalizer: a frame seen from an unknown pose is placed against a small map (keyframes of
// several photographed planes) at its true pose; a view of a place not in the map is refused.
#include "drvslam/loop/relocalizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/map/map_point.h"
#include "plane_views.h"
#include "test_support/missing_data.h"

namespace drvslam {
namespace {

class RelocalizerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!scene_.LoadVocabulary()) DRVSLAM_MISSING_TEST_DATA() << "no default vocabulary was built";
    for (const std::string name : {"graf1.png", "home.jpg", "fruits.jpg", "baboon.jpg"}) {
      const cv::Mat photo = test::LoadPhoto(name);
      if (photo.empty())
        DRVSLAM_MISSING_TEST_DATA() << name << " missing in " << DRVSLAM_OPENCV_DATA_DIR;
      photos_.push_back(photo);
    }
    // The map: each place seen by one keyframe. Photo 3 (baboon) stays out of it.
    for (std::size_t k = 0; k < 3; ++k) {
      keyframes_.push_back(scene_.MakeKeyFrame(photos_[k], SE3::Identity()));
      ASSERT_TRUE(keyframes_.back());
      database_.Add(keyframes_.back());
    }
  }

  test::PlaneScene scene_;
  std::vector<cv::Mat> photos_;
  std::vector<std::shared_ptr<KeyFrame>> keyframes_;
  KeyFrameDatabase database_;
};

TEST_F(RelocalizerTest, FindsTheTruePoseOfAChangedView) {
  Relocalizer relocalizer(scene_.vocabulary, database_, RelocalizationOptions());
  for (std::size_t place = 0; place < 3; ++place) {
    const SE3 truth = test::ViewPose(0.04, -0.09, 0.12, 0.15, -0.08, 0.3);
    Frame frame = scene_.MakeFrame(photos_[place], truth);
    ASSERT_TRUE(relocalizer.Relocalize(frame)) << "place " << place;
    EXPECT_EQ(frame.reference_keyframe, keyframes_[place]);
    EXPECT_EQ(relocalizer.LastReport().keyframe_id, keyframes_[place]->Id());
    EXPECT_GE(relocalizer.LastReport().inliers, 50);
    int matched = 0;
    for (const auto& point : frame.map_points) matched += point ? 1 : 0;
    EXPECT_EQ(matched, relocalizer.LastReport().inliers);
    const SE3 error = frame.Pose() * truth.Inverse();
    EXPECT_LT(error.Translation().norm(), 0.01) << "place " << place;
    const double angle = Eigen::AngleAxisd(error.Rotation()).angle();
    EXPECT_LT(angle, 0.5 * M_PI / 180.0) << "place " << place;
  }
  EXPECT_EQ(relocalizer.Attempts(), 3);
}

TEST_F(RelocalizerTest, RefusesAPlaceNotInTheMap) {
  Relocalizer relocalizer(scene_.vocabulary, database_, RelocalizationOptions());
  Frame frame = scene_.MakeFrame(photos_[3], test::ViewPose(0.02, 0.03, 0.05, 0.05, 0.0, 0.1));
  EXPECT_FALSE(relocalizer.Relocalize(frame));
  EXPECT_TRUE(frame.has_bow);
  for (const auto& point : frame.map_points) EXPECT_FALSE(point);
  EXPECT_EQ(relocalizer.LastReport().keyframe_id, -1);
}

TEST_F(RelocalizerTest, ResetForgetsTheMap) {
  Relocalizer relocalizer(scene_.vocabulary, database_, RelocalizationOptions());
  relocalizer.Reset();
  EXPECT_EQ(database_.Size(), 0u);
  Frame frame = scene_.MakeFrame(photos_[0], SE3::Identity());
  EXPECT_FALSE(relocalizer.Relocalize(frame));
  EXPECT_EQ(relocalizer.LastReport().candidates, 0);
}

TEST_F(RelocalizerTest, RejectsBadOptionsAndAnEmptyVocabulary) {
  RelocalizationOptions options;
  options.min_inliers = 5;  // below min_pnp_inliers
  EXPECT_THROW(Relocalizer(scene_.vocabulary, database_, options), Error);
  options = RelocalizationOptions();
  options.ransac_reprojection_error = -1.0;
  EXPECT_THROW(Relocalizer(scene_.vocabulary, database_, options), Error);
  EXPECT_THROW(
      Relocalizer(std::make_shared<const BowVocabulary>(), database_, RelocalizationOptions()),
      Error);
  EXPECT_THROW(Relocalizer(nullptr, database_, RelocalizationOptions()), Error);
}

}  // namespace
}  // namespace drvslam
