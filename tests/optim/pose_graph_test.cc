#include "drvslam/optim/pose_graph.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

constexpr int kLoopPoses = 30;

// Camera-to-world poses on a 2 m circle, each camera looking along the circle's tangent, as
// world-to-camera poses.
std::vector<SE3> CircleTruth() {
  std::vector<SE3> truth;
  for (int k = 0; k < kLoopPoses; ++k) {
    const double angle = 2.0 * M_PI * k / kLoopPoses;
    const Eigen::Matrix3d R_wc =
        Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()).toRotationMatrix();
    const Eigen::Vector3d t_wc(2.0 * std::cos(angle), 0.1 * std::sin(3 * angle),
                               -2.0 * std::sin(angle));
    truth.push_back(SE3(R_wc, t_wc).Inverse());
  }
  return truth;
}

// Odometry that drifts: every step's measurement carries a small bias and noise.
struct DriftingLoop {
  std::vector<SE3> truth;
  PoseGraphProblem problem;
};

DriftingLoop MakeDriftingLoop() {
  DriftingLoop loop;
  loop.truth = CircleTruth();
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 1.0);
  Vector6d bias;
  // A heading bias (yaw about the camera's y axis) and a forward (z) scale bias: the usual shape
  // of visual odometry drift.
  bias << 0.0, 0.0, 0.004, 0.0, 0.006, 0.0;
  loop.problem.poses_cw.push_back(loop.truth[0]);
  for (int k = 1; k < kLoopPoses; ++k) {
    Vector6d twist = bias;
    for (int i = 0; i < 6; ++i) twist(i) += 0.002 * noise(rng);
    const SE3 measured = SE3::Exp(twist) * loop.truth[k] * loop.truth[k - 1].Inverse();
    loop.problem.edges.push_back({k - 1, k, measured, 1.0});
    loop.problem.poses_cw.push_back(measured * loop.problem.poses_cw.back());
  }
  // The loop closure: the last pose seen again from the first, measured well.
  loop.problem.edges.push_back(
      {kLoopPoses - 1, 0, loop.truth[0] * loop.truth[kLoopPoses - 1].Inverse(), 1.0});
  loop.problem.fixed.assign(kLoopPoses, false);
  loop.problem.fixed[0] = true;
  return loop;
}

double PositionError(const SE3& estimate_cw, const SE3& truth_cw) {
  return (estimate_cw.Inverse().Translation() - truth_cw.Inverse().Translation()).norm();
}

double RmsPositionError(const std::vector<SE3>& estimate, const std::vector<SE3>& truth) {
  double sum = 0.0;
  for (std::size_t k = 0; k < truth.size(); ++k) {
    sum += std::pow(PositionError(estimate[k], truth[k]), 2);
  }
  return std::sqrt(sum / truth.size());
}

// How far the loop edge's measurement is from what the poses say.
double LoopEndError(const std::vector<SE3>& poses, const PoseGraphEdge& loop) {
  return (loop.T_to_from.Inverse() * poses[loop.to] * poses[loop.from].Inverse()).Log().norm();
}

TEST(PoseGraphTest, ClosesADriftingLoop) {
  const DriftingLoop loop = MakeDriftingLoop();
  const PoseGraphEdge& loop_edge = loop.problem.edges.back();
  const double end_before = LoopEndError(loop.problem.poses_cw, loop_edge);
  const double last_before = PositionError(loop.problem.poses_cw.back(), loop.truth.back());
  const double rms_before = RmsPositionError(loop.problem.poses_cw, loop.truth);
  ASSERT_GT(last_before, 0.2);  // the drift is real

  const PoseGraphResult result = OptimizePoseGraph(loop.problem);
  const double end_after = LoopEndError(result.poses_cw, loop_edge);
  const double last_after = PositionError(result.poses_cw.back(), loop.truth.back());
  const double rms_after = RmsPositionError(result.poses_cw, loop.truth);
  EXPECT_LT(end_after, end_before / 10.0);
  EXPECT_LT(last_after, last_before / 10.0);
  EXPECT_LT(rms_after, rms_before / 5.0);
  EXPECT_LT(rms_after, 0.05);
  EXPECT_LT(result.final_cost, result.initial_cost / 10.0);
  EXPECT_GT(result.iterations, 0);
  EXPECT_LE(result.iterations, PoseGraphOptions{}.max_iterations);
  // The fixed origin stays where it was, bit for bit.
  EXPECT_EQ(result.poses_cw[0].Quaternion().coeffs(),
            loop.problem.poses_cw[0].Quaternion().coeffs());
  EXPECT_EQ(result.poses_cw[0].Translation(), loop.problem.poses_cw[0].Translation());
}

TEST(PoseGraphTest, ConsistentGraphStaysPut) {
  const std::vector<SE3> truth = CircleTruth();
  PoseGraphProblem problem;
  problem.poses_cw = truth;
  problem.fixed.assign(truth.size(), false);
  problem.fixed[0] = true;
  for (int k = 1; k < kLoopPoses; ++k) {
    problem.edges.push_back({k - 1, k, truth[k] * truth[k - 1].Inverse(), 1.0});
  }
  const PoseGraphResult result = OptimizePoseGraph(problem);
  EXPECT_LT(result.initial_cost, 1e-20);
  EXPECT_LT(RmsPositionError(result.poses_cw, truth), 1e-9);
}

TEST(PoseGraphTest, FixedPosesStayFixed) {
  DriftingLoop loop = MakeDriftingLoop();
  loop.problem.fixed[10] = true;
  loop.problem.fixed[20] = true;
  const PoseGraphResult result = OptimizePoseGraph(loop.problem);
  for (int k : {0, 10, 20}) {
    EXPECT_EQ(result.poses_cw[k].Quaternion().coeffs(),
              loop.problem.poses_cw[k].Quaternion().coeffs())
        << k;
    EXPECT_EQ(result.poses_cw[k].Translation(), loop.problem.poses_cw[k].Translation()) << k;
  }
  // The free ones still move.
  EXPECT_GT(PositionError(result.poses_cw[25], loop.problem.poses_cw[25]), 1e-3);
}

TEST(PoseGraphTest, AllFixedReportsTheCost) {
  DriftingLoop loop = MakeDriftingLoop();
  loop.problem.fixed.assign(kLoopPoses, true);
  const PoseGraphResult result = OptimizePoseGraph(loop.problem);
  EXPECT_EQ(result.iterations, 0);
  EXPECT_GT(result.initial_cost, 0.0);
  EXPECT_EQ(result.initial_cost, result.final_cost);
  EXPECT_EQ(result.poses_cw.back().Translation(), loop.problem.poses_cw.back().Translation());
}

// Two measurements of the same relative pose disagree by a translation: the optimum is their
// weighted mean.
TEST(PoseGraphTest, EdgeWeightMatters) {
  const Eigen::Quaterniond rotation(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ()));
  PoseGraphProblem problem;
  problem.poses_cw = {SE3(), SE3()};
  problem.fixed = {true, false};
  problem.edges.push_back({0, 1, SE3(rotation, Eigen::Vector3d(1.0, 0.0, 0.0)), 1.0});
  problem.edges.push_back({0, 1, SE3(rotation, Eigen::Vector3d(2.0, 0.0, 0.0)), 3.0});
  const PoseGraphResult heavy_second = OptimizePoseGraph(problem);
  EXPECT_NEAR(heavy_second.poses_cw[1].Translation().x(), 1.75, 1e-6);
  EXPECT_NEAR(heavy_second.poses_cw[1].Translation().y(), 0.0, 1e-6);
  EXPECT_NEAR(RotationAngle(heavy_second.poses_cw[1]), 0.2, 1e-6);

  problem.edges[0].weight = 3.0;
  problem.edges[1].weight = 1.0;
  const PoseGraphResult heavy_first = OptimizePoseGraph(problem);
  EXPECT_NEAR(heavy_first.poses_cw[1].Translation().x(), 1.25, 1e-6);
}

TEST(PoseGraphTest, BadInputThrows) {
  const DriftingLoop loop = MakeDriftingLoop();
  PoseGraphOptions options;
  options.max_iterations = 0;
  EXPECT_THROW(OptimizePoseGraph(loop.problem, options), Error);

  PoseGraphProblem wrong_fixed = loop.problem;
  wrong_fixed.fixed.pop_back();
  EXPECT_THROW(OptimizePoseGraph(wrong_fixed), Error);

  PoseGraphProblem out_of_range = loop.problem;
  out_of_range.edges[3].to = kLoopPoses;
  EXPECT_THROW(OptimizePoseGraph(out_of_range), Error);

  PoseGraphProblem self_edge = loop.problem;
  self_edge.edges[3].from = self_edge.edges[3].to;
  EXPECT_THROW(OptimizePoseGraph(self_edge), Error);

  for (double weight : {0.0, -1.0, std::nan("")}) {
    PoseGraphProblem bad_weight = loop.problem;
    bad_weight.edges[2].weight = weight;
    EXPECT_THROW(OptimizePoseGraph(bad_weight), Error) << weight;
  }

  PoseGraphProblem bad_pose = loop.problem;
  bad_pose.poses_cw[4] = SE3(Eigen::Quaterniond::Identity(), Eigen::Vector3d(NAN, 0.0, 0.0));
  EXPECT_THROW(OptimizePoseGraph(bad_pose), Error);

  // Nothing to do is not an error.
  PoseGraphProblem empty;
  EXPECT_TRUE(OptimizePoseGraph(empty).poses_cw.empty());
}

}  // namespace
}  // namespace drvslam
