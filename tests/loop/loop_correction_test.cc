#include <gtest/gtest.h>

#include "drvslam/loop/global_bundle_adjuster.h"
#include "drvslam/loop/loop_corrector.h"
#include "drvslam/loop/loop_verifier.h"
#include "drvslam/mapping/map_consistency.h"
#include "loop_scene.h"

namespace drvslam {
namespace {

double PositionErrorOf(const test::LoopScene& scene, int k) {
  return test::PositionError(*scene.KeyFrameAt(k), scene.TruePose(k));
}

TEST(LoopVerifierTest, RecoversTheDriftFreePose) {
  test::LoopScene scene;
  const int current = 12;  // back where keyframe 0 was
  LoopVerification report;
  const auto match =
      VerifyLoop(scene.KeyFrameAt(current), {scene.KeyFrameAt(0)}, LoopVerifierRules{}, &report);
  ASSERT_TRUE(match.has_value());
  EXPECT_EQ(match->loop, scene.KeyFrameAt(0));
  EXPECT_GE(report.best_bow_matches, 60);
  // Keyframe 0 has no drift, so the loop side's frame is the true one.
  const SE3 error = match->corrected_T_cw * scene.TruePose(current).Inverse();
  EXPECT_LT(error.Translation().norm(), 1e-3);
  EXPECT_LT(RotationAngle(error), 1e-3);
  EXPECT_NEAR(match->correction_m, PositionErrorOf(scene, current), 1e-3);
  // The matched points are keyframe 0's points of the same scene points.
  int right = 0;
  for (std::size_t i = 0; i < match->matched_points.size(); ++i) {
    const auto& point = match->matched_points[i];
    if (!point) continue;
    right += point == scene.MapPointOf(0, scene.ScenePoint(current, i)) ? 1 : 0;
  }
  EXPECT_GE(match->matches, 60);
  EXPECT_GE(right, match->matches * 9 / 10);
}

TEST(LoopVerifierTest, RejectsAPlaceThatDoesNotMatch) {
  test::LoopScene scene;
  // Keyframe 6 looks at the opposite wall: no shared points.
  EXPECT_FALSE(VerifyLoop(scene.KeyFrameAt(12), {scene.KeyFrameAt(6)}, LoopVerifierRules{}));
}

TEST(LoopCorrectorTest, CorrectionReducesDriftAndFusesDuplicates) {
  test::LoopScene scene;
  const auto match = VerifyLoop(scene.KeyFrameAt(12), {scene.KeyFrameAt(0)}, LoopVerifierRules{});
  ASSERT_TRUE(match.has_value());
  const double drift_before = scene.MeanPositionError();
  const double end_before = PositionErrorOf(scene, 15);
  const std::size_t points_before = scene.GetMap().MapPointCount();
  const SE3 loop_pose = scene.KeyFrameAt(0)->Pose();

  KeyFrameEdgeSet loop_edges;
  const LoopCorrectionStats stats =
      CorrectLoop(*match, scene.GetMap(), OrbMatcher(), LoopCorrectionRules{}, &loop_edges);
  EXPECT_TRUE(stats.applied);
  EXPECT_GE(stats.corrected_keyframes, 2);
  EXPECT_GT(stats.fused_points, 40);
  EXPECT_GE(stats.new_loop_edges, 1);
  EXPECT_EQ(stats.graph_keyframes, 16);
  EXPECT_LT(stats.graph_final_cost, stats.graph_initial_cost);
  EXPECT_TRUE(loop_edges.count({0, 12}));
  EXPECT_LT(scene.GetMap().MapPointCount(), points_before);

  // The loop keyframe holds still; the drift is spread and mostly gone.
  EXPECT_LT((scene.KeyFrameAt(0)->Pose() * loop_pose.Inverse()).Log().norm(), 1e-9);
  const double drift_after = scene.MeanPositionError();
  EXPECT_LT(drift_after, 0.35 * drift_before)
      << "mean keyframe error " << drift_before << " m before, " << drift_after << " m after";
  EXPECT_LT(PositionErrorOf(scene, 15), 0.2 * end_before);
  // Keyframe 12 now sees keyframe 0's points instead of its duplicates.
  int shared = 0;
  const auto points = scene.KeyFrameAt(12)->MapPoints();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i] && points[i] == scene.MapPointOf(0, scene.ScenePoint(12, i))) ++shared;
  }
  EXPECT_GT(shared, 40);
  EXPECT_GT(scene.KeyFrameAt(12)->Weight(scene.KeyFrameAt(0)->Id()), 0);
  // Fusion kept every link two-sided.
  const auto problems = CheckMapConsistency(scene.GetMap());
  EXPECT_TRUE(problems.empty()) << problems.front();
}

TEST(LoopCorrectorTest, LoopWhoseKeyFrameLeftTheMapChangesNothing) {
  test::LoopScene scene;
  const auto match = VerifyLoop(scene.KeyFrameAt(12), {scene.KeyFrameAt(0)}, LoopVerifierRules{});
  ASSERT_TRUE(match.has_value());
  // The map was reset (tracking lost) between verification and correction.
  scene.GetMap().Clear();
  const SE3 before = scene.KeyFrameAt(5)->Pose();
  KeyFrameEdgeSet loop_edges;
  const LoopCorrectionStats stats =
      CorrectLoop(*match, scene.GetMap(), OrbMatcher(), LoopCorrectionRules{}, &loop_edges);
  EXPECT_FALSE(stats.applied);
  EXPECT_TRUE(loop_edges.empty());
  EXPECT_LT((scene.KeyFrameAt(5)->Pose() * before.Inverse()).Log().norm(), 1e-12);
}

TEST(GlobalBundleAdjusterTest, RefinesAfterCorrectionAndCarriesNewKeyFrames) {
  test::LoopScene scene;
  const auto match = VerifyLoop(scene.KeyFrameAt(12), {scene.KeyFrameAt(0)}, LoopVerifierRules{});
  ASSERT_TRUE(match.has_value());
  KeyFrameEdgeSet loop_edges;
  CorrectLoop(*match, scene.GetMap(), OrbMatcher(), LoopCorrectionRules{}, &loop_edges);
  const double corrected = scene.MeanPositionError();

  const GlobalBundle bundle = GatherGlobalBundle(scene.GetMap());
  ASSERT_EQ(bundle.keyframes.size(), 16u);
  EXPECT_TRUE(bundle.problem.keyframe_fixed[0]);
  EXPECT_GT(bundle.problem.observations.size(), 1000u);
  const LocalBundleAdjustmentResult result = SolveGlobalBundle(bundle, 10, nullptr);
  EXPECT_FALSE(result.interrupted);
  EXPECT_LT(result.final_inlier_chi2, result.initial_inlier_chi2);

  // A keyframe made while the solve ran, below the last one in the spanning tree.
  const auto parent = scene.KeyFrameAt(15);
  const SE3 offset(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.05, 0.0, 0.0));
  auto late =
      std::make_shared<KeyFrame>(scene.GetMap().NextKeyFrameId(), 99, 9.9,
                                 std::make_shared<const FrameFeatures>(parent->Features()),
                                 offset * parent->Pose(), std::vector<std::shared_ptr<MapPoint>>());
  scene.GetMap().AddKeyFrame(late);
  late->SetParent(parent);

  const GlobalBundleMergeStats merge = MergeGlobalBundle(scene.GetMap(), bundle, result);
  EXPECT_EQ(merge.keyframes_adjusted, 16);
  EXPECT_EQ(merge.keyframes_propagated, 1);
  EXPECT_GT(merge.points_adjusted, 100);
  EXPECT_LT((late->Pose() * parent->Pose().Inverse() * offset.Inverse()).Log().norm(), 1e-9);
  const auto problems = CheckMapConsistency(scene.GetMap());
  EXPECT_TRUE(problems.empty()) << problems.front();
  const double adjusted = scene.MeanPositionError();
  EXPECT_LT(adjusted, corrected + 0.005)
      << "mean keyframe error " << corrected << " m after correction, " << adjusted
      << " m after global BA";
}

}  // namespace
}  // namespace drvslam
