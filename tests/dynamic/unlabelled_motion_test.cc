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

// A near mover is large in the image: its moving points sample only part of it, and the region
// reaches Dynamic.regionReach metres around them at their depth, over the same surface only.
TEST(UnlabelledMotionTest, ANearMoverIsCoveredByTheMetricReach) {
  // A 0.8 m surface 200 px wide (x in [40, 240)) in front of a 3 m wall; eight moving points
  // near its middle.
  cv::Mat depth(240, 320, CV_32FC1, cv::Scalar(3.0f));
  depth(cv::Rect(40, 20, 200, 200)).setTo(0.8f);
  std::vector<FlowTrack> tracks;
  for (int i = 0; i < 8; ++i) tracks.push_back(Moving(130 + 5 * i, 120 + (i % 3) * 10));
  const auto covered = [&](double focal_px, double reach) {
    DynamicOptions options;
    options.region_reach = reach;
    const std::vector<MovingRegion> regions =
        FindUnlabelledMotion(tracks, cv::Mat(), depth, options, focal_px);
    cv::Mat mask = cv::Mat::zeros(240, 320, CV_8UC1);
    PaintRegions(regions, mask);
    return mask;
  };
  // Pixels only: the 20-pixel margin around the points (x in [130, 165]).
  const cv::Mat pixels_only = covered(0.0, 0.2);
  EXPECT_EQ(pixels_only.at<uint8_t>(120, 150), 255);
  EXPECT_EQ(pixels_only.at<uint8_t>(120, 60), 0);
  EXPECT_EQ(covered(400.0, 0.0).at<uint8_t>(120, 60), 0);  // reach off
  // 400 px focal length, 0.2 m at 0.8 m: 100 px around the points, over the surface only.
  const cv::Mat reached = covered(400.0, 0.2);
  EXPECT_EQ(reached.at<uint8_t>(120, 60), 255);
  EXPECT_EQ(reached.at<uint8_t>(40, 150), 255);
  EXPECT_EQ(reached.at<uint8_t>(120, 20), 0);       // the wall beside it
  EXPECT_EQ(reached.at<uint8_t>(120, 260), 0);      // the wall on the other side
  EXPECT_EQ(reached.at<uint8_t>(5, 150), 0);        // more than 100 px above the points' top
  EXPECT_EQ(cv::countNonZero(reached), 200 * 200);  // the whole surface, nothing else
}

// The reach is metric in depth too: a surface joined to the mover (a floor sloping away from
// its feet) is followed only while it stays within the reach of the mover's depth.
TEST(UnlabelledMotionTest, AJoinedSurfaceIsFollowedOnlyWithinTheReach) {
  // The mover at 0.8 m for y < 150; below it a floor whose depth grows 1 cm per row from 0.8 m,
  // depth-connected to it all the way (steps well under Dynamic.regionDepthStep).
  cv::Mat depth(240, 320, CV_32FC1, cv::Scalar(0.8f));
  for (int y = 150; y < 240; ++y) depth.row(y).setTo(0.8f + 0.01f * static_cast<float>(y - 150));
  std::vector<FlowTrack> tracks;
  for (int i = 0; i < 8; ++i) tracks.push_back(Moving(130 + 5 * i, 120 + (i % 3) * 10));
  DynamicOptions options;
  options.region_reach = 0.2;
  const std::vector<MovingRegion> regions =
      FindUnlabelledMotion(tracks, cv::Mat(), depth, options, 400.0);
  cv::Mat mask = cv::Mat::zeros(240, 320, CV_8UC1);
  PaintRegions(regions, mask);
  EXPECT_EQ(mask.at<uint8_t>(165, 150), 255);  // 0.95 m: within 0.2 m of the mover
  EXPECT_EQ(mask.at<uint8_t>(200, 150), 0);    // 1.30 m: beyond it, though joined and in the box
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
