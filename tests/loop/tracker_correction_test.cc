// Tracking across a map correction: a correction that moves the whole map under the update lock
// (as loop closing and global bundle adjustment do) raises the map's correction epoch, and the
// very next frame is tracked by the motion model in the corrected map, with no notification
// from the thread that corrected it.
#include <gtest/gtest.h>

#include <cmath>
#include <mutex>

#include "drvslam/map/map_point.h"
#include "drvslam/tracking/tracker.h"
#include "plane_views.h"
#include "test_support/missing_data.h"

namespace drvslam {
namespace {

// The camera slides 1 cm per frame along x in front of the photograph.
SE3 TruePose(int frame) { return test::ViewPose(0.0, 0.0, 0.0, -0.01 * frame, 0.0, 0.0); }

// Moves every keyframe and map point by the world change G (world_new = G * world_old), the way
// a correction rewrites the map, and raises the epoch, all under the update lock.
void MoveWholeMap(Map& map, const SE3& G) {
  std::lock_guard<std::mutex> lock(map.UpdateMutex());
  for (const auto& keyframe : map.KeyFrames()) keyframe->SetPose(keyframe->Pose() * G.Inverse());
  for (const auto& point : map.MapPoints()) point->SetPosition(G * point->Position());
  map.RaiseCorrectionEpoch();
}

TEST(TrackerCorrectionTest, NextFrameIsTrackedByTheMotionModelInTheCorrectedMap) {
  test::PlaneScene scene;
  const cv::Mat photo = test::LoadPhoto("graf1.png");
  if (photo.empty())
    DRVSLAM_MISSING_TEST_DATA() << "graf1.png missing in " << DRVSLAM_OPENCV_DATA_DIR;
  Tracker tracker(scene.map, TrackerOptions{}, 30.0);
  for (int i = 0; i < 5; ++i) {
    const TrackingResult result = tracker.Track(scene.MakeFrame(photo, TruePose(i)));
    ASSERT_EQ(result.state, TrackingState::kOk) << "frame " << i;
  }
  // The second frame has no velocity yet and is tracked against the reference keyframe.
  const int fallbacks = tracker.ReferenceFallbacks();
  ASSERT_LE(fallbacks, 1);

  // 0.3 m and 10 degrees: far beyond the motion model's search window if the last frame stayed
  // posed in the old map.
  const SE3 G = test::ViewPose(0.0, 10.0 * M_PI / 180.0, 0.0, 0.3, -0.1, 0.2);
  MoveWholeMap(scene.map, G);
  const long epoch = scene.map.CorrectionEpoch();
  EXPECT_EQ(epoch, 1);

  const TrackingResult result = tracker.Track(scene.MakeFrame(photo, TruePose(5)));
  ASSERT_EQ(result.state, TrackingState::kOk);
  EXPECT_EQ(tracker.ReferenceFallbacks(), fallbacks) << "the motion model predicted in the old map";
  ASSERT_TRUE(tracker.LastFrame().has_value());
  const SE3 expected = TruePose(5) * G.Inverse();
  const SE3 error = tracker.LastFrame()->Pose() * expected.Inverse();
  EXPECT_LT(error.Translation().norm(), 0.01);
  EXPECT_LT(RotationAngle(error), 0.01);
  // The tracker follows the epoch once: a later frame needs no further re-posing.
  EXPECT_EQ(tracker.Track(scene.MakeFrame(photo, TruePose(6))).state, TrackingState::kOk);
  EXPECT_EQ(tracker.ReferenceFallbacks(), fallbacks);
}

}  // namespace
}  // namespace drvslam
