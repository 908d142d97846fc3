#include "drvslam/feature/steered_brief.h"

#include <gtest/gtest.h>

#include <cmath>

#include "drvslam/feature/brief_pattern.h"

namespace drvslam {
namespace {

cv::Mat NoiseImage(int seed) {
  cv::Mat image(64, 80, CV_8UC1);
  cv::RNG rng(seed);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  return image;
}

// Moments summed pixel by pixel over the disc u^2 + v^2 <= 225.
float ReferenceAngle(const cv::Mat& image, int x, int y) {
  long m10 = 0, m01 = 0;
  for (int v = -15; v <= 15; ++v) {
    for (int u = -15; u <= 15; ++u) {
      if (u * u + v * v > 225) continue;
      m10 += u * image.at<uint8_t>(y + v, x + u);
      m01 += v * image.at<uint8_t>(y + v, x + u);
    }
  }
  float angle = std::atan2(static_cast<float>(m01), static_cast<float>(m10)) * 57.29577951308232f;
  if (angle < 0) angle += 360.0f;
  return angle >= 360.0f ? 0.0f : angle;
}

TEST(SteeredBriefTest, CentroidAngleMatchesPixelByPixelMoments) {
  for (int seed = 0; seed < 20; ++seed) {
    const cv::Mat image = NoiseImage(seed);
    for (const cv::Point p : {cv::Point(15, 15), cv::Point(63, 48), cv::Point(40, 30)}) {
      EXPECT_EQ(IntensityCentroidAngle(image, p.x, p.y), ReferenceAngle(image, p.x, p.y))
          << "seed " << seed << " at " << p;
    }
  }
}

TEST(SteeredBriefTest, CentroidPointsAtTheBrightSide) {
  cv::Mat image(64, 64, CV_8UC1, cv::Scalar(10));
  image(cv::Rect(33, 22, 10, 21)).setTo(200);  // right of (32, 32)
  EXPECT_NEAR(IntensityCentroidAngle(image, 32, 32), 0.0f, 0.5f);
  cv::Mat below(64, 64, CV_8UC1, cv::Scalar(10));
  below(cv::Rect(22, 33, 21, 10)).setTo(200);  // y grows downwards: 90 degrees
  EXPECT_NEAR(IntensityCentroidAngle(below, 32, 32), 90.0f, 0.5f);
  cv::Mat flat(64, 64, CV_8UC1, cv::Scalar(0));
  EXPECT_EQ(IntensityCentroidAngle(flat, 32, 32), 0.0f);
}

TEST(SteeredBriefTest, DescriptorMatchesPointByPointRotation) {
  const BriefPattern& pattern = GetBriefPattern();
  for (int seed = 0; seed < 10; ++seed) {
    const cv::Mat image = NoiseImage(100 + seed);
    for (const float angle : {0.0f, 30.0f, 90.0f, 137.5f, 359.9f}) {
      uint8_t descriptor[32];
      ComputeSteeredBrief(image, 40, 32, angle, descriptor);
      const float c = std::cos(angle / 57.29577951308232f);
      const float s = std::sin(angle / 57.29577951308232f);
      for (int i = 0; i < kBriefBits; ++i) {
        const BriefPointPair& p = pattern[i];
        const int x1 = 40 + cvRound(p.x1 * c - p.y1 * s), y1 = 32 + cvRound(p.x1 * s + p.y1 * c);
        const int x2 = 40 + cvRound(p.x2 * c - p.y2 * s), y2 = 32 + cvRound(p.x2 * s + p.y2 * c);
        const bool bit = image.at<uint8_t>(y1, x1) < image.at<uint8_t>(y2, x2);
        ASSERT_EQ(((descriptor[i / 8] >> (i % 8)) & 1) != 0, bit)
            << "seed " << seed << " angle " << angle << " bit " << i;
      }
    }
  }
}

}  // namespace
}  // namespace drvslam
