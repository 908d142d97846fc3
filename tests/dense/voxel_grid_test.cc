#include "drvslam/dense/voxel_grid.h"

#include <gtest/gtest.h>

namespace drvslam {
namespace {

DensePoint Point(float x, float y, float z, uint8_t grey = 0, int16_t label = -1) {
  DensePoint p;
  p.position = {x, y, z};
  p.r = p.g = p.b = grey;
  p.label = label;
  return p;
}

TEST(VoxelGrid, KeysRoundTripAndSeparateNeighbours) {
  const std::optional<int64_t> a = VoxelKey({0.01f, 0.01f, 0.01f}, 0.1);
  const std::optional<int64_t> b = VoxelKey({0.09f, 0.02f, 0.05f}, 0.1);
  const std::optional<int64_t> c = VoxelKey({-0.01f, 0.01f, 0.01f}, 0.1);
  ASSERT_TRUE(a && b && c);
  EXPECT_EQ(*a, *b);
  EXPECT_NE(*a, *c);
  using Index = Eigen::Matrix<int64_t, 3, 1>;
  EXPECT_EQ(UnpackVoxel(*c), Index(-1, 0, 0));
  EXPECT_EQ(UnpackVoxel(PackVoxel(-5, 7, 123456)), Index(-5, 7, 123456));
  EXPECT_FALSE(VoxelKey({1e9f, 0.0f, 0.0f}, 0.001));
  EXPECT_FALSE(VoxelKey({std::nanf(""), 0.0f, 0.0f}, 0.1));
}

TEST(VoxelGrid, DownsampleKeepsCentroidColourAndLabel) {
  const DenseCloud cloud = {Point(0.01f, 0.01f, 0.01f, 10), Point(0.03f, 0.05f, 0.07f, 30, 73),
                            Point(0.25f, 0.0f, 0.0f, 200)};
  const DenseCloud out = VoxelDownsample(cloud, 0.1);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_NEAR(out[0].position.x(), 0.02f, 1e-6);
  EXPECT_NEAR(out[0].position.y(), 0.03f, 1e-6);
  EXPECT_NEAR(out[0].position.z(), 0.04f, 1e-6);
  EXPECT_EQ(out[0].r, 20);
  EXPECT_EQ(out[0].label, 73);  // the key-object label survives a mixed voxel
  EXPECT_EQ(out[1].r, 200);
  EXPECT_EQ(out[1].label, -1);
}

TEST(VoxelGrid, DenseGridShrinksByTheLeafRatio) {
  DenseCloud cloud;
  for (int i = 0; i < 100; ++i) {
    for (int j = 0; j < 100; ++j) cloud.push_back(Point(0.001f * i, 0.001f * j, 1.0f));
  }
  // 10 cm x 10 cm at 1 mm spacing: 2 cm voxels leave 5 x 5.
  EXPECT_EQ(VoxelDownsample(cloud, 0.02).size(), 25u);
}

TEST(VoxelGrid, IsolatedPointsGo) {
  DenseCloud cloud;
  for (int i = 0; i < 10; ++i) cloud.push_back(Point(0.1f * i + 0.05f, 0.05f, 0.05f));
  cloud.push_back(Point(5.0f, 5.0f, 5.0f));  // alone
  const DenseCloud kept = RemoveIsolatedPoints(cloud, 0.1, 1);
  ASSERT_EQ(kept.size(), 10u);
  for (const DensePoint& p : kept) EXPECT_LT(p.position.x(), 1.0f);
  EXPECT_EQ(RemoveIsolatedPoints(cloud, 0.1, 0).size(), cloud.size());
  // The line's ends have one neighbour, the inner points two.
  EXPECT_EQ(RemoveIsolatedPoints(cloud, 0.1, 2).size(), 8u);
}

}  // namespace
}  // namespace drvslam
