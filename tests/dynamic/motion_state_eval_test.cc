// Motion-state scores: precision and recall are undefined (JSON null), not perfect, when there is
// nothing to score.
#include "drvslam/tools/truth/motion_state_eval.h"

#include <gtest/gtest.h>

namespace drvslam {
namespace {

TEST(ConfusionTest, CountsGiveTheTextbookRatios) {
  Confusion c;
  c.Add(true, true);    // tp
  c.Add(true, true);    // tp
  c.Add(false, true);   // fp
  c.Add(true, false);   // fn
  c.Add(false, false);  // tn
  const nlohmann::json json = ConfusionJson(c);
  EXPECT_EQ(json["tp"], 2);
  EXPECT_EQ(json["fp"], 1);
  EXPECT_EQ(json["fn"], 1);
  EXPECT_EQ(json["tn"], 1);
  EXPECT_NEAR(json["precision"].get<double>(), 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(json["recall"].get<double>(), 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(json["accuracy"].get<double>(), 3.0 / 5.0, 1e-12);
}

TEST(ConfusionTest, NothingScoredIsUndefinedNotPerfect) {
  const nlohmann::json json = ConfusionJson(Confusion{});
  EXPECT_TRUE(json["precision"].is_null()) << json.dump();
  EXPECT_TRUE(json["recall"].is_null()) << json.dump();
  EXPECT_TRUE(json["accuracy"].is_null()) << json.dump();
}

TEST(ConfusionTest, NothingJudgedMovingLeavesPrecisionUndefined) {
  Confusion c;
  c.Add(true, false);   // a moving object missed
  c.Add(false, false);  // a still one kept
  const nlohmann::json json = ConfusionJson(c);
  EXPECT_TRUE(json["precision"].is_null()) << json.dump();
  EXPECT_NEAR(json["recall"].get<double>(), 0.0, 1e-12);
  EXPECT_NEAR(json["accuracy"].get<double>(), 0.5, 1e-12);
}

TEST(ConfusionTest, NothingMovingLeavesRecallUndefined) {
  Confusion c;
  c.Add(false, true);  // a still object judged moving
  const nlohmann::json json = ConfusionJson(c);
  EXPECT_NEAR(json["precision"].get<double>(), 0.0, 1e-12);
  EXPECT_TRUE(json["recall"].is_null()) << json.dump();
}

TEST(MotionStateScoresTest, EmptyScoresWriteNullForEveryRule) {
  const nlohmann::json json = MotionStateScoresJson(MotionStateScores{});
  EXPECT_EQ(json["judged"], 0);
  for (const char* rule :
       {"delta_rule", "share_rule", "reprojection_rule", "combined_rule", "shipped"}) {
    EXPECT_TRUE(json[rule]["precision"].is_null()) << rule;
    EXPECT_TRUE(json[rule]["recall"].is_null()) << rule;
  }
}

}  // namespace
}  // namespace drvslam
