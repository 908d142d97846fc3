// What makes ORB useful for tracking: the same scene points are found again, with the same
// descriptors, after the camera rotates about its axis or moves closer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "drvslam/feature/descriptor_distance.h"
#include "drvslam/feature/orb_extractor.h"
#include "test_images.h"
#include "test_support/missing_data.h"

namespace drvslam {
namespace {

struct ExtractedFeatures {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
};

ExtractedFeatures ExtractFeatures(const cv::Mat& gray, int target = 1000) {
  OrbExtractor extractor{OrbExtractorOptions{}};
  ExtractedFeatures f;
  extractor.Extract(gray, cv::Mat(), target, &f.keypoints, &f.descriptors);
  return f;
}

double Median(std::vector<double> values) {
  if (values.empty()) return NAN;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// Index of the keypoint in `set` nearest to `p` within `radius` pixels (and, when octave >= 0,
// on that octave); -1 when none.
int Nearest(const std::vector<cv::KeyPoint>& set, cv::Point2f p, float radius, int octave = -1) {
  int best = -1;
  float best_d2 = radius * radius;
  for (size_t i = 0; i < set.size(); ++i) {
    if (octave >= 0 && set[i].octave != octave) continue;
    const cv::Point2f d = set[i].pt - p;
    const float d2 = d.dot(d);
    if (d2 <= best_d2) {
      best_d2 = d2;
      best = static_cast<int>(i);
    }
  }
  return best;
}

struct Comparison {
  int considered = 0;
  int repeated = 0;                    // a keypoint of the other image within the radius
  std::vector<double> true_distances;  // descriptor distance to the ground-truth partner
  std::vector<double> random_distances;
  double Repeatability() const { return static_cast<double>(repeated) / considered; }
};

// Maps every keypoint of `a` accepted by `inside` into image b with `map`, and looks for its
// partner among b's keypoints (on octave a.octave + octave_shift for the descriptor check).
Comparison Compare(const ExtractedFeatures& a, const ExtractedFeatures& b,
                   const std::function<cv::Point2f(cv::Point2f)>& map,
                   const std::function<bool(cv::Point2f)>& inside, int octave_shift) {
  Comparison c;
  for (size_t i = 0; i < a.keypoints.size(); ++i) {
    const cv::KeyPoint& kp = a.keypoints[i];
    if (!inside(kp.pt)) continue;
    ++c.considered;
    const cv::Point2f q = map(kp.pt);
    // Coarse levels locate corners to about one of their own pixels.
    const float radius = 2.5f * std::max(1.0f, kp.size / 31.0f);
    if (Nearest(b.keypoints, q, radius) >= 0) ++c.repeated;
    const int j = Nearest(b.keypoints, q, radius, kp.octave + octave_shift);
    if (j >= 0) {
      c.true_distances.push_back(
          DescriptorDistance(a.descriptors.row(static_cast<int>(i)), b.descriptors.row(j)));
    }
    const int r = static_cast<int>((i * 7919 + 13) % b.keypoints.size());
    c.random_distances.push_back(
        DescriptorDistance(a.descriptors.row(static_cast<int>(i)), b.descriptors.row(r)));
  }
  return c;
}

// What a view change must keep: at least `min_repeatability` of the keypoints found again, at
// least `min_matches` partners on the expected level whose descriptors stay close, and unrelated
// descriptors far apart. Prints the figures as `<change> <photo>: ...`.
void ExpectKeypointsAndDescriptorsSurvive(const Comparison& c, double min_repeatability,
                                          std::size_t min_matches, const char* change,
                                          const char* photo) {
  EXPECT_GE(c.Repeatability(), min_repeatability);
  ASSERT_GE(c.true_distances.size(), min_matches);
  EXPECT_LT(Median(c.true_distances), 40.0);
  // Steered BRIEF's bits lean towards the side of the intensity centroid, so unrelated
  // descriptors differ in ~100 of 256 bits rather than 128.
  EXPECT_GT(Median(c.random_distances), 90.0);
  std::printf("%s %s: repeat %.3f (%d), matched %zu median %.1f random %.1f\n", change, photo,
              c.Repeatability(), c.considered, c.true_distances.size(), Median(c.true_distances),
              Median(c.random_distances));
}

class InvarianceTest : public test::PhotoParamTest {};

TEST_P(InvarianceTest, RotationBy30Degrees) {
  const cv::Point2f center(319.5f, 239.5f);
  const cv::Mat rotation = cv::getRotationMatrix2D(center, 30.0, 1.0);
  cv::Mat rotated;
  cv::warpAffine(gray_, rotated, rotation, gray_.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  const ExtractedFeatures a = ExtractFeatures(gray_);
  const ExtractedFeatures b = ExtractFeatures(rotated);
  cv::Matx23d m = rotation;
  const auto map = [&](cv::Point2f p) {
    return cv::Point2f(static_cast<float>(m(0, 0) * p.x + m(0, 1) * p.y + m(0, 2)),
                       static_cast<float>(m(1, 0) * p.x + m(1, 1) * p.y + m(1, 2)));
  };
  // Within this disc the rotated image shows the original content, with room for a patch.
  const auto inside = [&](cv::Point2f p) { return cv::norm(p - center) < 200.0; };
  const Comparison c = Compare(a, b, map, inside, 0);
  ASSERT_GE(c.considered, 500);
  RecordProperty("repeatability", std::to_string(c.Repeatability()));
  ExpectKeypointsAndDescriptorsSurvive(c, 0.5, 200, "rotation30", GetParam());
}

TEST_P(InvarianceTest, ScaleChangeBy1Point2) {
  // The scaled image's level l sees what the original's level l + 1 sees.
  cv::Mat smaller;
  cv::resize(gray_, smaller, cv::Size(533, 400), 0, 0, cv::INTER_AREA);
  const ExtractedFeatures a = ExtractFeatures(gray_);
  const ExtractedFeatures b = ExtractFeatures(smaller, 800);
  const float sx = 533.0f / 640.0f;
  const float sy = 400.0f / 480.0f;
  const auto map = [&](cv::Point2f p) {
    return cv::Point2f((p.x + 0.5f) * sx - 0.5f, (p.y + 0.5f) * sy - 0.5f);
  };
  const auto inside = [&](cv::Point2f p) { return p.x > 40 && p.y > 40 && p.x < 600 && p.y < 440; };
  const Comparison c = Compare(a, b, map, inside, -1);
  ASSERT_GE(c.considered, 500);
  ExpectKeypointsAndDescriptorsSurvive(c, 0.4, 100, "scale1.2", GetParam());
}

TEST_P(InvarianceTest, QuarterTurnAddsNinetyDegrees) {
  cv::Mat turned;
  cv::rotate(gray_, turned, cv::ROTATE_90_CLOCKWISE);
  const ExtractedFeatures a = ExtractFeatures(gray_);
  const ExtractedFeatures b = ExtractFeatures(turned);
  // Clockwise on screen: (x, y) -> (rows - 1 - y, x), and gradients (dx, dy) -> (-dy, dx).
  int level0_pairs = 0;
  std::vector<double> errors;
  std::vector<double> distances;
  for (size_t i = 0; i < a.keypoints.size(); ++i) {
    const cv::KeyPoint& kp = a.keypoints[i];
    const cv::Point2f q(gray_.rows - 1 - kp.pt.y, kp.pt.x);
    const int j = Nearest(b.keypoints, q, 0.5f * kp.size / 31.0f, kp.octave);
    if (j < 0) continue;
    double error = std::fmod(b.keypoints[j].angle - kp.angle - 90.0 + 720.0, 360.0);
    if (error > 180.0) error -= 360.0;
    errors.push_back(std::abs(error));
    distances.push_back(
        DescriptorDistance(a.descriptors.row(static_cast<int>(i)), b.descriptors.row(j)));
    if (kp.octave == 0) {
      ++level0_pairs;
      // Level 0 is an exact pixel permutation: the centroid turns exactly.
      EXPECT_LT(std::abs(error), 0.01) << kp.pt;
    }
  }
  ASSERT_GE(level0_pairs, 50);
  ASSERT_GE(errors.size(), 300u);
  EXPECT_LT(Median(errors), 1.0);
  std::sort(errors.begin(), errors.end());
  EXPECT_LT(errors[errors.size() * 9 / 10], 10.0);
  EXPECT_LT(Median(distances), 20.0);
  std::printf("quarter %s: pairs %zu level0 %d median err %.3f p90 %.2f hamming %.1f\n", GetParam(),
              errors.size(), level0_pairs, Median(errors), errors[errors.size() * 9 / 10],
              Median(distances));
}

INSTANTIATE_TEST_SUITE_P(Photos, InvarianceTest, ::testing::Values("graf1.png", "home.jpg"));

}  // namespace
}  // namespace drvslam
