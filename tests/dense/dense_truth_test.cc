#include "drvslam/dense/dense_truth.h"

#include <gtest/gtest.h>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

synth::Triangle MakeTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                             const Eigen::Vector3d& c) {
  synth::Triangle t;
  t.p = {a, b, c};
  t.uv = {Eigen::Vector2f::Zero(), Eigen::Vector2f::Zero(), Eigen::Vector2f::Zero()};
  return t;
}

// The floor z = 0 over [-5, 5]^2 as two triangles.
synth::TriangleList Floor() {
  return {MakeTriangle({-5, -5, 0}, {5, -5, 0}, {5, 5, 0}),
          MakeTriangle({-5, -5, 0}, {5, 5, 0}, {-5, 5, 0})};
}

DensePoint At(double x, double y, double z, int16_t label = -1) {
  DensePoint p;
  p.position = Eigen::Vector3d(x, y, z).cast<float>();
  p.label = label;
  return p;
}

TEST(PointTriangleDistance, FaceEdgeAndVertexRegions) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_NEAR(PointTriangleDistance({0.2, 0.2, 0.5}, a, b, c), 0.5, 1e-12);   // face
  EXPECT_NEAR(PointTriangleDistance({0.5, -1.0, 0.0}, a, b, c), 1.0, 1e-12);  // edge ab
  EXPECT_NEAR(PointTriangleDistance({2.0, 0.0, 0.0}, a, b, c), 1.0, 1e-12);   // vertex b
  EXPECT_NEAR(PointTriangleDistance({-1.0, -1.0, 0.0}, a, b, c), std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(PointTriangleDistance({1.0, 1.0, 0.0}, a, b, c), std::sqrt(0.5), 1e-12);  // bc
  EXPECT_NEAR(PointTriangleDistance({0.3, 0.3, 0.0}, a, b, c), 0.0, 1e-12);
}

TEST(ScoreDenseCloud, CountsGhostsAndDistances) {
  // An "actor" box face standing at x = 1 (a vertical triangle pair), swept once.
  const synth::TriangleList actor = {MakeTriangle({1, -0.5, 0}, {1, 0.5, 0}, {1, 0.5, 1.8}),
                                     MakeTriangle({1, -0.5, 0}, {1, 0.5, 1.8}, {1, -0.5, 1.8})};
  DenseCloud cloud;
  for (int i = 0; i < 90; ++i) cloud.push_back(At(-2 + 0.03 * i, 0.1, 0.01));  // on the floor
  for (int i = 0; i < 10; ++i) cloud.push_back(At(1.01, 0.0, 0.5 + 0.1 * i));  // on the actor
  cloud.push_back(At(1.0, 0.0, 0.02));     // at the actor's foot, on the floor: not a ghost
  cloud.push_back(At(3.0, 3.0, 0.0, 73));  // a key object on the floor
  DenseTruthOptions options;
  const DenseTruthScores scores = ScoreDenseCloud(cloud, Floor(), actor, {73}, options);
  EXPECT_EQ(scores.points, cloud.size());
  EXPECT_EQ(scores.ghosts, 10u);
  EXPECT_NEAR(scores.ghost_share, 10.0 / cloud.size(), 1e-12);
  EXPECT_NEAR(scores.static_mean_distance, (90 * 0.01 + 0.02) / 92.0, 1e-6);
  EXPECT_NEAR(scores.median_distance, 0.01, 1e-6);
  // Ghost points stand 0.5 .. 1.4 m above the floor: capped at max_distance.
  EXPECT_NEAR(scores.p95_distance, options.max_distance, 1e-9);
  EXPECT_EQ(scores.key_object_points, 1u);
  EXPECT_EQ(scores.background_points, cloud.size() - 1);
}

TEST(ScoreDenseCloud, EmptyCloudScoresZero) {
  const DenseTruthScores scores = ScoreDenseCloud({}, Floor(), {}, {}, DenseTruthOptions());
  EXPECT_EQ(scores.points, 0u);
  EXPECT_EQ(scores.ghost_share, 0.0);
}

TEST(AlignCloudToTruth, UndoesTheEstimateFrame) {
  // The estimate's world is the ground truth shifted by (1, 2, 3).
  Trajectory truth, estimate;
  for (int i = 0; i < 10; ++i) {
    const Eigen::Vector3d p(0.1 * i, 0.05 * i * i, 0.02 * i);
    truth.push_back({0.1 * i, SE3(Eigen::Matrix3d::Identity(), p)});
    estimate.push_back(
        {0.1 * i + 0.001, SE3(Eigen::Matrix3d::Identity(), p - Eigen::Vector3d(1, 2, 3))});
  }
  const DenseCloud aligned = AlignCloudToTruth({At(0, 0, 0)}, estimate, truth);
  ASSERT_EQ(aligned.size(), 1u);
  EXPECT_NEAR((aligned[0].position.cast<double>() - Eigen::Vector3d(1, 2, 3)).norm(), 0, 1e-5);
  EXPECT_THROW(AlignCloudToTruth({}, Trajectory(estimate.begin(), estimate.begin() + 2), truth),
               Error);
}

}  // namespace
}  // namespace drvslam
