#include "drvslam/tools/eval/trajectory_plot.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "drvslam/core/error.h"
#include "eval_test_util.h"
#include "test_support/temp_folder.h"

namespace drvslam {
namespace {

using testing::HelixPose;
using testing::MakeTrajectory;

// Pixels within a small distance of a BGR colour.
int CountColour(const cv::Mat& image, const cv::Scalar& colour) {
  cv::Mat mask;
  cv::inRange(image, colour - cv::Scalar(30, 30, 30), colour + cv::Scalar(30, 30, 30), mask);
  return cv::countNonZero(mask);
}

class TrajectoryPlotTest : public ::testing::Test {
 protected:
  void SetUp() override {
    gt_ = MakeTrajectory(300, 0.0, 1.0 / 30.0, HelixPose);
    est_ = gt_;
    for (std::size_t k = 0; k < est_.size(); ++k) {
      const Eigen::Vector3d wobble(0.03 * std::sin(0.3 * k), 0.02 * std::cos(0.2 * k), 0.0);
      est_[k].T_wc = SE3(est_[k].T_wc.Quaternion(), est_[k].T_wc.Translation() + wobble);
    }
    ate_ = ComputeAte(gt_, est_, AteOptions{});
  }
  Trajectory gt_, est_;
  AteResult ate_;
};

TEST_F(TrajectoryPlotTest, DrawsBothTrajectoriesAndTheErrors) {
  const cv::Mat image = RenderTrajectoryPlot(gt_, est_, ate_);
  ASSERT_EQ(image.type(), CV_8UC3);
  EXPECT_GE(image.cols, 1200);
  EXPECT_GE(image.rows, 600);
  EXPECT_GT(CountColour(image, cv::Scalar(200, 110, 20)), 200);  // estimate, blue
  EXPECT_GT(CountColour(image, cv::Scalar(40, 40, 220)), 500);   // errors, red
  EXPECT_GT(CountColour(image, cv::Scalar(40, 40, 40)), 2000);   // ground truth and text
  // The left and right halves both hold drawings.
  const cv::Mat left = image(cv::Rect(0, 100, image.cols / 2, image.rows - 100));
  const cv::Mat right = image(cv::Rect(image.cols / 2, 100, image.cols / 2, image.rows - 100));
  EXPECT_GT(CountColour(left, cv::Scalar(200, 110, 20)), 200);
  EXPECT_GT(CountColour(right, cv::Scalar(40, 40, 220)), 300);
}

TEST_F(TrajectoryPlotTest, WritesAPngAndReportsBadPaths) {
  const std::filesystem::path path =
      testing::ProcessTempFolder() / "drvslam_trajectory_plot_test.plot";
  WriteTrajectoryPlot(path.string(), gt_, est_, ate_);  // PNG whatever the extension
  const cv::Mat read = cv::imread(path.string());
  ASSERT_FALSE(read.empty());
  EXPECT_EQ(read.size(), RenderTrajectoryPlot(gt_, est_, ate_).size());
  std::filesystem::remove(path);
  try {
    WriteTrajectoryPlot("/nonexistent-dir/plot.png", gt_, est_, ate_);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/plot.png"), std::string::npos);
  }
}

}  // namespace
}  // namespace drvslam
