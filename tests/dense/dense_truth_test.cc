#include "drvslam/tools/truth/dense_truth.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/tools/truth/dense_truth_json.h"

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
  EXPECT_NEAR(scores.ghost_share.value(), 10.0 / cloud.size(), 1e-12);
  EXPECT_NEAR(scores.static_mean_distance.value(), (90 * 0.01 + 0.02) / 92.0, 1e-6);
  EXPECT_NEAR(scores.median_distance.value(), 0.01, 1e-6);
  // Ghost points stand 0.5 .. 1.4 m above the floor: capped at max_distance.
  EXPECT_NEAR(scores.p95_distance.value(), options.max_distance, 1e-9);
  EXPECT_EQ(scores.key_object_points, 1u);
  EXPECT_EQ(scores.background_points, cloud.size() - 1);
}

// dense-eval --ghosts: each ghost with its index, distance to the static scene and the first
// swept triangle near it (its frame says when the actor was there).
TEST(ScoreDenseCloud, ListsEachGhostWithTheFirstActorTriangleNearIt) {
  // The actor's face at x = 1 in "frame 0" (triangles 0, 1) and at x = 2 in "frame 1" (2, 3).
  synth::TriangleList swept;
  for (const double x : {1.0, 2.0}) {
    swept.push_back(MakeTriangle({x, -0.5, 0}, {x, 0.5, 0}, {x, 0.5, 1.8}));
    swept.push_back(MakeTriangle({x, -0.5, 0}, {x, 0.5, 1.8}, {x, -0.5, 1.8}));
  }
  const DenseCloud cloud = {At(0.0, 0.0, 0.01), At(2.01, 0.2, 1.0), At(1.0, -0.2, 1.5)};
  std::vector<GhostPoint> ghosts;
  const DenseTruthScores scores =
      ScoreDenseCloud(cloud, Floor(), swept, {}, DenseTruthOptions(), &ghosts);
  ASSERT_EQ(scores.ghosts, 2u);
  ASSERT_EQ(ghosts.size(), 2u);
  EXPECT_EQ(ghosts[0].index, 1u);
  EXPECT_GE(ghosts[0].actor_triangle, 2u);  // frame 1's face
  EXPECT_NEAR(ghosts[0].static_distance, DenseTruthOptions().max_distance, 1e-9);
  EXPECT_EQ(ghosts[1].index, 2u);
  EXPECT_LE(ghosts[1].actor_triangle, 1u);  // frame 0's face
}

// An empty map has no ghost share or distance to score: undefined (null), not a perfect 0.
TEST(ScoreDenseCloud, EmptyCloudScoresAreUndefined) {
  const DenseTruthScores scores = ScoreDenseCloud({}, Floor(), {}, {}, DenseTruthOptions());
  EXPECT_EQ(scores.points, 0u);
  const nlohmann::json json = DenseTruthScoresJson(scores);
  EXPECT_EQ(json["ghosts"], 0);
  EXPECT_TRUE(json["ghost_share"].is_null()) << json.dump();
  for (const char* key : {"mean", "median", "p95", "static_mean", "static_p95"}) {
    EXPECT_TRUE(json["distance"][key].is_null()) << key << ": " << json.dump();
  }
  EXPECT_TRUE(json["key_object_density"].is_null()) << json.dump();
  EXPECT_TRUE(json["background_density"].is_null()) << json.dump();
}

// Every point a ghost: no static point is left to measure, so the static distances are
// undefined rather than 0 m.
TEST(ScoreDenseCloud, AllGhostsLeaveStaticDistancesUndefined) {
  const synth::TriangleList actor = {MakeTriangle({1, -0.5, 0}, {1, 0.5, 0}, {1, 0.5, 1.8}),
                                     MakeTriangle({1, -0.5, 0}, {1, 0.5, 1.8}, {1, -0.5, 1.8})};
  DenseCloud cloud;
  for (int i = 0; i < 5; ++i) cloud.push_back(At(1.01, 0.0, 0.5 + 0.1 * i));
  const DenseTruthScores scores = ScoreDenseCloud(cloud, Floor(), actor, {}, DenseTruthOptions());
  ASSERT_EQ(scores.ghosts, 5u);
  const nlohmann::json json = DenseTruthScoresJson(scores);
  EXPECT_NEAR(json["ghost_share"].get<double>(), 1.0, 1e-12);
  EXPECT_TRUE(json["distance"]["static_mean"].is_null()) << json.dump();
  EXPECT_TRUE(json["distance"]["static_p95"].is_null()) << json.dump();
  EXPECT_TRUE(json["key_object_density"].is_null()) << json.dump();
  const std::string text = FormatDenseTruthScores(scores);
  EXPECT_NE(text.find("without ghosts:    mean n/a, p95 n/a"), std::string::npos) << text;
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
