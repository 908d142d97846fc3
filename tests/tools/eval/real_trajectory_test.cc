// ATE and RPE on real TUM RGB-D ground-truth trajectories (from ../shared): a rigidly moved copy
// scores zero, and a noisy copy scores what an independent alignment (Eigen::umeyama) gives.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <random>
#include <string>

#include "drvslam/tools/eval/ate.h"
#include "drvslam/tools/eval/rpe.h"
#include "eval_test_util.h"
#include "test_support/missing_data.h"
#include "test_support/temp_folder.h"

namespace drvslam {
namespace {

using testing::InOtherWorld;
using testing::SomeWorldChange;

const char* const kSequences[] = {"rgbd_dataset_freiburg1_xyz", "rgbd_dataset_freiburg2_desk",
                                  "rgbd_dataset_freiburg3_long_office_household",
                                  "rgbd_dataset_freiburg3_walking_xyz"};

std::string GroundTruthPath(const std::string& sequence) {
  return std::string(DRVSLAM_SHARED_DIR) + "/tum-groundtruth/" + sequence + "/groundtruth.txt";
}

class RealTrajectoryTest : public ::testing::TestWithParam<const char*> {
 protected:
  void SetUp() override {
    const std::string path = GroundTruthPath(GetParam());
    if (!std::filesystem::exists(path))
      DRVSLAM_MISSING_TEST_DATA() << "missing shared data file " << path;
    gt_ = ReadTumTrajectory(path);
  }
  Trajectory gt_;
};

TEST_P(RealTrajectoryTest, MovedCopyThroughAFileHasZeroError) {
  const std::filesystem::path file =
      testing::ProcessTempFolder() / (std::string("drvslam_eval_") + GetParam() + ".txt");
  WriteTumTrajectory(file.string(), InOtherWorld(gt_, SomeWorldChange()));
  const Trajectory est = ReadTumTrajectory(file.string());
  std::filesystem::remove(file);

  const AteResult ate = ComputeAte(gt_, est, AteOptions{});
  EXPECT_EQ(ate.matched, gt_.size());
  EXPECT_LT(ate.errors.rmse, 1e-6);  // the file holds 9 decimals
  EXPECT_NEAR(ate.coverage, 1.0, 1e-12);
  const RpeResult rpe = ComputeRpe(gt_, est, RpeOptions{});
  EXPECT_LT(rpe.trans_rmse, 1e-6);
  EXPECT_LT(rpe.rot_rmse_deg, 1e-3);
  EXPECT_GT(rpe.pairs, gt_.size() / 2);
}

TEST_P(RealTrajectoryTest, NoisyCopyMatchesAnIndependentAlignment) {
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.01);
  Trajectory noisy = gt_;
  Eigen::Matrix3Xd est_points(3, gt_.size()), gt_points(3, gt_.size());
  for (std::size_t k = 0; k < gt_.size(); ++k) {
    const Eigen::Vector3d offset(noise(rng), noise(rng), noise(rng));
    noisy[k].T_wc = SE3(gt_[k].T_wc.Quaternion(), gt_[k].T_wc.Translation() + offset);
  }
  const Trajectory est = InOtherWorld(noisy, SomeWorldChange());
  for (std::size_t k = 0; k < gt_.size(); ++k) {
    est_points.col(k) = est[k].T_wc.Translation();
    gt_points.col(k) = gt_[k].T_wc.Translation();
  }
  const Eigen::Matrix4d umeyama = Eigen::umeyama(est_points, gt_points, false);
  const Eigen::Matrix3Xd residual =
      ((umeyama.topLeftCorner<3, 3>() * est_points).colwise() + umeyama.topRightCorner<3, 1>()) -
      gt_points;
  const double expected_rmse =
      std::sqrt(residual.colwise().squaredNorm().sum() / static_cast<double>(gt_.size()));

  const AteResult ate = ComputeAte(gt_, est, AteOptions{});
  EXPECT_NEAR(ate.errors.rmse, expected_rmse, 1e-9);
  // Three axes of 1 cm noise: about sqrt(3) cm, slightly less after the best alignment.
  EXPECT_NEAR(ate.errors.rmse, 0.01 * std::sqrt(3.0), 0.001);
  EXPECT_LE(ate.errors.rmse, 0.01 * std::sqrt(3.0) * 1.05);
}

INSTANTIATE_TEST_SUITE_P(TumGroundTruth, RealTrajectoryTest, ::testing::ValuesIn(kSequences),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           std::string name = info.param;
                           return name.substr(std::string("rgbd_dataset_").size());
                         });

}  // namespace
}  // namespace drvslam
