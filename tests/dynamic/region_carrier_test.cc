// Carrying regions of unlabelled motion through a blurred frame: each region moves with the
// median displacement of the tracks that start on it, is cropped at the image border, and is
// dropped when too few tracks start on it.
#include "drvslam/dynamic/region_carrier.h"

#include <gtest/gtest.h>

namespace drvslam {
namespace {

FlowTrack Track(float x, float y, float dx, float dy) {
  FlowTrack track;
  track.prev = {x, y};
  track.cur = {x + dx, y + dy};
  return track;
}

// A 20x20 region at (x, y), its left half on the mask.
MovingRegion Region(int x, int y) {
  MovingRegion region;
  region.box = cv::Rect(x, y, 20, 20);
  region.mask = cv::Mat::zeros(20, 20, CV_8UC1);
  region.mask(cv::Rect(0, 0, 10, 20)).setTo(255);
  region.points = 7;
  region.members = {0, 1, 2};
  return region;
}

TEST(RegionCarrierTest, ARegionMovesWithTheMedianOfItsTracks) {
  std::vector<FlowTrack> tracks = {Track(52, 52, 10, 5), Track(55, 60, 11, 5), Track(58, 65, 10, 4),
                                   Track(53, 62, 10, 5),
                                   Track(51, 68, 30, -20)};  // an outlier among them
  tracks.push_back(Track(65, 55, -40, 0));    // in the box but off the mask: not the region's
  tracks.push_back(Track(150, 150, -40, 0));  // elsewhere
  const std::vector<MovingRegion> carried = CarryRegions({Region(50, 50)}, tracks, {320, 240});
  ASSERT_EQ(carried.size(), 1u);
  EXPECT_EQ(carried[0].box, cv::Rect(60, 55, 20, 20));
  EXPECT_EQ(cv::countNonZero(carried[0].mask), 10 * 20);
  EXPECT_EQ(carried[0].mask.at<uint8_t>(0, 0), 255);
  EXPECT_EQ(carried[0].mask.at<uint8_t>(0, 15), 0);
  EXPECT_EQ(carried[0].points, 7);
  EXPECT_TRUE(carried[0].members.empty());
}

TEST(RegionCarrierTest, TooFewTracksDropTheRegion) {
  const std::vector<FlowTrack> tracks = {Track(52, 52, 10, 5), Track(55, 60, 11, 5)};
  EXPECT_TRUE(CarryRegions({Region(50, 50)}, tracks, {320, 240}).empty());
}

TEST(RegionCarrierTest, ARegionLeavingTheImageIsCroppedThenDropped) {
  // Moved 12 px left from x = 5: the box's first 7 columns leave the image.
  const std::vector<FlowTrack> left = {Track(6, 52, -12, 0), Track(8, 60, -12, 0),
                                       Track(9, 65, -12, 0)};
  const std::vector<MovingRegion> carried = CarryRegions({Region(5, 50)}, left, {320, 240});
  ASSERT_EQ(carried.size(), 1u);
  EXPECT_EQ(carried[0].box, cv::Rect(0, 50, 13, 20));
  EXPECT_EQ(cv::countNonZero(carried[0].mask), 3 * 20);  // the mask's last 3 columns remain
  // Moved 40 px left: nothing of it is in the image.
  const std::vector<FlowTrack> gone = {Track(6, 52, -40, 0), Track(8, 60, -40, 0),
                                       Track(9, 65, -40, 0)};
  EXPECT_TRUE(CarryRegions({Region(5, 50)}, gone, {320, 240}).empty());
}

}  // namespace
}  // namespace drvslam
