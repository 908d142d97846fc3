// The ROS 2 node's conversions, without DDS traffic: stamp pairing, sensor_msgs/Image and
// CameraInfo in, messages out, ROS_DOMAIN_ID.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/dynamic/dynamic_front_end.h"
#include "drvslam/ros2/dds_entities.h"
#include "drvslam/ros2/image_messages.h"
#include "drvslam/ros2/output_messages.h"
#include "drvslam/ros2/stamp_pairing.h"
#include "test_support/error_message.h"

namespace drvslam::ros2 {
namespace {

constexpr std::int64_t kMs = 1000000;

// The drvslam::Error `action` throws must say `text` (ErrorMessageOf is empty when none is thrown).
#define EXPECT_ERROR_SAYS(action, text)                                           \
  do {                                                                            \
    const std::string message = testing::ErrorMessageOf([&] { (void)(action); }); \
    EXPECT_NE(message.find(text), std::string::npos) << "message: " << message;   \
  } while (0)

cv::Mat Marked(int value) { return cv::Mat(1, 1, CV_8UC1, cv::Scalar(value)); }

TEST(StampPairerTest, PairsTheNewestColourWithItsNearestDepthAndSkipsOlderColour) {
  StampPairer pairer(5 * kMs);
  pairer.AddColour(100 * kMs, Marked(1));
  pairer.AddColour(133 * kMs, Marked(2));
  pairer.AddDepth(101 * kMs, Marked(11));
  EXPECT_FALSE(pairer.TakeNewest() == std::nullopt);  // 100 pairs with 101
  pairer.AddColour(166 * kMs, Marked(3));
  pairer.AddDepth(134 * kMs, Marked(12));
  pairer.AddDepth(168 * kMs, Marked(13));
  pairer.AddDepth(165 * kMs, Marked(14));
  const std::optional<RgbdPair> pair = pairer.TakeNewest();
  ASSERT_TRUE(pair.has_value());
  EXPECT_EQ(pair->stamp_ns, 166 * kMs);
  EXPECT_EQ(pair->bgr.at<std::uint8_t>(0, 0), 3);
  EXPECT_EQ(pair->depth.at<std::uint8_t>(0, 0), 14);  // 1 ms away beats 2 ms
  EXPECT_EQ(pairer.Skipped(), 1u);                    // 133 was passed over
  EXPECT_FALSE(pairer.TakeNewest().has_value());
}

TEST(StampPairerTest, NeverPairsBeyondTheToleranceAndDropsWhatOverflows) {
  StampPairer pairer(5 * kMs, 2);
  pairer.AddColour(100 * kMs, Marked(1));
  pairer.AddDepth(106 * kMs, Marked(11));
  EXPECT_FALSE(pairer.TakeNewest().has_value());
  pairer.AddColour(200 * kMs, Marked(2));
  pairer.AddColour(300 * kMs, Marked(3));  // pushes 100 out
  EXPECT_EQ(pairer.Dropped(), 1u);
  pairer.AddDepth(300 * kMs, Marked(13));
  const std::optional<RgbdPair> pair = pairer.TakeNewest();
  ASSERT_TRUE(pair.has_value());
  EXPECT_EQ(pair->stamp_ns, 300 * kMs);
}

TEST(StampTest, NanosecondsRoundTripIncludingBeforeTheEpoch) {
  for (std::int64_t ns : {std::int64_t{0}, std::int64_t{1700000000123456789}, std::int64_t{-1}}) {
    const builtin_interfaces_msg_dds__Time_ stamp = StampFromNanoseconds(ns);
    EXPECT_LT(stamp.nanosec, 1000000000u);
    EXPECT_EQ(StampNanoseconds(stamp), ns);
  }
  EXPECT_EQ(StampFromNanoseconds(-1).sec, -1);
}

// A message over `bytes` (kept by the caller).
sensor_msgs_msg_dds__Image_ ImageOf(std::vector<std::uint8_t>& bytes, const char* encoding,
                                    std::uint32_t width, std::uint32_t height, std::uint32_t step) {
  sensor_msgs_msg_dds__Image_ image{};
  image.width = width;
  image.height = height;
  image.step = step;
  image.encoding = const_cast<char*>(encoding);
  image.data._buffer = bytes.data();
  image.data._length = static_cast<std::uint32_t>(bytes.size());
  image.data._maximum = image.data._length;
  return image;
}

TEST(ImageMessagesTest, Rgb8BecomesBgrAndPaddedRowsAreSkipped) {
  // 2 x 2, step 8 (2 bytes of padding per row).
  std::vector<std::uint8_t> bytes = {10, 20, 30, 40, 50, 60, 0, 0, 70, 80, 90, 1, 2, 3, 0, 0};
  const cv::Mat bgr = ColourImage(ImageOf(bytes, "rgb8", 2, 2, 8), "/colour");
  ASSERT_EQ(bgr.type(), CV_8UC3);
  EXPECT_EQ(bgr.at<cv::Vec3b>(0, 0), cv::Vec3b(30, 20, 10));
  EXPECT_EQ(bgr.at<cv::Vec3b>(1, 1), cv::Vec3b(3, 2, 1));
  const cv::Mat same = ColourImage(ImageOf(bytes, "bgr8", 2, 2, 8), "/colour");
  EXPECT_EQ(same.at<cv::Vec3b>(0, 0), cv::Vec3b(10, 20, 30));
}

TEST(ImageMessagesTest, BadImagesAreErrorsNamingTheTopicAndTheProblem) {
  std::vector<std::uint8_t> bytes(12, 0);
  EXPECT_ERROR_SAYS(ColourImage(ImageOf(bytes, "rgb8", 2, 2, 5), "/cam"),
                    "/cam: step 5 is shorter than a row (6 bytes)");
  EXPECT_ERROR_SAYS(ColourImage(ImageOf(bytes, "rgb8", 2, 3, 6), "/cam"), "data holds 12 bytes");
  EXPECT_ERROR_SAYS(ColourImage(ImageOf(bytes, "yuv422", 2, 2, 6), "/cam"), "encoding 'yuv422'");
  EXPECT_ERROR_SAYS(DepthImageMetres(ImageOf(bytes, "rgb8", 2, 2, 6), "/depth"),
                    "not a depth encoding");
  EXPECT_ERROR_SAYS(ColourImage(ImageOf(bytes, "rgb8", 0, 2, 6), "/cam"), "empty");
  // Sizes beyond cv::Mat's int are named before any row arithmetic (steps of 0 and 2^32 - 1).
  EXPECT_ERROR_SAYS(ColourImage(ImageOf(bytes, "rgb8", 1, 0x80000000u, 0), "/cam"),
                    "/cam: 1 x 2147483648 pixels is larger than 32768 on a side");
  EXPECT_ERROR_SAYS(DepthImageMetres(ImageOf(bytes, "16UC1", 40000, 1, 0xffffffffu), "/depth"),
                    "40000 x 1 pixels is larger than 32768");
  // The largest side still passes the size check and stops at the data length.
  EXPECT_ERROR_SAYS(ColourImage(ImageOf(bytes, "mono8", 32768, 1, 32768), "/cam"),
                    "data holds 12 bytes");
}

TEST(ImageMessagesTest, DepthIsMetresFromMillimetresOrFloatsWithInvalidAsZero) {
  std::vector<std::uint8_t> millimetres = {0xd2, 0x04, 0x00, 0x00};  // 1234 mm, 0
  const cv::Mat depth = DepthImageMetres(ImageOf(millimetres, "16UC1", 2, 1, 4), "/depth");
  ASSERT_EQ(depth.type(), CV_32FC1);
  EXPECT_FLOAT_EQ(depth.at<float>(0, 0), 1.234f);
  EXPECT_EQ(depth.at<float>(0, 1), 0.0f);
  sensor_msgs_msg_dds__Image_ big = ImageOf(millimetres, "16UC1", 2, 1, 4);
  big.is_bigendian = 1;  // 0xd204 = 53764 mm
  EXPECT_FLOAT_EQ(DepthImageMetres(big, "/depth").at<float>(0, 0), 53.764f);

  const float values[3] = {2.5f, std::numeric_limits<float>::quiet_NaN(), -1.0f};
  std::vector<std::uint8_t> floats(sizeof values);
  std::memcpy(floats.data(), values, sizeof values);
  const cv::Mat metres = DepthImageMetres(ImageOf(floats, "32FC1", 3, 1, 12), "/depth");
  EXPECT_FLOAT_EQ(metres.at<float>(0, 0), 2.5f);
  EXPECT_EQ(metres.at<float>(0, 1), 0.0f);
  EXPECT_EQ(metres.at<float>(0, 2), 0.0f);
}

sensor_msgs_msg_dds__CameraInfo_ InfoOf(std::vector<double>& d, const char* model) {
  sensor_msgs_msg_dds__CameraInfo_ info{};
  info.width = 848;
  info.height = 480;
  const double k[9] = {600, 0, 424, 0, 610, 240, 0, 0, 1};
  std::copy(k, k + 9, info.k);
  info.distortion_model = const_cast<char*>(model);
  info.d._buffer = d.data();
  info.d._length = static_cast<std::uint32_t>(d.size());
  info.d._maximum = info.d._length;
  return info;
}

TEST(CameraInfoTest, IntrinsicsAndDistortionComeFromKAndD) {
  std::vector<double> d = {0.1, -0.2, 0.001, 0.002, 0.03};
  const CameraOptions base;  // TUM fr3: fx 535.4, bf 40
  const CameraOptions camera = CameraFromInfo(InfoOf(d, "plumb_bob"), base, "/info");
  EXPECT_EQ(camera.width, 848);
  EXPECT_EQ(camera.height, 480);
  EXPECT_DOUBLE_EQ(camera.fx, 600.0);
  EXPECT_DOUBLE_EQ(camera.fy, 610.0);
  EXPECT_DOUBLE_EQ(camera.cx, 424.0);
  EXPECT_DOUBLE_EQ(camera.cy, 240.0);
  EXPECT_DOUBLE_EQ(camera.k1, 0.1);
  EXPECT_DOUBLE_EQ(camera.k3, 0.03);
  EXPECT_DOUBLE_EQ(camera.bf / camera.fx, base.bf / base.fx);  // the same baseline in metres
}

TEST(CameraInfoTest, WhatTheModelCannotHoldIsAnError) {
  std::vector<double> rational = {0.1, 0, 0, 0, 0, 0.5, 0, 0};
  EXPECT_ERROR_SAYS(
      CameraFromInfo(InfoOf(rational, "rational_polynomial"), CameraOptions(), "/info"),
      "after k3");
  std::vector<double> fisheye = {0.1, 0.2, 0, 0};
  EXPECT_ERROR_SAYS(CameraFromInfo(InfoOf(fisheye, "equidistant"), CameraOptions(), "/info"),
                    "distortion model 'equidistant'");
  std::vector<double> none;
  sensor_msgs_msg_dds__CameraInfo_ info = InfoOf(none, "");
  info.k[0] = 0.0;
  EXPECT_ERROR_SAYS(CameraFromInfo(info, CameraOptions(), "/info"),
                    "camera info on /info: K has no positive focal lengths");
  sensor_msgs_msg_dds__CameraInfo_ huge = InfoOf(none, "");
  huge.height = 0xffffffffu;
  EXPECT_ERROR_SAYS(CameraFromInfo(huge, CameraOptions(), "/info"),
                    "camera info on /info: 848 x 4294967295 pixels is larger than 32768");
}

TEST(RosDomainIdTest, ReadsTheVariableAsRos2Does) {
  ASSERT_EQ(unsetenv("ROS_DOMAIN_ID"), 0);
  EXPECT_EQ(RosDomainId(), 0u);
  ASSERT_EQ(setenv("ROS_DOMAIN_ID", "42", 1), 0);
  EXPECT_EQ(RosDomainId(), 42u);
  ASSERT_EQ(setenv("ROS_DOMAIN_ID", "233", 1), 0);
  EXPECT_ERROR_SAYS(RosDomainId(), "ROS_DOMAIN_ID=233: expected an integer 0..232");
  ASSERT_EQ(setenv("ROS_DOMAIN_ID", "7x", 1), 0);
  EXPECT_ERROR_SAYS(RosDomainId(), "ROS_DOMAIN_ID=7x");
  ASSERT_EQ(unsetenv("ROS_DOMAIN_ID"), 0);
}

TEST(OutputMessagesTest, PoseMessagesCarryThePoseTwistCovariancesStampAndFrames) {
  OdometryEstimate estimate;
  estimate.T_wc = SE3(Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitY())),
                      Eigen::Vector3d(1, 2, 3));
  estimate.linear_velocity = Eigen::Vector3d(0.1, -0.2, 0.3);
  estimate.angular_velocity = Eigen::Vector3d(-0.4, 0.5, 0.6);
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) {
      estimate.pose_covariance(r, c) = 10 * r + c;
      estimate.twist_covariance(r, c) = 100 + 10 * r + c;
    }
  }
  const PoseMessages messages(estimate, 5 * 1000000000LL + 7, "map", "cam");
  const auto& odometry = messages.Odometry();
  EXPECT_STREQ(odometry.header.frame_id, "map");
  EXPECT_STREQ(odometry.child_frame_id, "cam");
  EXPECT_EQ(odometry.header.stamp.sec, 5);
  EXPECT_EQ(odometry.header.stamp.nanosec, 7u);
  EXPECT_DOUBLE_EQ(odometry.pose.pose.position.z, 3.0);
  EXPECT_NEAR(odometry.pose.pose.orientation.y, std::sin(0.25), 1e-12);
  EXPECT_NEAR(odometry.pose.pose.orientation.w, std::cos(0.25), 1e-12);
  // The twist in the child frame as given; both covariances row-major.
  EXPECT_DOUBLE_EQ(odometry.twist.twist.linear.y, -0.2);
  EXPECT_DOUBLE_EQ(odometry.twist.twist.angular.z, 0.6);
  EXPECT_DOUBLE_EQ(odometry.pose.covariance[6 * 2 + 4], 24.0);
  EXPECT_DOUBLE_EQ(odometry.twist.covariance[6 * 5 + 1], 151.0);
  const auto& tf = messages.Transforms();
  ASSERT_EQ(tf.transforms._length, 1u);
  EXPECT_STREQ(tf.transforms._buffer[0].child_frame_id, "cam");
  EXPECT_DOUBLE_EQ(tf.transforms._buffer[0].transform.translation.y, 2.0);
  EXPECT_DOUBLE_EQ(messages.Pose().pose.position.x, 1.0);
}

TEST(OutputMessagesTest, PointCloudPacksXyzAndRgbAsPclDoes) {
  DenseCloud points(2);
  points[1].position = {1.5f, -2.0f, 3.0f};
  points[1].r = 0x12;
  points[1].g = 0x34;
  points[1].b = 0x56;
  const PointCloudMessage cloud(points, true, 0, "map");
  const auto& message = cloud.Message();
  EXPECT_EQ(message.width, 2u);
  EXPECT_EQ(message.point_step, 16u);
  EXPECT_EQ(message.row_step, 32u);
  ASSERT_EQ(message.fields._length, 4u);
  EXPECT_STREQ(message.fields._buffer[3].name, "rgb");
  EXPECT_EQ(message.fields._buffer[3].offset, 12u);
  ASSERT_EQ(message.data._length, 32u);
  float y = 0;
  std::memcpy(&y, message.data._buffer + 16 + 4, 4);
  EXPECT_EQ(y, -2.0f);
  std::uint32_t rgb = 0;
  std::memcpy(&rgb, message.data._buffer + 16 + 12, 4);
  EXPECT_EQ(rgb, 0x123456u);
  const PointCloudMessage plain(points, false, 0, "map");
  EXPECT_EQ(plain.Message().point_step, 12u);
  EXPECT_EQ(plain.Message().fields._length, 3u);
}

TEST(OutputMessagesTest, GridCellsAreMinusOneZeroAndHundredFromItsOrigin) {
  OccupancyGrid grid;
  grid.width = 3;
  grid.height = 1;
  grid.resolution = 0.1;
  grid.origin = {-0.5, 0.25};
  grid.cells = {GridCell::kUnknown, GridCell::kFree, GridCell::kOccupied};
  const GridMessage message(grid, 0, "drvslam_grid");
  const auto& m = message.Message();
  EXPECT_STREQ(m.header.frame_id, "drvslam_grid");
  EXPECT_EQ(m.info.width, 3u);
  EXPECT_FLOAT_EQ(m.info.resolution, 0.1f);
  EXPECT_DOUBLE_EQ(m.info.origin.position.x, -0.5);
  EXPECT_DOUBLE_EQ(m.info.origin.orientation.w, 1.0);
  ASSERT_EQ(m.data._length, 3u);
  EXPECT_EQ(m.data._buffer[0], -1);
  EXPECT_EQ(m.data._buffer[1], 0);
  EXPECT_EQ(m.data._buffer[2], 100);
}

TEST(OutputMessagesTest, MotionMaskMarksMovingObjectsOverStaticOnes) {
  DynamicFrameReport report;
  const cv::Size size(4, 2);
  Instance still;
  still.mask = cv::Mat(size, CV_8UC1, cv::Scalar(0));
  still.mask(cv::Rect(0, 0, 3, 2)).setTo(255);
  Instance moving;
  moving.mask = cv::Mat(size, CV_8UC1, cv::Scalar(0));
  moving.mask(cv::Rect(2, 0, 1, 1)).setTo(255);
  report.instances = {moving, still};
  report.objects.resize(2);
  report.objects[0].moving = true;
  MovingRegion region;
  region.box = cv::Rect(3, 1, 1, 1);
  region.mask = cv::Mat(1, 1, CV_8UC1, cv::Scalar(255));
  report.unlabelled.push_back(region);
  const cv::Mat mask = MotionMaskImage(report, size);
  EXPECT_EQ(mask.at<std::uint8_t>(0, 0), 128);
  EXPECT_EQ(mask.at<std::uint8_t>(0, 2), 255);  // moving over static
  EXPECT_EQ(mask.at<std::uint8_t>(1, 3), 255);  // unlabelled motion
  EXPECT_EQ(mask.at<std::uint8_t>(0, 3), 0);
  const MonoImageMessage image(mask, 0, "cam");
  EXPECT_STREQ(image.Message().encoding, "mono8");
  EXPECT_EQ(image.Message().step, 4u);
  EXPECT_EQ(image.Message().data._buffer[2], 255);
}

}  // namespace
}  // namespace drvslam::ros2
