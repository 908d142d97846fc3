// What the ROS 2 node publishes, built from drvslam's results: the camera's pose as
// nav_msgs/Odometry, geometry_msgs/PoseStamped and a tf2_msgs/TFMessage; point clouds as
// sensor_msgs/PointCloud2; the occupancy grid as nav_msgs/OccupancyGrid; the moving-object mask
// as a mono8 sensor_msgs/Image. Each class owns the buffers its message points into, so it is
// neither copied nor moved: build one, Write() its Message(), let it go.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "drvslam/core/se3.h"
#include "drvslam/dense/dense_point.h"
#include "drvslam/dense/occupancy_grid.h"
#include "drvslam/ros2/ros2_msgs.h"

namespace drvslam {
struct DynamicFrameReport;
}

namespace drvslam::ros2 {

class NonMovable {
 public:
  NonMovable() = default;
  NonMovable(const NonMovable&) = delete;
  NonMovable& operator=(const NonMovable&) = delete;
};

// One transform `parent` -> `child` (the pose of child in parent) as a TFMessage.
class TransformMessage : NonMovable {
 public:
  TransformMessage(const SE3& T_parent_child, std::int64_t stamp_ns, const std::string& parent,
                   const std::string& child);
  const tf2_msgs_msg_dds__TFMessage_& Message() const { return message_; }

 private:
  std::string parent_;
  std::string child_;
  geometry_msgs_msg_dds__TransformStamped_ transform_{};
  tf2_msgs_msg_dds__TFMessage_ message_{};
};

// What Odometry carries of one frame (TrackResult's causal pose, velocity and covariances).
struct OdometryEstimate {
  SE3 T_wc;
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();   // camera frame, m/s
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // camera frame, rad/s
  // Over (x, y, z, rotation about the parent's x, y, z), parent frame.
  Eigen::Matrix<double, 6, 6> pose_covariance = Eigen::Matrix<double, 6, 6>::Zero();
  // Over (linear, angular velocity), child frame.
  Eigen::Matrix<double, 6, 6> twist_covariance = Eigen::Matrix<double, 6, 6>::Zero();
};

// The camera pose T_wc at `stamp_ns` in frame `map_frame` (drvslam's world frame: the first
// camera's optical frame), child `camera_frame`. Odometry carries the pose with its covariance
// and, as REP 105 asks, the twist and its covariance in the child frame (row-major 6x6).
class PoseMessages : NonMovable {
 public:
  PoseMessages(const OdometryEstimate& estimate, std::int64_t stamp_ns,
               const std::string& map_frame, const std::string& camera_frame);
  const nav_msgs_msg_dds__Odometry_& Odometry() const { return odometry_; }
  const geometry_msgs_msg_dds__PoseStamped_& Pose() const { return pose_; }
  const tf2_msgs_msg_dds__TFMessage_& Transforms() const { return transform_.Message(); }

 private:
  std::string map_frame_;
  std::string camera_frame_;
  nav_msgs_msg_dds__Odometry_ odometry_{};
  geometry_msgs_msg_dds__PoseStamped_ pose_{};
  TransformMessage transform_;  // for /tf
};

// An unordered cloud (height 1) of float32 x, y, z, and with `with_colour` a float32 "rgb"
// field packing 8-bit r, g, b as PCL and RViz read it.
class PointCloudMessage : NonMovable {
 public:
  PointCloudMessage(const DenseCloud& points, bool with_colour, std::int64_t stamp_ns,
                    const std::string& frame);
  const sensor_msgs_msg_dds__PointCloud2_& Message() const { return message_; }

 private:
  std::string frame_;
  std::vector<std::string> names_;
  std::vector<sensor_msgs_msg_dds__PointField_> fields_;
  std::vector<std::uint8_t> data_;
  sensor_msgs_msg_dds__PointCloud2_ message_{};
};

// The grid in its own frame `grid_frame` (x, y on the floor, z up; its pose in the world goes
// on /tf_static): cells -1 unknown, 0 free, 100 occupied, row-major from cell (0, 0).
class GridMessage : NonMovable {
 public:
  GridMessage(const OccupancyGrid& grid, std::int64_t stamp_ns, const std::string& grid_frame);
  const nav_msgs_msg_dds__OccupancyGrid_& Message() const { return message_; }

 private:
  std::string frame_;
  std::vector<std::int8_t> cells_;
  nav_msgs_msg_dds__OccupancyGrid_ message_{};
};

// A CV_8UC1 image as mono8.
class MonoImageMessage : NonMovable {
 public:
  MonoImageMessage(const cv::Mat& mono, std::int64_t stamp_ns, const std::string& frame);
  const sensor_msgs_msg_dds__Image_& Message() const { return message_; }

 private:
  std::string frame_;
  std::string encoding_ = "mono8";
  std::vector<std::uint8_t> data_;
  sensor_msgs_msg_dds__Image_ message_{};
};

// The frame's objects as a CV_8UC1 image of `size`: 255 on objects judged moving and on
// unlabelled moving regions (what tracking ignored), 128 on detected objects judged static,
// 0 elsewhere.
cv::Mat MotionMaskImage(const DynamicFrameReport& report, cv::Size size);

}  // namespace drvslam::ros2
