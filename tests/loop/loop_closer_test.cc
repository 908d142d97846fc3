#include "drvslam/loop/loop_closer.h"

#include <gtest/gtest.h>

#include <atomic>

#include "drvslam/core/error.h"
#include "loop_scene.h"

namespace drvslam {
namespace {

struct HookCounts {
  std::atomic<int> paused{0};
  std::atomic<int> resumed{0};
};

LoopCloser::Hooks CountingHooks(HookCounts* counts) {
  LoopCloser::Hooks hooks;
  hooks.pause_mapping = [counts] { ++counts->paused; };
  hooks.resume_mapping = [counts] { ++counts->resumed; };
  return hooks;
}

// Feeds the scene's keyframes as local mapping would, each filed in the database first.
LoopClosingStats CloseLoops(test::LoopScene& scene, bool sequential, HookCounts* counts,
                            const LoopClosingOptions& options = {}) {
  KeyFrameDatabase database;
  StageTimings timings;
  LoopCloser closer(scene.GetMap(), database, options, sequential, CountingHooks(counts), &timings);
  for (int k = 0; k < scene.KeyFrameCount(); ++k) {
    database.Add(scene.KeyFrameAt(k));
    closer.InsertKeyFrame(scene.KeyFrameAt(k));
  }
  closer.Shutdown();
  const auto stages = timings.Summaries();
  EXPECT_EQ(stages.at("loop_detection").count, static_cast<std::size_t>(scene.KeyFrameCount()));
  return closer.Stats();
}

TEST(LoopCloserTest, SequentialClosesTheLoopOnceAndAdjustsTheMap) {
  test::LoopScene scene;
  const double drift_before = scene.MeanPositionError();
  HookCounts counts;
  const LoopClosingStats stats = CloseLoops(scene, /*sequential=*/true, &counts);
  EXPECT_EQ(stats.keyframes_processed, 16);
  EXPECT_EQ(stats.detections, 1);
  EXPECT_EQ(stats.rejected, 0);
  ASSERT_EQ(stats.corrections, 1);
  EXPECT_EQ(stats.global_bas, 1);
  ASSERT_EQ(stats.loops.size(), 1u);
  EXPECT_EQ(stats.loops[0].keyframe_id, scene.KeyFrameAt(14)->Id());
  EXPECT_GT(stats.loops[0].correction_m, 0.05);
  // Mapping was paused for the correction and for the merge, and released each time.
  EXPECT_EQ(counts.paused.load(), 2);
  EXPECT_EQ(counts.resumed.load(), 2);
  // Raised by both steps of the correction that write under the lock, and by the merge.
  EXPECT_EQ(scene.GetMap().CorrectionEpoch(), 3);
  EXPECT_LT(scene.MeanPositionError(), 0.35 * drift_before);
}

TEST(LoopCloserTest, ARejectedCandidateIsRecordedWithHowFarItGot) {
  test::LoopScene scene;
  HookCounts counts;
  LoopClosingOptions options;
  options.min_total_matches = 100000;  // the true loop cannot pass the last check
  const LoopClosingStats stats = CloseLoops(scene, /*sequential=*/true, &counts, options);
  // Not closed at keyframe 14, the loop is detected again at keyframe 15.
  EXPECT_EQ(stats.detections, 2);
  EXPECT_EQ(stats.rejected, 2);
  EXPECT_EQ(stats.corrections, 0);
  ASSERT_EQ(stats.rejections.size(), 2u);
  EXPECT_EQ(stats.rejections[1].keyframe_id, scene.KeyFrameAt(15)->Id());
  const LoopRejection& rejection = stats.rejections[0];
  EXPECT_EQ(rejection.keyframe_id, scene.KeyFrameAt(14)->Id());
  EXPECT_EQ(rejection.timestamp, scene.KeyFrameAt(14)->Timestamp());
  EXPECT_GE(rejection.candidates_tried, 1);
  // It got past the bag-of-words and RANSAC checks; only the match count stopped it.
  EXPECT_GE(rejection.best_bow_matches, options.min_bow_matches);
  EXPECT_GE(rejection.best_ransac_inliers, options.min_inliers);
  EXPECT_GT(rejection.best_total_matches, 0);
  EXPECT_LT(rejection.best_total_matches, options.min_total_matches);
  EXPECT_EQ(counts.paused.load(), 0);
}

TEST(LoopCloserTest, ThreadedFindsTheSameLoop) {
  test::LoopScene scene;
  HookCounts counts;
  const LoopClosingStats stats = CloseLoops(scene, /*sequential=*/false, &counts);
  EXPECT_EQ(stats.keyframes_processed, 16);
  EXPECT_EQ(stats.corrections, 1);
  // Shutdown waits for the global bundle adjustment; nothing interrupts it here.
  EXPECT_EQ(stats.global_bas, 1);
  EXPECT_EQ(counts.paused.load(), counts.resumed.load());
}

TEST(LoopCloserTest, DisabledOnlyCountsKeyFrames) {
  test::LoopScene scene;
  const double drift_before = scene.MeanPositionError();
  HookCounts counts;
  LoopClosingOptions options;
  options.enabled = false;
  KeyFrameDatabase database;
  LoopCloser closer(scene.GetMap(), database, options, true, CountingHooks(&counts));
  for (int k = 0; k < scene.KeyFrameCount(); ++k) {
    database.Add(scene.KeyFrameAt(k));
    closer.InsertKeyFrame(scene.KeyFrameAt(k));
  }
  EXPECT_EQ(closer.Stats().keyframes_processed, 16);
  EXPECT_EQ(closer.Stats().corrections, 0);
  EXPECT_EQ(counts.paused.load(), 0);
  EXPECT_DOUBLE_EQ(scene.MeanPositionError(), drift_before);
}

TEST(LoopCloserTest, NoCorrectionWithoutRevisit) {
  test::LoopSceneOptions scene_options;
  scene_options.revisit = false;
  test::LoopScene scene(scene_options);
  HookCounts counts;
  LoopClosingOptions options;
  options.min_keyframes_between = 2;
  const LoopClosingStats stats = CloseLoops(scene, true, &counts, options);
  EXPECT_EQ(stats.corrections, 0);
  EXPECT_EQ(counts.paused.load(), 0);
}

TEST(LoopCloserTest, BadOptionsThrow) {
  Map map;
  KeyFrameDatabase database;
  LoopClosingOptions options;
  options.min_inliers = 0;
  EXPECT_THROW(LoopCloser(map, database, options, true, {}), Error);
}

}  // namespace
}  // namespace drvslam
