#include "drvslam/feature/descriptor_distance.h"

#include <gtest/gtest.h>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

int CountBitsOneByOne(const cv::Mat& a, const cv::Mat& b) {
  int bits = 0;
  for (int i = 0; i < 32; ++i) {
    for (int k = 0; k < 8; ++k)
      bits += ((a.at<uint8_t>(0, i) >> k) & 1) != ((b.at<uint8_t>(0, i) >> k) & 1);
  }
  return bits;
}

TEST(DescriptorDistanceTest, MatchesBitByBitCount) {
  cv::RNG rng(42);
  cv::Mat rows(200, 32, CV_8UC1);
  rng.fill(rows, cv::RNG::UNIFORM, 0, 256);
  for (int i = 0; i + 1 < rows.rows; ++i) {
    const cv::Mat a = rows.row(i);
    const cv::Mat b = rows.row(i + 1);
    EXPECT_EQ(DescriptorDistance(a, b), CountBitsOneByOne(a, b)) << i;
    EXPECT_EQ(DescriptorDistance(a, b), cv::norm(a, b, cv::NORM_HAMMING)) << i;
    EXPECT_EQ(DescriptorDistance(a.ptr<uint8_t>(), b.ptr<uint8_t>()), CountBitsOneByOne(a, b));
  }
}

TEST(DescriptorDistanceTest, Extremes) {
  const cv::Mat zeros = cv::Mat::zeros(1, 32, CV_8UC1);
  const cv::Mat ones(1, 32, CV_8UC1, cv::Scalar(255));
  cv::Mat one_bit = zeros.clone();
  one_bit.at<uint8_t>(0, 31) = 0x80;
  EXPECT_EQ(DescriptorDistance(zeros, zeros), 0);
  EXPECT_EQ(DescriptorDistance(zeros, ones), 256);
  EXPECT_EQ(DescriptorDistance(ones, zeros), 256);
  EXPECT_EQ(DescriptorDistance(zeros, one_bit), 1);
}

TEST(DescriptorDistanceTest, UnalignedRowsOfAWiderMatrix) {
  // Rows starting at odd addresses (a column range of a wider matrix).
  cv::Mat wide(2, 33, CV_8UC1, cv::Scalar(0));
  wide.at<uint8_t>(1, 1) = 0x0F;
  const cv::Mat a = wide(cv::Rect(1, 0, 32, 1));
  const cv::Mat b = wide(cv::Rect(1, 1, 32, 1));
  EXPECT_EQ(DescriptorDistance(a, b), 4);
}

TEST(DescriptorDistanceTest, RejectsOtherShapes) {
  const cv::Mat good = cv::Mat::zeros(1, 32, CV_8UC1);
  EXPECT_THROW(DescriptorDistance(good, cv::Mat::zeros(1, 31, CV_8UC1)), Error);
  EXPECT_THROW(DescriptorDistance(cv::Mat::zeros(2, 32, CV_8UC1), good), Error);
  EXPECT_THROW(DescriptorDistance(good, cv::Mat::zeros(1, 8, CV_32SC1)), Error);
  EXPECT_THROW(DescriptorDistance(good, cv::Mat()), Error);
}

}  // namespace
}  // namespace drvslam
