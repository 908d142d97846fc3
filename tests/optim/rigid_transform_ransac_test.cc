#include "drvslam/optim/rigid_transform_ransac.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

const double kDegree = M_PI / 180.0;

struct Correspondences {
  std::vector<Eigen::Vector3d> a;
  std::vector<Eigen::Vector3d> b;
  std::vector<double> tolerance;
  std::vector<bool> is_inlier;
};

SE3 KnownTransform() {
  return SE3(
      Eigen::Quaterniond(Eigen::AngleAxisd(0.6, Eigen::Vector3d(0.3, -1.0, 0.4).normalized())),
      Eigen::Vector3d(0.4, -0.2, 1.3));
}

// `inliers` points of a 3 m cube (b) mapped by scale * T into a with 2 mm noise, then `outliers`
// random pairs. Inlier and outlier slots are shuffled.
Correspondences MakeCorrespondences(int inliers, int outliers, double scale = 1.0,
                                    unsigned seed = 3) {
  const SE3 transform = KnownTransform();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> box(-1.5, 1.5);
  std::normal_distribution<double> noise(0.0, 0.002);
  std::vector<bool> slots(inliers, true);
  slots.resize(inliers + outliers, false);
  std::shuffle(slots.begin(), slots.end(), rng);
  Correspondences c;
  for (bool inlier : slots) {
    const Eigen::Vector3d b(box(rng), box(rng), box(rng) + 3.0);
    Eigen::Vector3d a = scale * (transform.Rotation() * b) + transform.Translation();
    if (inlier) {
      a += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    } else {
      a = Eigen::Vector3d(box(rng), box(rng), box(rng) + 3.0);
    }
    c.a.push_back(a);
    c.b.push_back(b);
    c.tolerance.push_back(0.015);
    c.is_inlier.push_back(inlier);
  }
  return c;
}

void ExpectNear(const SE3& estimate, const SE3& truth, double max_degrees, double max_metres) {
  EXPECT_LT(RotationAngle(estimate.Inverse() * truth), max_degrees * kDegree);
  EXPECT_LT((estimate.Translation() - truth.Translation()).norm(), max_metres);
}

TEST(RigidTransformRansacTest, RecoversTransformWithFortyPercentOutliers) {
  const Correspondences c = MakeCorrespondences(60, 40);
  const RigidRansacResult result = EstimateRigidTransformRansac(c.a, c.b, c.tolerance);
  ASSERT_TRUE(result.found);
  ExpectNear(result.T_ab, KnownTransform(), 0.1, 0.003);
  EXPECT_EQ(result.inlier_count, 60);
  ASSERT_EQ(result.inliers.size(), c.a.size());
  EXPECT_EQ(result.inliers, c.is_inlier);
}

TEST(RigidTransformRansacTest, SameSeedSameResult) {
  const Correspondences c = MakeCorrespondences(40, 60);
  RigidRansacOptions options;
  options.seed = 42;
  const RigidRansacResult first = EstimateRigidTransformRansac(c.a, c.b, c.tolerance, options);
  const RigidRansacResult second = EstimateRigidTransformRansac(c.a, c.b, c.tolerance, options);
  ASSERT_TRUE(first.found);
  EXPECT_EQ(first.T_ab.Quaternion().coeffs(), second.T_ab.Quaternion().coeffs());
  EXPECT_EQ(first.T_ab.Translation(), second.T_ab.Translation());
  EXPECT_EQ(first.inliers, second.inliers);
}

TEST(RigidTransformRansacTest, TooFewInliersIsNotFound) {
  const Correspondences c = MakeCorrespondences(12, 60);
  const RigidRansacResult result = EstimateRigidTransformRansac(c.a, c.b, c.tolerance);
  EXPECT_FALSE(result.found);
  EXPECT_LT(result.inlier_count, RigidRansacOptions{}.min_inliers);
  EXPECT_EQ(result.inliers.size(), c.a.size());

  // With a lower bar the same 12 are enough.
  RigidRansacOptions options;
  options.min_inliers = 10;
  options.max_iterations = 3000;
  const RigidRansacResult lowered = EstimateRigidTransformRansac(c.a, c.b, c.tolerance, options);
  ASSERT_TRUE(lowered.found);
  EXPECT_EQ(lowered.inlier_count, 12);
  ExpectNear(lowered.T_ab, KnownTransform(), 0.5, 0.01);
}

TEST(RigidTransformRansacTest, DegenerateInputIsNotFound) {
  // Fewer than a minimal sample.
  const std::vector<Eigen::Vector3d> two = {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 0, 1)};
  RigidRansacOptions options;
  options.min_inliers = 3;
  EXPECT_FALSE(EstimateRigidTransformRansac(two, two, {0.01, 0.01}, options).found);
  // All on one line: the rotation about it is unknown.
  std::vector<Eigen::Vector3d> line;
  for (int i = 0; i < 30; ++i) line.push_back(Eigen::Vector3d(0.1 * i, 0.05 * i, 2.0));
  const RigidRansacResult result =
      EstimateRigidTransformRansac(line, line, std::vector<double>(30, 0.01), options);
  EXPECT_FALSE(result.found);
  EXPECT_EQ(result.inlier_count, 0);
}

TEST(RigidTransformRansacTest, SimilarityRecoversScale) {
  const double scale = 1.7;
  Correspondences c = MakeCorrespondences(60, 40, scale);
  const SimilarityRansacResult result = EstimateSimilarityTransformRansac(c.a, c.b, c.tolerance);
  ASSERT_TRUE(result.found);
  EXPECT_NEAR(result.scale, scale, 2e-3);
  ExpectNear(result.T_ab, KnownTransform(), 0.1, 0.01);
  EXPECT_EQ(result.inliers, c.is_inlier);
  // The rigid estimator cannot explain a scaled scene.
  EXPECT_FALSE(EstimateRigidTransformRansac(c.a, c.b, c.tolerance).found);
}

TEST(RigidTransformRansacTest, BadInputThrows) {
  const Correspondences c = MakeCorrespondences(30, 10);
  std::vector<double> short_tolerance = c.tolerance;
  short_tolerance.pop_back();
  EXPECT_THROW(EstimateRigidTransformRansac(c.a, c.b, short_tolerance), Error);
  std::vector<Eigen::Vector3d> short_b = c.b;
  short_b.pop_back();
  EXPECT_THROW(EstimateSimilarityTransformRansac(c.a, short_b, c.tolerance), Error);

  std::vector<Eigen::Vector3d> nan_a = c.a;
  nan_a[5].y() = NAN;
  EXPECT_THROW(EstimateRigidTransformRansac(nan_a, c.b, c.tolerance), Error);
  std::vector<double> negative = c.tolerance;
  negative[2] = -0.1;
  EXPECT_THROW(EstimateRigidTransformRansac(c.a, c.b, negative), Error);

  RigidRansacOptions options;
  options.max_iterations = 0;
  EXPECT_THROW(EstimateRigidTransformRansac(c.a, c.b, c.tolerance, options), Error);
  options = {};
  options.min_inliers = 2;
  EXPECT_THROW(EstimateRigidTransformRansac(c.a, c.b, c.tolerance, options), Error);
  for (double probability : {0.0, 1.0, std::nan("")}) {
    options = {};
    options.probability = probability;
    EXPECT_THROW(EstimateSimilarityTransformRansac(c.a, c.b, c.tolerance, options), Error);
  }
}

}  // namespace
}  // namespace drvslam
