// What the ROS 2 node receives, turned into what System::TrackRGBD takes: sensor_msgs/Image to
// OpenCV images (colour to BGR, depth to metres), sensor_msgs/CameraInfo to camera intrinsics,
// and header stamps to nanoseconds. Each conversion checks the message and throws
// drvslam::Error naming the topic and the problem; nothing here touches DDS.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>

#include "drvslam/core/camera.h"
#include "drvslam/ros2/ros2_msgs.h"

namespace drvslam::ros2 {

// builtin_interfaces/Time <-> nanoseconds since the epoch of the stamp's clock.
std::int64_t StampNanoseconds(const builtin_interfaces_msg_dds__Time_& stamp);
builtin_interfaces_msg_dds__Time_ StampFromNanoseconds(std::int64_t nanoseconds);

// A colour image (encodings rgb8, bgr8, rgba8, bgra8, mono8) as CV_8UC3 BGR, copied out of the
// message. `topic` names the source in errors.
cv::Mat ColourImage(const sensor_msgs_msg_dds__Image_& image, const std::string& topic);

// A depth image as CV_32FC1 metres, 0 where there is no measurement: 16UC1 in millimetres (REP
// 118, what the RealSense and Orbbec drivers publish; 0 = none) or 32FC1 in metres (NaN and
// infinities = none). Big-endian data is swapped.
cv::Mat DepthImageMetres(const sensor_msgs_msg_dds__Image_& image, const std::string& topic);

// Intrinsics from CameraInfo's K (fx, fy, cx, cy), its size, and for the plumb_bob and
// rational_polynomial models D's coefficients k1 k2 p1 p2 k3 (any further nonzero one is an
// error: drvslam's model has no k4..k6). Everything else
// (fps, RGB order) stays as in `base`; the virtual stereo baseline bf keeps base's baseline in
// metres (bf / fx), so "close" depth means the same distance at any focal length. Throws Error
// for a K without positive focal lengths, a zero size, or an unknown distortion model with
// nonzero coefficients.
CameraOptions CameraFromInfo(const sensor_msgs_msg_dds__CameraInfo_& info,
                             const CameraOptions& base, const std::string& topic);

}  // namespace drvslam::ros2
