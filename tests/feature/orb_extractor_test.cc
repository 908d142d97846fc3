#include "drvslam/feature/orb_extractor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/features2d.hpp>
#include <string>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/feature/descriptor_distance.h"
#include "test_images.h"
#include "test_support/missing_data.h"

namespace drvslam {
namespace {

struct Features {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
};

Features Extract(OrbExtractor& extractor, const cv::Mat& gray, int target,
                 const cv::Mat& mask = cv::Mat()) {
  Features f;
  extractor.Extract(gray, mask, target, &f.keypoints, &f.descriptors);
  return f;
}

// Keypoints per cell of a cols x rows grid over the image.
std::vector<int> CellCounts(const std::vector<cv::KeyPoint>& keypoints, cv::Size image, int cols,
                            int rows) {
  std::vector<int> counts(cols * rows, 0);
  for (const cv::KeyPoint& kp : keypoints) {
    const int cx = std::clamp(static_cast<int>(kp.pt.x * cols / image.width), 0, cols - 1);
    const int cy = std::clamp(static_cast<int>(kp.pt.y * rows / image.height), 0, rows - 1);
    ++counts[cy * cols + cx];
  }
  return counts;
}

class PhotoTest : public test::PhotoParamTest {
 protected:
  OrbExtractor extractor_{OrbExtractorOptions{}};
};

TEST_P(PhotoTest, CountStaysWithinFivePercentBelowTarget) {
  for (const int target : {500, 1000, 2000}) {
    const Features f = Extract(extractor_, gray_, target);
    EXPECT_LE(static_cast<int>(f.keypoints.size()), target);
    EXPECT_GE(static_cast<int>(f.keypoints.size()), 0.95 * target) << "target " << target;
    EXPECT_EQ(f.descriptors.rows, static_cast<int>(f.keypoints.size()));
    EXPECT_EQ(f.descriptors.cols, 32);
    EXPECT_EQ(f.descriptors.type(), CV_8UC1);
  }
}

TEST_P(PhotoTest, KeypointFieldsFollowTheContract) {
  const Features f = Extract(extractor_, gray_, 1000);
  const std::vector<float>& scales = extractor_.ScaleFactors();
  int last_octave = 0;
  std::vector<int> per_level(extractor_.Levels(), 0);
  for (const cv::KeyPoint& kp : f.keypoints) {
    ASSERT_GE(kp.octave, last_octave);  // ordered by level
    ASSERT_LT(kp.octave, extractor_.Levels());
    last_octave = kp.octave;
    ++per_level[kp.octave];
    EXPECT_GE(kp.angle, 0.0f);
    EXPECT_LT(kp.angle, 360.0f);
    EXPECT_FLOAT_EQ(kp.size, 31.0f * scales[kp.octave]);
    EXPECT_GE(kp.response, 7.0f);  // FAST score of at least the fallback threshold
    // Inside the image with the patch border of the level.
    EXPECT_GE(kp.pt.x, 15.0f * scales[kp.octave]);
    EXPECT_GE(kp.pt.y, 15.0f * scales[kp.octave]);
    EXPECT_LE(kp.pt.x, 640 - 16.0f * scales[kp.octave]);
    EXPECT_LE(kp.pt.y, 480 - 16.0f * scales[kp.octave]);
  }
  // Shares fall geometrically with the level, as ORB-SLAM's do.
  const std::vector<int> shares = extractor_.LevelShares(1000);
  for (int l = 0; l < extractor_.Levels(); ++l) {
    EXPECT_NEAR(per_level[l], shares[l], 0.05 * shares[l] + 2) << "level " << l;
  }
}

TEST_P(PhotoTest, KeypointsSpreadOverTheImage) {
  const Features f = Extract(extractor_, gray_, 1000);
  const std::vector<int> counts = CellCounts(f.keypoints, gray_.size(), 8, 6);
  const int occupied =
      static_cast<int>(std::count_if(counts.begin(), counts.end(), [](int c) { return c > 0; }));
  const int max_count = *std::max_element(counts.begin(), counts.end());
  // An even spread puts ~2.1% of the keypoints in each cell. graf1 is textured all over;
  // home.jpg has a smooth sky where even the fallback threshold finds few corners.
  const bool graf = std::string(GetParam()) == "graf1.png";
  EXPECT_GE(occupied, graf ? 47 : 40) << "of 48 cells";
  EXPECT_LE(max_count, (graf ? 0.05 : 0.08) * f.keypoints.size());
}

TEST_P(PhotoTest, SkipMaskRemovesFeaturesButKeepsTheCount) {
  cv::Mat mask = cv::Mat::zeros(gray_.size(), CV_8UC1);
  mask(cv::Rect(0, 0, 320, 480)).setTo(255);
  const Features f = Extract(extractor_, gray_, 1000, mask);
  for (const cv::KeyPoint& kp : f.keypoints) {
    ASSERT_EQ(mask.at<uint8_t>(cvRound(kp.pt.y), cvRound(kp.pt.x)), 0)
        << "keypoint at " << kp.pt << " octave " << kp.octave;
  }
  EXPECT_GE(static_cast<int>(f.keypoints.size()), 950);
}

TEST_P(PhotoTest, ScatteredMaskIsRespectedAtEveryLevel) {
  // Many small boxes, as moving objects' masks are: every level must test the mask at the
  // keypoint's level-0 position.
  cv::Mat mask = cv::Mat::zeros(gray_.size(), CV_8UC1);
  for (int y = 0; y < 480; y += 60) {
    for (int x = (y / 60) % 2 * 40; x < 640; x += 80) mask(cv::Rect(x, y, 40, 30)).setTo(1);
  }
  const Features f = Extract(extractor_, gray_, 1000, mask);
  for (const cv::KeyPoint& kp : f.keypoints) {
    ASSERT_EQ(mask.at<uint8_t>(cvRound(kp.pt.y), cvRound(kp.pt.x)), 0) << kp.pt;
  }
  EXPECT_GE(static_cast<int>(f.keypoints.size()), 950);
}

TEST_P(PhotoTest, RepeatedRunsAreIdentical) {
  const Features a = Extract(extractor_, gray_, 1000);
  // The same extractor after other targets and a mask, and a fresh one: buffers reused between
  // frames must not leak into the result.
  cv::Mat mask = cv::Mat::zeros(gray_.size(), CV_8UC1);
  mask(cv::Rect(100, 100, 200, 200)).setTo(255);
  Extract(extractor_, gray_, 2000, mask);
  Extract(extractor_, gray_.t(), 300);
  const Features b = Extract(extractor_, gray_, 1000);
  OrbExtractor fresh{OrbExtractorOptions{}};
  const Features c = Extract(fresh, gray_, 1000);
  for (const Features* other : {&b, &c}) {
    ASSERT_EQ(a.keypoints.size(), other->keypoints.size());
    for (size_t i = 0; i < a.keypoints.size(); ++i) {
      const cv::KeyPoint& p = a.keypoints[i];
      const cv::KeyPoint& q = other->keypoints[i];
      ASSERT_EQ(p.pt, q.pt);
      ASSERT_EQ(p.angle, q.angle);
      ASSERT_EQ(p.octave, q.octave);
      ASSERT_EQ(p.response, q.response);
      ASSERT_EQ(p.size, q.size);
    }
    ASSERT_EQ(cv::norm(a.descriptors, other->descriptors, cv::NORM_L1), 0.0);
  }
}

TEST_P(PhotoTest, OneAndTwoThreadsGiveTheSameFeatures) {
  OrbExtractorOptions one_thread;
  one_thread.threads = 1;
  OrbExtractor single(one_thread);
  ASSERT_EQ(OrbExtractorOptions{}.threads, 2);  // extractor_ splits its levels
  cv::Mat mask = cv::Mat::zeros(gray_.size(), CV_8UC1);
  mask(cv::Rect(50, 40, 180, 220)).setTo(255);
  // 300: coarse levels fill their shares; 5000: they cannot, and pass the rest down.
  for (const int target : {300, 1000, 5000}) {
    for (const cv::Mat& skip : {cv::Mat(), mask}) {
      const Features a = Extract(single, gray_, target, skip);
      const Features b = Extract(extractor_, gray_, target, skip);
      ASSERT_EQ(a.keypoints.size(), b.keypoints.size()) << "target " << target;
      ASSERT_GT(a.keypoints.size(), 0u);
      for (size_t i = 0; i < a.keypoints.size(); ++i) {
        ASSERT_EQ(a.keypoints[i].pt, b.keypoints[i].pt) << "keypoint " << i;
        ASSERT_EQ(a.keypoints[i].angle, b.keypoints[i].angle);
        ASSERT_EQ(a.keypoints[i].octave, b.keypoints[i].octave);
        ASSERT_EQ(a.keypoints[i].response, b.keypoints[i].response);
        ASSERT_EQ(a.keypoints[i].size, b.keypoints[i].size);
      }
      ASSERT_EQ(cv::norm(a.descriptors, b.descriptors, cv::NORM_L1), 0.0) << "target " << target;
    }
  }
}

TEST_P(PhotoTest, ZeroTargetMeansOptionsCount) {
  OrbExtractorOptions options;
  options.n_features = 700;
  OrbExtractor extractor(options);
  const Features by_default = Extract(extractor, gray_, 0);
  const Features negative = Extract(extractor, gray_, -5);
  const Features explicit_700 = Extract(extractor, gray_, 700);
  EXPECT_EQ(by_default.keypoints.size(), explicit_700.keypoints.size());
  EXPECT_EQ(negative.keypoints.size(), explicit_700.keypoints.size());
  EXPECT_GE(static_cast<int>(by_default.keypoints.size()), 665);
}

TEST_P(PhotoTest, PyramidHoldsTheLastImage) {
  Extract(extractor_, gray_, 500);
  const std::vector<cv::Mat>& pyramid = extractor_.Pyramid();
  ASSERT_EQ(static_cast<int>(pyramid.size()), 8);
  EXPECT_EQ(cv::norm(pyramid[0], gray_, cv::NORM_INF), 0.0);
  for (int l = 1; l < 8; ++l) {
    EXPECT_EQ(pyramid[l].cols, cvRound(640 / std::pow(1.2, l))) << l;
    EXPECT_EQ(pyramid[l].rows, cvRound(480 / std::pow(1.2, l))) << l;
    // Downsampling keeps the mean brightness.
    EXPECT_NEAR(cv::mean(pyramid[l])[0], cv::mean(gray_)[0], 2.0) << l;
  }
}

INSTANTIATE_TEST_SUITE_P(Photos, PhotoTest, ::testing::Values("graf1.png", "home.jpg"));

TEST(OrbExtractorTest, ScaleTablesFollowTheOptions) {
  OrbExtractorOptions options;
  options.n_levels = 4;
  options.scale_factor = 1.5;
  OrbExtractor extractor(options);
  ASSERT_EQ(extractor.Levels(), 4);
  const float expected[] = {1.0f, 1.5f, 2.25f, 3.375f};
  for (int l = 0; l < 4; ++l) {
    EXPECT_FLOAT_EQ(extractor.ScaleFactors()[l], expected[l]);
    EXPECT_FLOAT_EQ(extractor.InvScaleFactors()[l], 1.0f / expected[l]);
    EXPECT_FLOAT_EQ(extractor.LevelSigma2()[l], expected[l] * expected[l]);
    EXPECT_FLOAT_EQ(extractor.InvLevelSigma2()[l], 1.0f / (expected[l] * expected[l]));
  }
}

TEST(OrbExtractorTest, LevelSharesAreGeometricAndSumToTheTarget) {
  OrbExtractor extractor{OrbExtractorOptions{}};
  for (const int target : {1, 7, 500, 1000, 2000, 12345}) {
    const std::vector<int> shares = extractor.LevelShares(target);
    ASSERT_EQ(shares.size(), 8u);
    int sum = 0;
    for (int s : shares) sum += s;
    EXPECT_EQ(sum, target);
  }
  const std::vector<int> shares = extractor.LevelShares(1000);
  // 1000 * (1 - 1/1.2) / (1 - 1.2^-8) = 217.3, then / 1.2 per level.
  EXPECT_EQ(shares[0], 217);
  EXPECT_EQ(shares[1], 181);
  EXPECT_EQ(shares[2], 151);
  for (int l = 1; l + 1 < 8; ++l) EXPECT_NEAR(shares[l] * 1.2, shares[l - 1], 2.0) << l;
}

// Smooth noise whose whole range is `amplitude` grey levels: local contrast stays below the
// initial FAST threshold (20) but not below the fallback one (7).
cv::Mat LowContrastTexture(cv::Size size, double amplitude, int seed) {
  cv::Mat noise(size, CV_32FC1);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 1.0);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 1.5);
  double lo, hi;
  cv::minMaxLoc(noise, &lo, &hi);
  cv::Mat gray;
  noise.convertTo(gray, CV_8UC1, amplitude / (hi - lo), 110.0 - amplitude * lo / (hi - lo));
  return gray;
}

TEST(OrbExtractorTest, FallbackThresholdFindsCornersInLowContrast) {
  const cv::Mat gray = LowContrastTexture(cv::Size(640, 480), 40.0, 7);
  std::vector<cv::KeyPoint> strong;
  cv::FAST(gray, strong, 20, true);
  ASSERT_LE(strong.size(), 2u) << "the texture is meant to be too faint for FAST at 20";
  OrbExtractor extractor{OrbExtractorOptions{}};
  const Features f = Extract(extractor, gray, 1000);
  EXPECT_GE(static_cast<int>(f.keypoints.size()), 950);
  for (const cv::KeyPoint& kp : f.keypoints) EXPECT_LT(kp.response, 20.0f);

  OrbExtractorOptions strict;
  strict.min_th_fast = 20;
  OrbExtractor no_fallback(strict);
  EXPECT_LE(Extract(no_fallback, gray, 1000).keypoints.size(), 2u);
}

TEST(OrbExtractorTest, FallbackGivesFaintHalfItsShare) {
  // Strong texture on the left, faint on the right: cells on the right fall back to the lower
  // threshold and so keep a good part of the count (the faint texture offers fewer corners on
  // coarse levels); without the fallback they would get nothing.
  cv::Mat gray = LowContrastTexture(cv::Size(640, 480), 40.0, 3);
  LowContrastTexture(cv::Size(320, 480), 255.0, 4).copyTo(gray(cv::Rect(0, 0, 320, 480)));
  OrbExtractor extractor{OrbExtractorOptions{}};
  const Features f = Extract(extractor, gray, 1000);
  const auto right = std::count_if(f.keypoints.begin(), f.keypoints.end(),
                                   [](const cv::KeyPoint& kp) { return kp.pt.x >= 330; });
  EXPECT_GE(static_cast<int>(f.keypoints.size()), 950);
  EXPECT_GE(right, 250);

  OrbExtractorOptions strict;
  strict.min_th_fast = 20;
  OrbExtractor no_fallback(strict);
  const Features g = Extract(no_fallback, gray, 1000);
  EXPECT_LE(std::count_if(g.keypoints.begin(), g.keypoints.end(),
                          [](const cv::KeyPoint& kp) { return kp.pt.x >= 330; }),
            5);
}

TEST(OrbExtractorTest, FlatAndTinyImagesGiveNoFeatures) {
  OrbExtractor extractor{OrbExtractorOptions{}};
  for (const cv::Size size : {cv::Size(640, 480), cv::Size(33, 33), cv::Size(1, 1)}) {
    const Features f = Extract(extractor, cv::Mat(size, CV_8UC1, cv::Scalar(90)), 1000);
    EXPECT_TRUE(f.keypoints.empty()) << size;
    EXPECT_EQ(f.descriptors.rows, 0);
  }
  // Tiny but textured: only positions a full patch away from the edges are allowed.
  cv::Mat noise(40, 40, CV_8UC1);
  cv::randu(noise, 0, 256);
  const Features f = Extract(extractor, noise, 1000);
  for (const cv::KeyPoint& kp : f.keypoints) {
    EXPECT_EQ(kp.octave, 0);
    EXPECT_GE(kp.pt.x, 16.0f);
    EXPECT_LE(kp.pt.x, 23.0f);
  }
}

TEST(OrbExtractorTest, RejectsBadInputs) {
  OrbExtractor extractor{OrbExtractorOptions{}};
  const cv::Mat gray(480, 640, CV_8UC1, cv::Scalar(0));
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  EXPECT_THROW(
      extractor.Extract(cv::Mat(480, 640, CV_8UC3), cv::Mat(), 100, &keypoints, &descriptors),
      Error);
  EXPECT_THROW(
      extractor.Extract(cv::Mat(480, 640, CV_16UC1), cv::Mat(), 100, &keypoints, &descriptors),
      Error);
  EXPECT_THROW(extractor.Extract(cv::Mat(), cv::Mat(), 100, &keypoints, &descriptors), Error);
  EXPECT_THROW(extractor.Extract(gray, cv::Mat(240, 320, CV_8UC1), 100, &keypoints, &descriptors),
               Error);
  EXPECT_THROW(extractor.Extract(gray, cv::Mat(480, 640, CV_32FC1), 100, &keypoints, &descriptors),
               Error);
  EXPECT_THROW(extractor.Extract(gray, cv::Mat(), 100, nullptr, &descriptors), Error);
  EXPECT_THROW(extractor.Extract(gray, cv::Mat(), 100, &keypoints, nullptr), Error);
  try {
    extractor.Extract(gray, cv::Mat(240, 320, CV_8UC1), 100, &keypoints, &descriptors);
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("mask"), std::string::npos) << e.what();
  }
  OrbExtractorOptions bad;
  bad.n_levels = 0;
  EXPECT_THROW(OrbExtractor{bad}, Error);
}

TEST(OrbExtractorTest, AcceptsImageViews) {
  // A ROI is not continuous: rows must be read through the step.
  cv::Mat big(600, 800, CV_8UC1);
  cv::randu(big, 0, 256);
  cv::GaussianBlur(big, big, cv::Size(5, 5), 1.5);
  const cv::Mat view = big(cv::Rect(50, 40, 640, 480));
  OrbExtractor extractor{OrbExtractorOptions{}};
  const Features from_view = Extract(extractor, view, 1000);
  const Features from_copy = Extract(extractor, view.clone(), 1000);
  ASSERT_EQ(from_view.keypoints.size(), from_copy.keypoints.size());
  EXPECT_GE(from_view.keypoints.size(), 950u);
  EXPECT_EQ(cv::norm(from_view.descriptors, from_copy.descriptors, cv::NORM_L1), 0.0);
}

}  // namespace
}  // namespace drvslam
