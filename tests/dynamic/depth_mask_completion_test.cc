// Depth completion of instance masks: the body parts a network's mask misses are added when
// they are depth-connected to the mask at about its depth, inside the grown box; the wall behind
// and pixels without depth are not.
#include "drvslam/dynamic/depth_mask_completion.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

// A 200x200 scene: a wall at 4 m, a "person" at 2 m (a torso 60x100 at (70, 40) and an arm
// 40x10 at (130, 60), both at 2 m with a gentle slope), and the network's mask on the torso only.
struct CompletionScene {
  cv::Mat depth = cv::Mat(200, 200, CV_32FC1, cv::Scalar(4.0f));
  Instance person;
  CompletionScene() {
    for (int y = 40; y < 140; ++y) {
      for (int x = 70; x < 130; ++x) depth.at<float>(y, x) = 2.0f + 0.001f * (x - 70);
    }
    for (int y = 60; y < 70; ++y) {
      for (int x = 130; x < 170; ++x) depth.at<float>(y, x) = 2.06f + 0.001f * (x - 130);
    }
    person.class_id = 0;
    person.class_name = "person";
    person.box = cv::Rect(70, 40, 60, 100);
    person.mask = cv::Mat::zeros(depth.size(), CV_8UC1);
    person.mask(person.box).setTo(255);
  }
};

TEST(DepthMaskCompletionTest, TheMissedArmJoinsTheMaskAndTheWallDoesNot) {
  CompletionScene scene;
  MaskCompletionOptions options;
  options.margin = 0.7;  // the arm reaches 40 px past a 60 px wide box
  const int added = CompleteMaskWithDepth(scene.person, scene.depth, options);
  EXPECT_EQ(added, 40 * 10);
  EXPECT_EQ(cv::countNonZero(scene.person.mask(cv::Rect(130, 60, 40, 10))), 400);
  EXPECT_EQ(cv::countNonZero(scene.person.mask), 60 * 100 + 400);
  EXPECT_EQ(scene.person.box, cv::Rect(70, 40, 100, 100));
}

TEST(DepthMaskCompletionTest, GrowthStaysInsideTheGrownBoxAndNeedsDepth) {
  CompletionScene scene;
  MaskCompletionOptions options;
  options.margin = 0.25;  // 15 px: only the arm's first 15 columns
  EXPECT_EQ(CompleteMaskWithDepth(scene.person, scene.depth, options), 15 * 10);
  CompletionScene holes;
  holes.depth(cv::Rect(130, 60, 1, 10)).setTo(0.0f);  // no depth where the arm meets the body
  options.margin = 0.7;
  EXPECT_EQ(CompleteMaskWithDepth(holes.person, holes.depth, options), 0);
  // A step larger than completionDepthStep ends the surface.
  CompletionScene step;
  step.depth(cv::Rect(130, 60, 40, 10)) += 0.1f;
  EXPECT_EQ(CompleteMaskWithDepth(step.person, step.depth, options), 0);
}

TEST(DepthMaskCompletionTest, WithoutDepthOnTheMaskNothingChangesAndBadInputThrows) {
  CompletionScene scene;
  scene.depth.setTo(0.0f);
  const cv::Mat before = scene.person.mask.clone();
  EXPECT_EQ(CompleteMaskWithDepth(scene.person, scene.depth, MaskCompletionOptions()), 0);
  EXPECT_EQ(cv::countNonZero(before != scene.person.mask), 0);
  cv::Mat wrong(10, 10, CV_32FC1, cv::Scalar(1.0f));
  EXPECT_THROW(CompleteMaskWithDepth(scene.person, wrong, MaskCompletionOptions()), Error);
}

}  // namespace
}  // namespace drvslam
