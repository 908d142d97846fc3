#include "drvslam/semantic/letterbox.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <string>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

struct SizePair {
  cv::Size image;
  cv::Size input;
  cv::Rect content;  // expected
};

class LetterboxSizes : public ::testing::TestWithParam<SizePair> {};

TEST_P(LetterboxSizes, ContentFitsCentredAndRoundTripsExactly) {
  const SizePair& p = GetParam();
  const Letterbox letterbox(p.image, p.input);
  EXPECT_EQ(letterbox.Content(), p.content);
  // The content's corners are the image's corners.
  const cv::Point2d origin = letterbox.InputToImage(cv::Point2d(p.content.tl()));
  const cv::Point2d far = letterbox.InputToImage(cv::Point2d(p.content.br()));
  EXPECT_NEAR(origin.x, 0.0, 1e-9);
  EXPECT_NEAR(origin.y, 0.0, 1e-9);
  EXPECT_NEAR(far.x, p.image.width, 1e-9);
  EXPECT_NEAR(far.y, p.image.height, 1e-9);

  cv::RNG rng(7);
  for (int i = 0; i < 200; ++i) {
    const cv::Point2d image_point(rng.uniform(0.0, double(p.image.width)),
                                  rng.uniform(0.0, double(p.image.height)));
    const cv::Point2d input_point = letterbox.ImageToInput(image_point);
    EXPECT_TRUE(cv::Rect2d(p.content).contains(input_point) || input_point.x == p.content.br().x ||
                input_point.y == p.content.br().y);
    const cv::Point2d back = letterbox.InputToImage(input_point);
    EXPECT_NEAR(back.x, image_point.x, 1e-9);
    EXPECT_NEAR(back.y, image_point.y, 1e-9);
  }
  // The affine form agrees with the point form.
  const cv::Matx23d affine = letterbox.ImageToInputAffine();
  const cv::Point2d q(p.image.width * 0.3, p.image.height * 0.7);
  const cv::Point2d mapped = letterbox.ImageToInput(q);
  EXPECT_NEAR(affine(0, 0) * q.x + affine(0, 2), mapped.x, 1e-9);
  EXPECT_NEAR(affine(1, 1) * q.y + affine(1, 2), mapped.y, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(NonSquare, LetterboxSizes,
                         ::testing::Values(
                             // TUM frames into the two shared models.
                             SizePair{{640, 480}, {320, 256}, {0, 8, 320, 240}},
                             SizePair{{640, 480}, {640, 480}, {0, 0, 640, 480}},
                             // vtest.avi and messi5.jpg.
                             SizePair{{768, 576}, {320, 256}, {0, 8, 320, 240}},
                             SizePair{{548, 342}, {640, 480}, {0, 40, 640, 399}},
                             // Portrait and very wide images: padding on the other axis.
                             SizePair{{300, 700}, {320, 256}, {105, 0, 110, 256}},
                             SizePair{{1000, 100}, {640, 480}, {0, 208, 640, 64}},
                             // Upscaling a small image.
                             SizePair{{160, 120}, {640, 480}, {0, 0, 640, 480}}),
                         [](const ::testing::TestParamInfo<SizePair>& info) {
                           const SizePair& p = info.param;
                           return std::to_string(p.image.width) + "x" +
                                  std::to_string(p.image.height) + "_to_" +
                                  std::to_string(p.input.width) + "x" +
                                  std::to_string(p.input.height);
                         });

TEST(LetterboxTest, ApplyPadsWithGreyAndScalesTheImageIntoTheContent) {
  const Letterbox letterbox({640, 480}, {320, 256});
  const cv::Mat image(480, 640, CV_8UC3, cv::Scalar(10, 20, 30));
  const cv::Mat input = letterbox.Apply(image);
  ASSERT_EQ(input.size(), cv::Size(320, 256));
  EXPECT_EQ(input.at<cv::Vec3b>(0, 0), cv::Vec3b(114, 114, 114));
  EXPECT_EQ(input.at<cv::Vec3b>(255, 319), cv::Vec3b(114, 114, 114));
  EXPECT_EQ(input.at<cv::Vec3b>(8, 0), cv::Vec3b(10, 20, 30));
  EXPECT_EQ(input.at<cv::Vec3b>(247, 319), cv::Vec3b(10, 20, 30));
  EXPECT_EQ(input.at<cv::Vec3b>(248, 100), cv::Vec3b(114, 114, 114));
}

TEST(LetterboxTest, BoxesInPaddingAreClippedToTheImage) {
  const Letterbox letterbox({640, 480}, {320, 256});
  // 10 input pixels above the content and 20 below the top: image rows 0..24 after clipping.
  const cv::Rect box = letterbox.InputBoxToImage(cv::Rect2d(-5, -2, 50, 22));
  EXPECT_EQ(box, cv::Rect(0, 0, 90, 24));
  EXPECT_TRUE(letterbox.InputBoxToImage(cv::Rect2d(10, 0, 20, 5)).empty());
}

TEST(LetterboxTest, RejectsBadSizes) {
  EXPECT_THROW(Letterbox({0, 480}, {320, 256}), Error);
  EXPECT_THROW(Letterbox({640, 480}, {320, -1}), Error);
  const Letterbox letterbox({640, 480}, {320, 256});
  EXPECT_THROW(letterbox.Apply(cv::Mat(100, 100, CV_8UC3)), Error);
}

}  // namespace
}  // namespace drvslam
