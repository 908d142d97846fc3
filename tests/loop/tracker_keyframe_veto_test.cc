// A frame whose keyframe is vetoed (its movers could not be looked for) is still tracked, but
// never becomes a keyframe; the same frames without the veto do make one.
#include <gtest/gtest.h>

#include "drvslam/tracking/tracker.h"
#include "plane_views.h"
#include "test_support/missing_data.h"

namespace drvslam {
namespace {

// The camera slides 6 cm per frame along x in front of the photograph: the first keyframe's
// points leave the view, and a new keyframe is wanted after about fifteen frames.
SE3 FastTruePose(int frame) { return test::ViewPose(0.0, 0.0, 0.0, -0.06 * frame, 0.0, 0.0); }

// Frames 0..frames-1 through a new tracker; frames in [veto_begin, veto_end) are vetoed. Returns
// the frames that became keyframes after the first (the map's origin).
std::vector<int> KeyFramesMade(const cv::Mat& photo, int frames, int veto_begin, int veto_end) {
  test::PlaneScene scene;
  Tracker tracker(scene.map, TrackerOptions{}, 30.0);
  std::vector<int> made;
  for (int i = 0; i < frames; ++i) {
    tracker.VetoKeyFrame(i >= veto_begin && i < veto_end);
    const TrackingResult result = tracker.Track(scene.MakeFrame(photo, FastTruePose(i)));
    EXPECT_EQ(result.state, TrackingState::kOk) << "frame " << i;
    if (i > 0 && result.new_keyframe) made.push_back(i);
  }
  return made;
}

TEST(TrackerKeyFrameVetoTest, VetoedFramesAreTrackedButMakeNoKeyFrame) {
  const cv::Mat photo = test::LoadPhoto("graf1.png");
  if (photo.empty())
    DRVSLAM_MISSING_TEST_DATA() << "graf1.png missing in " << DRVSLAM_OPENCV_DATA_DIR;
  constexpr int kFrames = 20;
  const std::vector<int> free = KeyFramesMade(photo, kFrames, 0, 0);
  ASSERT_FALSE(free.empty()) << "the slide should make a keyframe without the veto";
  ASSERT_LT(free.front(), kFrames - 1);
  EXPECT_TRUE(KeyFramesMade(photo, kFrames, 1, kFrames).empty());
  // The veto lasts only while it is set: vetoed through the frame that made the first keyframe,
  // a later frame makes one.
  const std::vector<int> later = KeyFramesMade(photo, kFrames, 1, free.front() + 1);
  ASSERT_FALSE(later.empty());
  EXPECT_GT(later.front(), free.front());
}

}  // namespace
}  // namespace drvslam
