#include "drvslam/tools/eval/alignment.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

std::vector<Eigen::Vector3d> RandomPoints(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-2.0, 2.0);
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k < n; ++k) points.emplace_back(uniform(rng), uniform(rng), uniform(rng));
  return points;
}

double MaxResidual(const Alignment& alignment, const std::vector<Eigen::Vector3d>& est,
                   const std::vector<Eigen::Vector3d>& gt) {
  double worst = 0.0;
  for (std::size_t k = 0; k < est.size(); ++k) {
    worst = std::max(worst, (alignment.Apply(est[k]) - gt[k]).norm());
  }
  return worst;
}

const Eigen::Matrix3d kRotation =
    Eigen::AngleAxisd(1.9, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
const Eigen::Vector3d kTranslation(0.4, -3.0, 2.2);

TEST(AlignPointsTest, RecoversKnownRigidTransform) {
  const std::vector<Eigen::Vector3d> est = RandomPoints(50, 1);
  std::vector<Eigen::Vector3d> gt;
  for (const Eigen::Vector3d& p : est) gt.push_back(kRotation * p + kTranslation);
  const Alignment alignment = AlignPoints(est, gt, false);
  EXPECT_LT((alignment.R - kRotation).norm(), 1e-12);
  EXPECT_LT((alignment.t - kTranslation).norm(), 1e-12);
  EXPECT_EQ(alignment.scale, 1.0);
  EXPECT_LT(MaxResidual(alignment, est, gt), 1e-12);
}

TEST(AlignPointsTest, RecoversKnownScaleOnlyWhenAsked) {
  const std::vector<Eigen::Vector3d> est = RandomPoints(40, 2);
  std::vector<Eigen::Vector3d> gt;
  for (const Eigen::Vector3d& p : est) gt.push_back(2.5 * (kRotation * p) + kTranslation);
  const Alignment similarity = AlignPoints(est, gt, true);
  EXPECT_NEAR(similarity.scale, 2.5, 1e-12);
  EXPECT_LT((similarity.R - kRotation).norm(), 1e-12);
  EXPECT_LT(MaxResidual(similarity, est, gt), 1e-11);
  const Alignment rigid = AlignPoints(est, gt, false);
  EXPECT_EQ(rigid.scale, 1.0);
  EXPECT_GT(MaxResidual(rigid, est, gt), 0.1);
}

// A mirrored, non-planar set: the best orthogonal matrix is the mirror itself, which the
// reflection guard must refuse. With the set's covariance diagonal with distinct values, the best
// proper rotation is the identity (Umeyama), leaving 2|z| on the points off the plane.
TEST(AlignPointsTest, MirroredSetGivesBestProperRotation) {
  const double a = 3.0, b = 2.0, c = 0.5;
  const std::vector<Eigen::Vector3d> gt = {{a, 0, 0},  {-a, 0, 0}, {0, b, 0},
                                           {0, -b, 0}, {0, 0, c},  {0, 0, -c}};
  std::vector<Eigen::Vector3d> est;
  for (const Eigen::Vector3d& p : gt) est.emplace_back(p.x(), p.y(), -p.z());
  const Alignment alignment = AlignPoints(est, gt, false);
  EXPECT_NEAR(alignment.R.determinant(), 1.0, 1e-12);
  EXPECT_LT((alignment.R - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_LT(alignment.t.norm(), 1e-12);
  EXPECT_NEAR((alignment.Apply(est[4]) - gt[4]).norm(), 2.0 * c, 1e-12);
  EXPECT_NEAR((alignment.Apply(est[0]) - gt[0]).norm(), 0.0, 1e-12);
}

// Planar sets leave the third singular direction's sign free; whichever sign the SVD picks, the
// result must be a rotation that maps the points exactly. Mirroring x inside the plane is
// reachable by a 180-degree turn about y.
TEST(AlignPointsTest, MirroredPlanarSetIsMatchedByARotation) {
  std::vector<Eigen::Vector3d> gt;
  for (const Eigen::Vector3d& p : RandomPoints(20, 3)) gt.emplace_back(p.x(), p.y(), 0.0);
  std::vector<Eigen::Vector3d> est;
  for (const Eigen::Vector3d& p : gt) est.emplace_back(-p.x(), p.y(), 0.0);
  const Alignment alignment = AlignPoints(est, gt, false);
  EXPECT_NEAR(alignment.R.determinant(), 1.0, 1e-12);
  EXPECT_LT(MaxResidual(alignment, est, gt), 1e-12);
  EXPECT_LT((alignment.R - Eigen::Vector3d(-1, 1, -1).asDiagonal().toDenseMatrix()).norm(), 1e-12);
}

TEST(AlignPointsTest, ColinearSetsAlignWithAProperRotation) {
  std::vector<Eigen::Vector3d> gt, est;
  const Eigen::Vector3d direction = Eigen::Vector3d(1.0, 2.0, -0.5).normalized();
  for (int k = 0; k < 10; ++k) {
    gt.push_back(0.3 * k * direction + Eigen::Vector3d(1, 1, 1));
    est.push_back(kRotation.transpose() * (gt.back() - kTranslation));
  }
  for (bool with_scale : {false, true}) {
    const Alignment alignment = AlignPoints(est, gt, with_scale);
    EXPECT_NEAR(alignment.R.determinant(), 1.0, 1e-12);
    EXPECT_NEAR(alignment.scale, 1.0, 1e-12);
    EXPECT_LT(MaxResidual(alignment, est, gt), 1e-12);
  }
}

TEST(AlignPointsTest, RejectsBadInput) {
  const std::vector<Eigen::Vector3d> three = RandomPoints(3, 4);
  const std::vector<Eigen::Vector3d> two = RandomPoints(2, 5);
  EXPECT_THROW(AlignPoints(three, two, false), Error);
  EXPECT_THROW(AlignPoints({}, {}, false), Error);
  const std::vector<Eigen::Vector3d> same(4, Eigen::Vector3d(1, 2, 3));
  EXPECT_THROW(AlignPoints(same, RandomPoints(4, 6), true), Error);
  // Without scale a degenerate estimate is merely translated onto the ground-truth centroid.
  const std::vector<Eigen::Vector3d> gt = RandomPoints(4, 6);
  const Alignment alignment = AlignPoints(same, gt, false);
  Eigen::Vector3d gt_mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : gt) gt_mean += p / 4.0;
  EXPECT_LT((alignment.Apply(same[0]) - gt_mean).norm(), 1e-12);
}

}  // namespace
}  // namespace drvslam
