// Depth agreement and the tentative window: the map points a keyframe of a photographed plane
// made agree with a frame's depth at its true pose; moved 30 cm along the view, or with the
// surface measured 1 m farther (the camera sees through where the map has points), they do not.
// Points tracking rarely finds where they are predicted (a mover that left) do not testify. A
// pose found again is verified after LocalizationCheck::kConfirmFrames agreeing frames.
#include "drvslam/tracking/depth_agreement.h"

#include <gtest/gtest.h>

#include "drvslam/tracking/localization_check.h"
#include "plane_views.h"
#include "test_support/missing_data.h"

namespace drvslam {
namespace {

class DepthAgreementTest : public ::testing::Test {
 protected:
  void SetUp() override {
    photo_ = test::LoadPhoto("graf1.png");
    if (photo_.empty()) DRVSLAM_MISSING_TEST_DATA() << "graf1.png missing";
    if (!scene_.LoadVocabulary()) DRVSLAM_MISSING_TEST_DATA() << "no default vocabulary";
    keyframe_ = scene_.MakeKeyFrame(photo_, SE3::Identity());
    ASSERT_TRUE(keyframe_);
  }

  test::PlaneScene scene_;
  cv::Mat photo_;
  std::shared_ptr<KeyFrame> keyframe_;
};

TEST_F(DepthAgreementTest, AgreesAtTheTruePoseOnly) {
  const SE3 truth = test::ViewPose(0.02, -0.03, 0.01, 0.1, -0.05, 0.1);
  const test::PlaneView view = test::RenderPlaneView(photo_, scene_.settings.camera, truth);
  Frame frame = scene_.factory.Build(1.0, view.bgr, view.depth);
  const auto points = keyframe_->MapPoints();

  frame.SetPose(truth);
  const DepthAgreement right = MeasureDepthAgreement(frame, view.depth, points);
  EXPECT_GT(right.expected, 200);
  EXPECT_GT(right.AgreeShare(), 0.95);
  EXPECT_TRUE(DepthAgrees(right));

  // 30 cm nearer the plane than it is: every point is predicted 30 cm too near.
  frame.SetPose(test::ViewPose(0.02, -0.03, 0.01, 0.1, -0.05, -0.2));
  const DepthAgreement moved = MeasureDepthAgreement(frame, view.depth, points);
  EXPECT_LT(moved.AgreeShare(), 0.1);
  EXPECT_GT(moved.MissingShare(), 0.9);
  EXPECT_FALSE(DepthAgrees(moved));

  // The true pose, but the surface measured 1 m behind the map's points.
  frame.SetPose(truth);
  const cv::Mat farther = view.depth + 1.0;
  const DepthAgreement through = MeasureDepthAgreement(frame, farther, points);
  EXPECT_EQ(through.agree, 0);
  EXPECT_EQ(through.missing, through.Measured());
  EXPECT_FALSE(DepthAgrees(through));

  // Without a depth image there is no evidence: the pose passes.
  const DepthAgreement none = MeasureDepthAgreement(frame, cv::Mat(), points);
  EXPECT_EQ(none.Measured(), 0);
  EXPECT_TRUE(DepthAgrees(none));
}

TEST_F(DepthAgreementTest, PointsRarelyFoundWhereExpectedDoNotTestify) {
  const SE3 truth = test::ViewPose(0.02, -0.03, 0.01, 0.1, -0.05, 0.1);
  const test::PlaneView view = test::RenderPlaneView(photo_, scene_.settings.camera, truth);
  Frame frame = scene_.factory.Build(1.0, view.bgr, view.depth);
  frame.SetPose(truth);
  const auto points = keyframe_->MapPoints();
  // What the map had on the right half of the view has gone: the depth there is 1 m farther,
  // as where a mapped person walked off.
  const int half = view.depth.cols / 2;
  cv::Mat depth = view.depth.clone();
  depth.colRange(half, depth.cols) += 1.0;
  const DepthAgreement before = MeasureDepthAgreement(frame, depth, points);
  EXPECT_GT(before.MissingShare(), 0.3);
  EXPECT_FALSE(DepthAgrees(before));

  // Those points were predicted visible in 10 more frames and found in 2 (a found ratio near
  // 0.2); half the others found in 10 of 10, the rest as the keyframe left them.
  std::vector<std::shared_ptr<MapPoint>> gone;
  const PinholeCamera& camera = frame.Geometry().camera;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i] || points[i]->IsBad()) continue;
    const Eigen::Vector3d p = truth * points[i]->Position();
    const bool right = camera.Fx() * p.x() / p.z() + camera.Cx() >= half;
    if (right) {
      points[i]->IncreaseVisible(10);
      points[i]->IncreaseFound(2);
      gone.push_back(points[i]);
    } else if (i % 2 == 0) {
      points[i]->IncreaseVisible(10);
      points[i]->IncreaseFound(10);
    }
  }
  ASSERT_GT(gone.size(), 50u);
  const DepthAgreement after = MeasureDepthAgreement(frame, depth, points);
  EXPECT_LT(after.MissingShare(), 0.05);
  EXPECT_GT(after.AgreeShare(), 0.9);
  EXPECT_LT(after.expected, before.expected - static_cast<int>(gone.size()) / 2);
  EXPECT_TRUE(DepthAgrees(after));

  // Found as often as predicted, they testify again.
  for (const auto& point : gone) point->IncreaseFound(point->Visible() - point->Found());
  EXPECT_FALSE(DepthAgrees(MeasureDepthAgreement(frame, depth, points)));
}

TEST(LocalizationCheckTest, VerifiedAfterConsecutiveAgreeingFrames) {
  LocalizationCheck check;
  EXPECT_EQ(check.Quality(true), LocalizationQuality::kVerified);
  DepthAgreement good;
  good.agree = 90;
  good.occluded = 10;
  DepthAgreement bad;
  bad.agree = 30;
  bad.missing = 70;

  check.Start();
  for (int k = 1; k < LocalizationCheck::kConfirmFrames; ++k) {
    EXPECT_TRUE(check.Confirm(good));
    EXPECT_EQ(check.Quality(true), LocalizationQuality::kTentative) << "frame " << k;
  }
  EXPECT_TRUE(check.Confirm(good));
  EXPECT_EQ(check.Quality(true), LocalizationQuality::kVerified);
  EXPECT_EQ(check.Verified(), 1);

  check.Start();
  EXPECT_TRUE(check.Confirm(good));
  EXPECT_FALSE(check.Confirm(bad));
  EXPECT_EQ(check.LastRejection(), LocalizationRejection::kDepthDisagrees);
  EXPECT_EQ(check.DepthRejections(), 1);
  EXPECT_FALSE(check.Pending());

  check.Start();
  check.Fail();
  EXPECT_EQ(check.LastRejection(), LocalizationRejection::kNotConfirmed);
  EXPECT_EQ(check.UnconfirmedRejections(), 1);
  EXPECT_EQ(check.Quality(false), LocalizationQuality::kLost);
  EXPECT_EQ(check.Verified(), 1);
}

}  // namespace
}  // namespace drvslam
