#include "drvslam/semantic/yolo_decode.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"
#include "drvslam/semantic/mask_propagator.h"

namespace drvslam {
namespace {

// (4 box rows + 3 classes + 2 coefficients) x anchors, all zero.
cv::Mat EmptyPredictions(int anchors) { return cv::Mat::zeros(4 + 3 + 2, anchors, CV_32F); }

void SetAnchor(cv::Mat& p, int anchor, cv::Vec4f cxcywh, cv::Vec3f scores) {
  for (int r = 0; r < 4; ++r) p.at<float>(r, anchor) = cxcywh[r];
  for (int c = 0; c < 3; ++c) p.at<float>(4 + c, anchor) = scores[c];
}

TEST(DecodeCandidatesTest, KeepsEachAnchorsBestClassAboveTheThreshold) {
  cv::Mat p = EmptyPredictions(4);
  SetAnchor(p, 0, {100, 50, 20, 40}, {0.1f, 0.8f, 0.3f});
  SetAnchor(p, 1, {10, 10, 4, 4}, {0.2f, 0.2f, 0.24f});  // below 0.25
  SetAnchor(p, 2, {60, 70, 30, 10}, {0.9f, 0.0f, 0.95f});
  SetAnchor(p, 3, {60, 70, 0, 10}, {0.9f, 0.0f, 0.0f});  // degenerate box
  const std::vector<YoloCandidate> found = DecodeCandidates(p, 3, 0.25f);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found[0].anchor, 0);
  EXPECT_EQ(found[0].class_id, 1);
  EXPECT_FLOAT_EQ(found[0].score, 0.8f);
  EXPECT_DOUBLE_EQ(found[0].box.x, 90.0);
  EXPECT_DOUBLE_EQ(found[0].box.y, 30.0);
  EXPECT_DOUBLE_EQ(found[0].box.width, 20.0);
  EXPECT_DOUBLE_EQ(found[0].box.height, 40.0);
  EXPECT_EQ(found[1].anchor, 2);
  EXPECT_EQ(found[1].class_id, 2);
  EXPECT_THROW(DecodeCandidates(p, 10, 0.25f), Error);
}

TEST(ClassAwareNmsTest, OverlappingBoxesOfDifferentClassesAreBothKept) {
  // IoU of the first two is 0.81: a person holding a phone-shaped box.
  const std::vector<cv::Rect2d> boxes = {{0, 0, 100, 100}, {5, 5, 90, 90}, {200, 0, 50, 50}};
  const std::vector<float> scores = {0.7f, 0.9f, 0.5f};
  const std::vector<int> different = {0, 67, 0};
  EXPECT_EQ(ClassAwareNms(boxes, scores, different, 0.45f, 100), (std::vector<int>{1, 0, 2}));
  const std::vector<int> same = {0, 0, 0};
  EXPECT_EQ(ClassAwareNms(boxes, scores, same, 0.45f, 100), (std::vector<int>{1, 2}));
  // A looser IoU threshold keeps both.
  EXPECT_EQ(ClassAwareNms(boxes, scores, same, 0.85f, 100), (std::vector<int>{1, 0, 2}));
  EXPECT_EQ(ClassAwareNms(boxes, scores, different, 0.45f, 2), (std::vector<int>{1, 0}));
  EXPECT_TRUE(ClassAwareNms({}, {}, {}, 0.45f, 10).empty());
  EXPECT_THROW(ClassAwareNms(boxes, scores, {0}, 0.45f, 10), Error);
}

TEST(ClassAwareNmsTest, ChainsSuppressOnlyFromKeptBoxes) {
  // B overlaps A and C, but A and C do not overlap: A suppresses B, so C survives.
  const std::vector<cv::Rect2d> boxes = {{0, 0, 10, 10}, {4, 0, 10, 10}, {8, 0, 10, 10}};
  const std::vector<float> scores = {0.9f, 0.8f, 0.7f};
  EXPECT_EQ(ClassAwareNms(boxes, scores, {3, 3, 3}, 0.3f, 10), (std::vector<int>{0, 2}));
}

// Two prototype channels on an 8 x 10 grid: +8 in the left half / top half, -8 elsewhere.
cv::Mat HalfPlanePrototypes() {
  const int sizes[] = {1, 2, 8, 10};
  cv::Mat protos(4, sizes, CV_32F);
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 10; ++x) {
      protos.at<float>(cv::Vec4i(0, 0, y, x)) = x < 5 ? 8.0f : -8.0f;
      protos.at<float>(cv::Vec4i(0, 1, y, x)) = y < 4 ? 8.0f : -8.0f;
    }
  }
  return protos;
}

TEST(MaskDecodeTest, ProbabilitiesAreSigmoidOfCoefficientsTimesPrototypes) {
  const cv::Mat protos = HalfPlanePrototypes();
  const cv::Mat coefficients = (cv::Mat_<float>(3, 2) << 1, 0, 0, 1, 0.5f, 0.5f);
  const std::vector<cv::Mat> masks = MaskProbabilities(coefficients, protos, cv::Size(10, 8));
  ASSERT_EQ(masks.size(), 3u);
  const auto sigmoid = [](double v) { return 1.0 / (1.0 + std::exp(-v)); };
  EXPECT_NEAR(masks[0].at<float>(3, 2), sigmoid(8), 1e-6);
  EXPECT_NEAR(masks[0].at<float>(3, 7), sigmoid(-8), 1e-6);
  EXPECT_NEAR(masks[1].at<float>(1, 7), sigmoid(8), 1e-6);
  EXPECT_NEAR(masks[1].at<float>(6, 2), sigmoid(-8), 1e-6);
  // Top-left quadrant +8, top-right and bottom-left 0, bottom-right -8.
  EXPECT_NEAR(masks[2].at<float>(0, 0), sigmoid(8), 1e-6);
  EXPECT_NEAR(masks[2].at<float>(0, 9), 0.5, 1e-6);
  EXPECT_NEAR(masks[2].at<float>(7, 9), sigmoid(-8), 1e-6);
  EXPECT_THROW(MaskProbabilities(coefficients, protos, cv::Size(10, 9)), Error);
}

TEST(MaskDecodeTest, PrototypeMaskMapsBackThroughTheLetterboxAndIsCroppedToTheBox) {
  // A 640x480 image seen by a 320x256 model: content rows 8..247, prototypes 80x64 (a quarter).
  const Letterbox letterbox({640, 480}, {320, 256});
  const cv::Rect truth(200, 120, 240, 200);  // image pixels
  cv::Mat probabilities(64, 80, CV_32F);
  for (int py = 0; py < 64; ++py) {
    for (int px = 0; px < 80; ++px) {
      // Centre of the prototype cell in input pixels, then in image pixels.
      const cv::Point2d image_point = letterbox.InputToImage({(px + 0.5) * 4.0, (py + 0.5) * 4.0});
      probabilities.at<float>(py, px) = truth.contains(image_point) ? 0.95f : 0.05f;
    }
  }
  cv::Mat expected = cv::Mat::zeros(480, 640, CV_8UC1);
  expected(truth).setTo(255);

  const cv::Mat whole = ProbabilitiesToImageMask(probabilities, letterbox, {0, 0, 640, 480}, 0.5f);
  ASSERT_EQ(whole.size(), cv::Size(640, 480));
  ASSERT_EQ(whole.type(), CV_8UC1);
  // Prototype cells are 8 image pixels wide: edges may be off by up to half a cell.
  EXPECT_GT(MaskIoU(whole, expected), 0.95);
  const cv::Rect found = cv::boundingRect(whole);
  EXPECT_NEAR(found.x, truth.x, 4);
  EXPECT_NEAR(found.y, truth.y, 4);
  EXPECT_NEAR(found.br().x, truth.br().x, 4);
  EXPECT_NEAR(found.br().y, truth.br().y, 4);

  // Cropping: nothing outside the given box, everything inside it that the truth covers.
  const cv::Rect crop(300, 100, 100, 300);
  const cv::Mat cropped = ProbabilitiesToImageMask(probabilities, letterbox, crop, 0.5f);
  cv::Mat outside = cropped.clone();
  outside(crop).setTo(0);
  EXPECT_EQ(cv::countNonZero(outside), 0);
  const cv::Rect both = crop & truth;
  const cv::Rect inner(both.x + 5, both.y + 5, both.width - 10, both.height - 10);
  EXPECT_EQ(cv::countNonZero(cropped(inner) == 0), 0);
  // Values are only 0 and 255.
  EXPECT_EQ(cv::countNonZero((cropped != 0) & (cropped != 255)), 0);
}

}  // namespace
}  // namespace drvslam
