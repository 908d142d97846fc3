#include "drvslam/loop/loop_detector.h"

#include <gtest/gtest.h>

#include "loop_scene.h"

namespace drvslam {
namespace {

// Feeds the scene's keyframes in order, as loop closing receives them; returns, per keyframe,
// the ids of the consistent candidates.
std::vector<std::vector<long>> Detections(test::LoopScene& scene, const LoopDetectorRules& rules) {
  KeyFrameDatabase database;
  LoopDetector detector(database, rules);
  std::vector<std::vector<long>> found;
  for (int k = 0; k < scene.KeyFrameCount(); ++k) {
    database.Add(scene.KeyFrameAt(k));
    std::vector<long> ids;
    for (const auto& candidate : detector.Detect(scene.KeyFrameAt(k), k + 1).consistent) {
      ids.push_back(candidate->Id());
    }
    found.push_back(ids);
  }
  return found;
}

TEST(LoopDetectorTest, RevisitIsConfirmedAfterConsistentKeyFrames) {
  test::LoopScene scene;
  LoopDetectorRules rules;
  rules.min_consistency = 3;
  rules.min_keyframes_between = 10;
  const auto found = Detections(scene, rules);
  ASSERT_EQ(found.size(), 16u);
  // Keyframe 11 is the first to see the start again (its candidate group starts at 0
  // consistency); keyframes 12, 13 and 14 confirm it, and 14 reports the loop.
  for (int k = 0; k < 14; ++k) EXPECT_TRUE(found[k].empty()) << "keyframe " << k;
  ASSERT_FALSE(found[14].empty());
  // Keyframe 14 looks where keyframe 2 (and partly 1, 3) looked on the first turn.
  EXPECT_GE(found[14].front(), 1);
  EXPECT_LE(found[14].front(), 4);
}

TEST(LoopDetectorTest, FewerConsistentKeyFramesConfirmSooner) {
  test::LoopScene scene;
  LoopDetectorRules rules;
  rules.min_consistency = 1;
  const auto found = Detections(scene, rules);
  for (int k = 0; k < 12; ++k) EXPECT_TRUE(found[k].empty()) << "keyframe " << k;
  EXPECT_FALSE(found[12].empty());
}

TEST(LoopDetectorTest, NoLoopWithoutRevisit) {
  test::LoopSceneOptions options;
  options.revisit = false;
  test::LoopScene scene(options);
  LoopDetectorRules rules;
  rules.min_consistency = 0;  // every candidate would count
  rules.min_keyframes_between = 2;
  for (const auto& ids : Detections(scene, rules)) EXPECT_TRUE(ids.empty());
}

TEST(LoopDetectorTest, NoSearchRightAfterAClosedLoop) {
  test::LoopScene scene;
  KeyFrameDatabase database;
  LoopDetectorRules rules;
  rules.min_consistency = 0;
  rules.min_keyframes_between = 5;
  LoopDetector detector(database, rules);
  for (int k = 0; k < scene.KeyFrameCount(); ++k) database.Add(scene.KeyFrameAt(k));
  detector.LoopClosed(12);
  EXPECT_FALSE(detector.Detect(scene.KeyFrameAt(13), 14).searched);
  EXPECT_TRUE(detector.Detect(scene.KeyFrameAt(13), 18).searched);
}

}  // namespace
}  // namespace drvslam
