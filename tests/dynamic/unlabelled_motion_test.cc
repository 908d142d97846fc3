// Unlabelled motion: a tight group of moving points on one depth surface becomes a region that
// follows the surface; scattered moving points, points on labelled masks and points without
// depth do not.
#include "drvslam/dynamic/unlabelled_motion.h"

#include <gtest/gtest.h>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

FlowTrack Moving(float x, float y) {
  FlowTrack track;
  track.prev = {x - 5, y};
  track.cur = {x, y};
  track.moving = true;
  return track;
}

// A 3 m background with a 1.5 m box at x, y in [100, 160).
cv::Mat Depth() {
  cv::Mat depth(240, 320, CV_32FC1, cv::Scalar(3.0f));
  depth(cv::Rect(100, 100, 60, 60)).setTo(1.5f);
  return depth;
}

TEST(UnlabelledMotionTest, AGroupOnOneSurfaceBecomesARegion) {
  DynamicOptions options;
  std::vector<FlowTrack> tracks;
  for (int i = 0; i < 8; ++i) tracks.push_back(Moving(110 + 5 * i, 120 + (i % 3) * 10));
  const std::vector<MovingRegion> regions =
      FindUnlabelledMotion(tracks, cv::Mat(), Depth(), options);
  ASSERT_EQ(regions.size(), 1u);
  EXPECT_EQ(regions[0].points, 8);
  cv::Mat mask = cv::Mat::zeros(240, 320, CV_8UC1);
  PaintRegions(regions, mask);
  // The region covers the box's surface near the points, not the background beside it.
  EXPECT_EQ(mask.at<uint8_t>(125, 130), 255);
  EXPECT_EQ(mask.at<uint8_t>(102, 102), 255);
  EXPECT_EQ(mask.at<uint8_t>(125, 95), 0);
  EXPECT_EQ(mask.at<uint8_t>(165, 130), 0);
}

TEST(UnlabelledMotionTest, ScatteredPointsAreNoise) {
  DynamicOptions options;
  std::vector<FlowTrack> tracks;
  for (int i = 0; i < 10; ++i) tracks.push_back(Moving(10 + 31 * i, 10 + 22 * i));
  EXPECT_TRUE(FindUnlabelledMotion(tracks, cv::Mat(), Depth(), options).empty());
}

TEST(UnlabelledMotionTest, DifferentDepthsDoNotJoin) {
  DynamicOptions options;
  std::vector<FlowTrack> tracks;
  // Four on the box, four on the background just beside it: neither group is large enough.
  for (int i = 0; i < 4; ++i) tracks.push_back(Moving(102 + 4 * i, 130));
  for (int i = 0; i < 4; ++i) tracks.push_back(Moving(84 + 4 * i, 130));
  EXPECT_TRUE(FindUnlabelledMotion(tracks, cv::Mat(), Depth(), options).empty());
}

TEST(UnlabelledMotionTest, LabelledAndDepthlessPointsAreSkipped) {
  DynamicOptions options;
  std::vector<FlowTrack> tracks;
  for (int i = 0; i < 8; ++i) tracks.push_back(Moving(110 + 5 * i, 120));
  cv::Mat labelled = cv::Mat::zeros(240, 320, CV_8UC1);
  labelled(cv::Rect(100, 100, 60, 60)).setTo(255);
  EXPECT_TRUE(FindUnlabelledMotion(tracks, labelled, Depth(), options).empty());
  cv::Mat no_depth = Depth();
  no_depth.setTo(0.0f);
  EXPECT_TRUE(FindUnlabelledMotion(tracks, cv::Mat(), no_depth, options).empty());
  // Static points are never grouped.
  for (FlowTrack& track : tracks) track.moving = false;
  EXPECT_TRUE(FindUnlabelledMotion(tracks, cv::Mat(), Depth(), options).empty());
}

TEST(UnlabelledMotionTest, BadInputsAreErrors) {
  DynamicOptions options;
  EXPECT_THROW(FindUnlabelledMotion({}, cv::Mat(), cv::Mat(), options), Error);
  EXPECT_THROW(FindUnlabelledMotion({}, cv::Mat(10, 10, CV_8UC1), Depth(), options), Error);
}

}  // namespace
}  // namespace drvslam
