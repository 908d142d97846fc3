// Carrying regions of unlabelled motion through a blurred frame: each region moves with the
// tracks that start on it (their median displacement when they are few or disagree, a fitted
// similarity when most agree on one), is cropped at the image border, and is dropped when too
// few tracks start on it. A carried region that this frame found again is not kept twice.
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
  // The masked left half, moved by (10, 5): the box is the moved mask's.
  EXPECT_EQ(carried[0].box, cv::Rect(60, 55, 10, 20));
  EXPECT_EQ(cv::countNonZero(carried[0].mask), 10 * 20);
  EXPECT_EQ(carried[0].points, 7);
  EXPECT_TRUE(carried[0].members.empty());
}

TEST(RegionCarrierTest, ManyAgreeingTracksCarryARegionByTheirSimilarity) {
  // Eight tracks on the mask, all rotated 90 degrees about the region's corner (50, 50) and
  // shifted by (100, 0): a rigid motion that a median displacement would get wrong.
  std::vector<FlowTrack> tracks;
  for (const cv::Point2f p :
       {cv::Point2f(51, 51), cv::Point2f(58, 51), cv::Point2f(51, 68), cv::Point2f(58, 68),
        cv::Point2f(54, 55), cv::Point2f(55, 63), cv::Point2f(52, 60), cv::Point2f(57, 57)}) {
    const cv::Point2f rotated(50 - (p.y - 50), 50 + (p.x - 50));
    tracks.push_back(Track(p.x, p.y, rotated.x + 100 - p.x, rotated.y - p.y));
  }
  const std::vector<MovingRegion> carried = CarryRegions({Region(50, 50)}, tracks, {320, 240});
  ASSERT_EQ(carried.size(), 1u);
  // The 10 x 20 half turned on its side: 20 wide, 10 high, left of x = 150 and below y = 50.
  EXPECT_NEAR(carried[0].box.width, 20, 1);
  EXPECT_NEAR(carried[0].box.height, 10, 1);
  EXPECT_NEAR(carried[0].box.x, 130, 1);
  EXPECT_NEAR(carried[0].box.y, 50, 1);
  EXPECT_NEAR(cv::countNonZero(carried[0].mask), 10 * 20, 30);
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
  EXPECT_EQ(carried[0].box, cv::Rect(0, 50, 3, 20));  // the mask's last 3 columns remain
  EXPECT_EQ(cv::countNonZero(carried[0].mask), 3 * 20);
  // Moved 40 px left: nothing of it is in the image.
  const std::vector<FlowTrack> gone = {Track(6, 52, -40, 0), Track(8, 60, -40, 0),
                                       Track(9, 65, -40, 0)};
  EXPECT_TRUE(CarryRegions({Region(5, 50)}, gone, {320, 240}).empty());
}

TEST(RegionCarrierTest, CarriedRegionsMostlyFoundAgainAreDropped) {
  const cv::Size image(320, 240);
  // Each Region covers 10x20 = 200 pixels (its left half).
  const std::vector<MovingRegion> carried = {Region(50, 50), Region(150, 50), Region(250, 50)};
  // Found: all of the first region's mask, a quarter of the second's (its top 5 rows), none of
  // the third's.
  MovingRegion first = Region(50, 50);
  MovingRegion quarter;
  quarter.box = cv::Rect(150, 50, 10, 5);
  quarter.mask = cv::Mat(5, 10, CV_8UC1, cv::Scalar(255));
  const std::vector<MovingRegion> kept = WithoutCovered(carried, {first, quarter}, image);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].box, cv::Rect(150, 50, 20, 20));
  EXPECT_EQ(kept[1].box, cv::Rect(250, 50, 20, 20));
  // The second region half found (top 10 rows): it goes too.
  quarter.box = cv::Rect(150, 50, 10, 10);
  quarter.mask = cv::Mat(10, 10, CV_8UC1, cv::Scalar(255));
  EXPECT_EQ(WithoutCovered(carried, {quarter}, image).size(), 2u);
  // Nothing found: every carried region stays.
  EXPECT_EQ(WithoutCovered(carried, {}, image).size(), 3u);
}

}  // namespace
}  // namespace drvslam
