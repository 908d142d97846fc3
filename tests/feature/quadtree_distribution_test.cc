#include "drvslam/feature/quadtree_distribution.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace drvslam {
namespace {

std::vector<cv::KeyPoint> Grid(int x0, int y0, int x1, int y1, int step, float response) {
  std::vector<cv::KeyPoint> corners;
  for (int y = y0; y < y1; y += step) {
    for (int x = x0; x < x1; x += step) corners.emplace_back(cv::Point2f(x, y), 7, -1, response);
  }
  return corners;
}

TEST(QuadtreeDistributionTest, KeepsAllWhenAtMostTarget) {
  std::vector<cv::KeyPoint> corners = Grid(0, 0, 100, 100, 20, 10);
  DistributeQuadtree(cv::Rect(0, 0, 100, 100), 25, &corners);
  EXPECT_EQ(corners.size(), 25u);
  DistributeQuadtree(cv::Rect(0, 0, 100, 100), 0, &corners);
  EXPECT_TRUE(corners.empty());
}

TEST(QuadtreeDistributionTest, DenseClusterDoesNotTakeTheBudget) {
  // A dense, strong cluster in one corner and a sparse, weak spread elsewhere: the sparse
  // corners must still get their share.
  const cv::Rect region(0, 0, 400, 400);
  std::vector<cv::KeyPoint> corners = Grid(0, 0, 100, 100, 2, 50);  // 2500 strong
  const std::vector<cv::KeyPoint> sparse = Grid(110, 110, 400, 400, 25, 10);
  corners.insert(corners.end(), sparse.begin(), sparse.end());
  DistributeQuadtree(region, 100, &corners);
  ASSERT_EQ(corners.size(), 100u);
  const int in_cluster =
      static_cast<int>(std::count_if(corners.begin(), corners.end(), [](const cv::KeyPoint& kp) {
        return kp.pt.x < 100 && kp.pt.y < 100;
      }));
  // The cluster covers 1/16 of the region; an even spread gives it ~6, not most of 100.
  EXPECT_LE(in_cluster, 16);
  EXPECT_GE(in_cluster, 3);
}

TEST(QuadtreeDistributionTest, KeepsTheStrongestOfEachNode) {
  // Pairs of neighbours, one strong and one weak: with as many nodes as pairs, each keeps the
  // strong one.
  std::vector<cv::KeyPoint> corners;
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 8; ++x) {
      corners.emplace_back(cv::Point2f(x * 16 + 4, y * 16 + 4), 7, -1, 30);
      corners.emplace_back(cv::Point2f(x * 16 + 5, y * 16 + 5), 7, -1, 10);
    }
  }
  DistributeQuadtree(cv::Rect(0, 0, 128, 128), 64, &corners);
  ASSERT_EQ(corners.size(), 64u);
  for (const cv::KeyPoint& kp : corners) EXPECT_EQ(kp.response, 30.0f) << kp.pt;
}

TEST(QuadtreeDistributionTest, EmptyAreasCostNothing) {
  // Corners only in the right half: all of the target is met there.
  std::vector<cv::KeyPoint> corners = Grid(200, 0, 400, 300, 3, 20);
  DistributeQuadtree(cv::Rect(0, 0, 400, 300), 300, &corners);
  EXPECT_EQ(corners.size(), 300u);
  std::vector<int> cells(16, 0);
  for (const cv::KeyPoint& kp : corners) {
    ++cells[static_cast<int>((kp.pt.y) / 75) * 4 + static_cast<int>((kp.pt.x - 200) / 50)];
  }
  // 16 cells of the right half, ~19 each.
  for (int c : cells) {
    EXPECT_GE(c, 10);
    EXPECT_LE(c, 30);
  }
}

TEST(QuadtreeDistributionTest, DuplicatedCornersTerminate) {
  std::vector<cv::KeyPoint> corners(50, cv::KeyPoint(cv::Point2f(10, 10), 7, -1, 5));
  corners.emplace_back(cv::Point2f(30, 30), 7, -1, 5);
  DistributeQuadtree(cv::Rect(0, 0, 64, 64), 10, &corners);
  EXPECT_EQ(corners.size(), 2u);
}

TEST(QuadtreeDistributionTest, WideRegionsGetSeveralRoots) {
  std::vector<cv::KeyPoint> corners = Grid(0, 0, 900, 100, 5, 10);
  DistributeQuadtree(cv::Rect(0, 0, 900, 100), 90, &corners);
  ASSERT_EQ(corners.size(), 90u);
  std::vector<int> thirds(3, 0);
  for (const cv::KeyPoint& kp : corners) ++thirds[static_cast<int>(kp.pt.x / 300)];
  for (int t : thirds) EXPECT_NEAR(t, 30, 6);
}

}  // namespace
}  // namespace drvslam
