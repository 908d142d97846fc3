#include "drvslam/feature/gaussian_smoothing.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

cv::Mat Noise(cv::Size size, int seed) {
  cv::Mat image(size, CV_8UC1);
  cv::RNG rng(seed);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  return image;
}

TEST(GaussianSmoothingTest, WithinOneGreyLevelOfOpenCv) {
  std::vector<uint16_t> buffer;
  for (const cv::Size size : {cv::Size(640, 480), cv::Size(37, 23), cv::Size(16, 16),
                              cv::Size(5, 9), cv::Size(1, 1), cv::Size(2, 7)}) {
    const cv::Mat src = Noise(size, size.area());
    cv::Mat ours;
    cv::Mat reference;
    SmoothGaussian7(src, &ours, &buffer);
    cv::GaussianBlur(src, reference, cv::Size(7, 7), 2.0, 2.0, cv::BORDER_REFLECT_101);
    ASSERT_EQ(ours.size(), src.size());
    EXPECT_LE(cv::norm(ours, reference, cv::NORM_INF), 1.0) << size;
  }
}

TEST(GaussianSmoothingTest, KeepsFlatImagesAndReadsViews) {
  std::vector<uint16_t> buffer;
  cv::Mat flat(50, 70, CV_8UC1, cv::Scalar(255));
  cv::Mat out;
  SmoothGaussian7(flat, &out, &buffer);
  EXPECT_EQ(cv::norm(out, flat, cv::NORM_INF), 0.0);
  const cv::Mat big = Noise(cv::Size(200, 100), 5);
  const cv::Mat view = big(cv::Rect(13, 7, 101, 61));
  cv::Mat from_view, from_copy;
  SmoothGaussian7(view, &from_view, &buffer);
  SmoothGaussian7(view.clone(), &from_copy, &buffer);
  EXPECT_EQ(cv::norm(from_view, from_copy, cv::NORM_INF), 0.0);
}

TEST(GaussianSmoothingTest, RejectsInPlaceAndOtherTypes) {
  std::vector<uint16_t> buffer;
  cv::Mat image = Noise(cv::Size(20, 20), 1);
  EXPECT_THROW(SmoothGaussian7(image, &image, &buffer), Error);
  cv::Mat out;
  EXPECT_THROW(SmoothGaussian7(cv::Mat(10, 10, CV_16UC1), &out, &buffer), Error);
}

}  // namespace
}  // namespace drvslam
