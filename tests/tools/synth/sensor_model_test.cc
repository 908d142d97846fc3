#include "drvslam/tools/synth/sensor_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core/utility.hpp>

#include "drvslam/core/error.h"

namespace drvslam::synth {
namespace {

CameraOptions SmallCamera() {
  CameraOptions camera;
  camera.width = 200;
  camera.height = 100;
  camera.fx = camera.fy = 200.0;
  camera.cx = 100.0;
  camera.cy = 50.0;
  return camera;
}

// A clean frame: left half a wall at 2 m, right half a box face at 1 m (a depth edge at
// x = 100), textured with a smooth gradient; the top rows seen at a grazing angle.
RenderBuffers CleanFrame() {
  RenderBuffers frame;
  frame.bgr.create(100, 200, CV_8UC3);
  frame.depth.create(100, 200, CV_32FC1);
  frame.instance = cv::Mat::zeros(100, 200, CV_16UC1);
  frame.incidence.create(100, 200, CV_32FC1);
  for (int y = 0; y < 100; ++y) {
    for (int x = 0; x < 200; ++x) {
      frame.bgr.at<cv::Vec3b>(y, x) =
          cv::Vec3b(static_cast<uint8_t>(x), 100, static_cast<uint8_t>(y));
      frame.depth.at<float>(y, x) = x < 100 ? 2.0f : 1.0f;
      frame.incidence.at<float>(y, x) = y < 10 ? 0.05f : 0.9f;
    }
  }
  return frame;
}

TEST(SensorModelTest, CleanOptionsChangeNothing) {
  const SensorModel model(SensorOptions::Clean(), SmallCamera(), 1);
  RenderBuffers frame = CleanFrame();
  const RenderBuffers clean = CleanFrame();
  model.Apply(3, 0.1, SE3(), &frame);
  EXPECT_EQ(cv::norm(frame.bgr, clean.bgr, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(frame.depth, clean.depth, cv::NORM_INF), 0.0);
  EXPECT_DOUBLE_EQ(model.ExposureGain(1.0), 1.0);
}

TEST(SensorModelTest, DepthNoiseGrowsWithDistanceSquared) {
  SensorOptions options = SensorOptions::Clean();
  options.depth_noise = true;
  options.depth_noise_coeff = 0.002;
  const SensorModel model(options, SmallCamera(), 5);
  RenderBuffers frame = CleanFrame();
  model.Apply(0, 0.0, SE3(), &frame);
  double sum_far = 0, sq_far = 0, sum_near = 0, sq_near = 0;
  int far = 0, near = 0;
  for (int y = 0; y < 100; ++y) {
    for (int x = 0; x < 200; ++x) {
      const double error = frame.depth.at<float>(y, x) - (x < 100 ? 2.0 : 1.0);
      if (x < 100) {
        sum_far += error, sq_far += error * error, ++far;
      } else {
        sum_near += error, sq_near += error * error, ++near;
      }
    }
  }
  const double sigma_far = std::sqrt(sq_far / far - std::pow(sum_far / far, 2));
  const double sigma_near = std::sqrt(sq_near / near - std::pow(sum_near / near, 2));
  EXPECT_NEAR(sigma_far, 0.002 * 4.0, 0.0008);
  EXPECT_NEAR(sigma_near, 0.002 * 1.0, 0.0002);
  EXPECT_NEAR(sum_far / far, 0.0, 0.0006);
}

TEST(SensorModelTest, QuantizationRangeAndHoles) {
  SensorOptions options = SensorOptions::Clean();
  options.depth_quantization = true;
  options.depth_noise = true;
  options.depth_noise_coeff = 0.001;
  RenderBuffers frame = CleanFrame();
  SensorModel(options, SmallCamera(), 2).Apply(0, 0.0, SE3(), &frame);
  for (int x = 20; x < 200; x += 7) {
    const double steps = frame.depth.at<float>(50, x) * 5000.0;
    EXPECT_NEAR(steps, std::round(steps), 2e-3);
  }

  options = SensorOptions::Clean();
  options.range_limits = true;
  options.min_range = 1.5;
  options.max_range = 5.0;
  frame = CleanFrame();
  SensorModel(options, SmallCamera(), 2).Apply(0, 0.0, SE3(), &frame);
  EXPECT_EQ(frame.depth.at<float>(50, 150), 0.0f);  // 1 m is nearer than min_range
  EXPECT_EQ(frame.depth.at<float>(50, 50), 2.0f);

  options = SensorOptions::Clean();
  options.grazing_holes = true;
  frame = CleanFrame();
  SensorModel(options, SmallCamera(), 2).Apply(0, 0.0, SE3(), &frame);
  EXPECT_EQ(cv::countNonZero(frame.depth.rowRange(0, 10)), 0);
  EXPECT_EQ(cv::countNonZero(frame.depth.rowRange(10, 100)), 90 * 200);

  options = SensorOptions::Clean();
  options.edge_holes = true;
  options.edge_hole_probability = 1.0;
  frame = CleanFrame();
  SensorModel(options, SmallCamera(), 2).Apply(0, 0.0, SE3(), &frame);
  // Both sides of the jump lose their depth; nothing else does.
  EXPECT_EQ(cv::countNonZero(frame.depth.colRange(99, 101)), 0);
  EXPECT_EQ(cv::countNonZero(frame.depth.colRange(0, 99)), 99 * 100);
  EXPECT_EQ(cv::countNonZero(frame.depth.colRange(101, 200)), 99 * 100);
}

TEST(SensorModelTest, ColourNoiseAndExposure) {
  SensorOptions options = SensorOptions::Clean();
  options.color_noise = true;
  options.color_noise_sigma = 3.0;
  RenderBuffers frame = CleanFrame();
  const RenderBuffers clean = CleanFrame();
  SensorModel(options, SmallCamera(), 4).Apply(1, 0.0, SE3(), &frame);
  cv::Mat difference;
  cv::subtract(frame.bgr, clean.bgr, difference, cv::noArray(), CV_32FC3);
  cv::Scalar mean, stddev;
  cv::meanStdDev(difference.reshape(1), mean, stddev);
  EXPECT_NEAR(stddev[0], 3.0, 0.3);
  EXPECT_NEAR(mean[0], 0.0, 0.2);

  options = SensorOptions::Clean();
  options.exposure = true;
  options.exposure_amplitude = 0.1;
  const SensorModel model(options, SmallCamera(), 4);
  double lowest = 2.0, highest = 0.0;
  for (double t = 0.0; t < 60.0; t += 0.05) {
    lowest = std::min(lowest, model.ExposureGain(t));
    highest = std::max(highest, model.ExposureGain(t));
  }
  EXPECT_GE(lowest, 0.9 - 1e-12);
  EXPECT_LE(highest, 1.1 + 1e-12);
  EXPECT_GT(highest - lowest, 0.1);
}

TEST(SensorModelTest, MotionBlurFollowsCameraMotion) {
  SensorOptions options = SensorOptions::Clean();
  options.motion_blur = true;
  const SensorModel model(options, SmallCamera(), 4);
  RenderBuffers still = CleanFrame();
  model.Apply(0, 0.0, SE3(), &still);
  EXPECT_EQ(cv::norm(still.bgr, CleanFrame().bgr, cv::NORM_INF), 0.0);
  // 1 cm sideways during the exposure shifts the wall (2 m) by 1 px: the horizontal colour ramp
  // is averaged over that pixel of motion; depth stays exact.
  RenderBuffers moved = CleanFrame();
  model.Apply(0, 0.0, SE3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.01, 0, 0)), &moved);
  EXPECT_GT(cv::norm(moved.bgr, CleanFrame().bgr, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(moved.depth, CleanFrame().depth, cv::NORM_INF), 0.0);
  EXPECT_NEAR(moved.bgr.at<cv::Vec3b>(50, 50)[0], 49.5, 1.0);
}

TEST(SensorModelTest, SameFrameSameNoiseOnAnyThreadCount) {
  const SensorModel model(SensorOptions(), SmallCamera(), 8);
  RenderBuffers a = CleanFrame(), b = CleanFrame(), c = CleanFrame();
  const int threads = cv::getNumThreads();
  cv::setNumThreads(1);
  model.Apply(6, 0.2, SE3(), &a);
  cv::setNumThreads(4);
  model.Apply(6, 0.2, SE3(), &b);
  cv::setNumThreads(threads);
  model.Apply(7, 0.2, SE3(), &c);
  EXPECT_EQ(cv::norm(a.bgr, b.bgr, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.depth, b.depth, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a.bgr, c.bgr, cv::NORM_INF), 0.0);  // another frame, other noise
}

TEST(SensorModelTest, BadOptionsAreNamed) {
  SensorOptions options;
  options.max_range = 0.1;
  try {
    options.Check();
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("sensor.max_range"), std::string::npos);
  }
  options = SensorOptions();
  options.depth_noise_coeff = -1.0;
  EXPECT_THROW(options.Check(), Error);
  options = SensorOptions();
  options.blur_samples = 1;
  EXPECT_THROW(SensorModel(options, SmallCamera(), 1), Error);
}

}  // namespace
}  // namespace drvslam::synth
