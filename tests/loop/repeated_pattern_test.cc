// Localization in a saved map of a wall with a repeated photograph (tiled_wall.h): the map has a
// keyframe in front of each copy and of the different photograph; a camera then slides along
// the wall on another path, from a view of the copies only (it could be in front of any of
// them) to a view of the different photograph. No pose a robot may act on may be off by a
// period: every one reported is within kMaxErrorMetres of the truth, and once the view shows the
// different photograph the camera is localized again.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <vector>

#include "drvslam/loop/relocalizer.h"
#include "drvslam/tracking/keyframe_factory.h"
#include "drvslam/tracking/tracker.h"
#include "plane_views.h"
#include "test_support/missing_data.h"
#include "tiled_wall.h"

namespace drvslam {
namespace {

constexpr double kMaxErrorMetres = 0.10;
constexpr int kFrames = 60;
// The path: from 6 cm right of copy 1's centre to 2 cm right of the different photograph's
// centre, 4 cm a frame, 6 cm closer to the wall than the map's keyframes, 2 cm lower, turned by
// 1.7 degrees.
constexpr double kStartX = 1.26;
constexpr double kStep = 0.04;
// From here on at least three quarters of the view is the different photograph.
constexpr double kUnambiguousX = 3.3;

SE3 PathPose(int frame) { return test::WallCamera(kStartX + kStep * frame, 0.02, 0.06, 0.03); }

// What a robot may act on (before #31: every tracked frame).
bool Reported(const TrackingResult& result) {
  return result.quality == LocalizationQuality::kVerified;
}

class RepeatedPatternTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!scene_.LoadVocabulary()) DRVSLAM_MISSING_TEST_DATA() << "no default vocabulary was built";
    const cv::Mat tile = test::LoadPhoto("graf1.png");
    const cv::Mat unique = test::LoadPhoto("home.jpg");
    if (tile.empty() || unique.empty()) {
      DRVSLAM_MISSING_TEST_DATA() << "graf1.png or home.jpg missing in " << DRVSLAM_OPENCV_DATA_DIR;
    }
    wall_ = std::make_unique<test::TiledWall>(tile, unique);
    // The map: one keyframe squarely in front of each copy and of the different photograph.
    for (int k = 0; k <= test::kRepeats; ++k) {
      const SE3 T_cw = test::WallCamera(test::TiledWall::CentreX(k), 0.0, 0.0, 0.0);
      Frame frame = MakeFrame(T_cw);
      frame.SetPose(T_cw);
      auto keyframe = CreateInitialKeyFrame(frame, scene_.map, 50);
      ASSERT_TRUE(keyframe) << "copy " << k;
      scene_.ComputeBow(frame);
      keyframe->SetBow(frame.bow, frame.bow_features);
      database_.Add(keyframe);
    }
  }

  Frame MakeFrame(const SE3& T_cw) {
    const test::WallView view = wall_->Render(scene_.settings.camera, T_cw);
    scene_.next_timestamp += 1.0 / 30.0;
    return scene_.factory.Build(scene_.next_timestamp, view.bgr, view.depth);
  }

  test::PlaneScene scene_;
  std::unique_ptr<test::TiledWall> wall_;
  KeyFrameDatabase database_;
};

TEST_F(RepeatedPatternTest, NoReportedPoseIsAPeriodOffAndTheUniqueViewIsFound) {
  Relocalizer relocalizer(scene_.vocabulary, database_, RelocalizationOptions());
  Tracker tracker(scene_.map, TrackerOptions{}, 30.0);
  tracker.SetPlaceRecognition(&relocalizer);
  tracker.StartInLoadedMap();
  tracker.SetLocalizationOnly(true);

  int reported = 0;
  int wrong = 0;
  int tentative = 0;
  int tentative_wrong = 0;
  int first_unambiguous_reported = -1;
  bool last_reported = false;
  double last_error = 0.0;
  for (int i = 0; i < kFrames; ++i) {
    const SE3 truth = PathPose(i);
    const TrackingResult result = tracker.Track(MakeFrame(truth));
    // Tentative poses are counted apart: a robot is told not to act on them.
    if (result.quality == LocalizationQuality::kTentative) {
      ++tentative;
      const Eigen::Vector3d centre = tracker.LastFrame()->Pose().Inverse().Translation();
      if ((centre - truth.Inverse().Translation()).norm() > kMaxErrorMetres) ++tentative_wrong;
    }
    if (!Reported(result)) {
      last_reported = false;
      continue;
    }
    ASSERT_TRUE(tracker.LastFrame().has_value());
    const Eigen::Vector3d centre = tracker.LastFrame()->Pose().Inverse().Translation();
    const double error = (centre - truth.Inverse().Translation()).norm();
    ++reported;
    if (error > kMaxErrorMetres) {
      ++wrong;
      ADD_FAILURE() << "frame " << i << ": reported " << error << " m from the truth";
    }
    const double x = kStartX + kStep * i;
    if (x >= kUnambiguousX && first_unambiguous_reported < 0) first_unambiguous_reported = i;
    last_reported = true;
    last_error = error;
  }
  std::printf(
      "repeated pattern: %d of %d frames verified, %d more than %.2f m off; %d tentative (%d "
      "off); first verified in the unambiguous view: frame %d; relocalization attempts %d, %d "
      "refused as ambiguous\n",
      reported, kFrames, wrong, kMaxErrorMetres, tentative, tentative_wrong,
      first_unambiguous_reported, relocalizer.Attempts(), relocalizer.AmbiguousRejections());
  EXPECT_EQ(wrong, 0);
  // The unambiguous stretch is 8 frames long; localization must come within its first 5.
  const int first_unambiguous =
      static_cast<int>(std::ceil((kUnambiguousX - kStartX) / kStep - 1e-9));
  ASSERT_GE(first_unambiguous_reported, 0) << "never localized in the unambiguous view";
  EXPECT_LE(first_unambiguous_reported, first_unambiguous + 4);
  EXPECT_TRUE(last_reported);
  EXPECT_LT(last_error, 0.02);
}

}  // namespace
}  // namespace drvslam
