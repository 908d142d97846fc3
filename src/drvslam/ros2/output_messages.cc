#include "drvslam/ros2/output_messages.h"

#include <cstring>
#include <opencv2/imgproc.hpp>

#include "drvslam/dynamic/dynamic_front_end.h"
#include "drvslam/ros2/image_messages.h"

namespace drvslam::ros2 {
namespace {

char* Text(const std::string& text) { return const_cast<char*>(text.c_str()); }

std_msgs_msg_dds__Header_ Header(std::int64_t stamp_ns, const std::string& frame) {
  std_msgs_msg_dds__Header_ header{};
  header.stamp = StampFromNanoseconds(stamp_ns);
  header.frame_id = Text(frame);
  return header;
}

geometry_msgs_msg_dds__Pose_ PoseOf(const SE3& transform) {
  geometry_msgs_msg_dds__Pose_ pose{};
  const Eigen::Vector3d& t = transform.Translation();
  const Eigen::Quaterniond q = transform.Quaternion().normalized();
  pose.position = {t.x(), t.y(), t.z()};
  pose.orientation = {q.x(), q.y(), q.z(), q.w()};
  return pose;
}

geometry_msgs_msg_dds__Transform_ TransformOf(const SE3& transform) {
  const geometry_msgs_msg_dds__Pose_ pose = PoseOf(transform);
  geometry_msgs_msg_dds__Transform_ out{};
  out.translation = {pose.position.x, pose.position.y, pose.position.z};
  out.rotation = pose.orientation;
  return out;
}

template <typename Sequence, typename Element>
Sequence BorrowOne(Element* element) {
  Sequence sequence{};
  sequence._length = 1;
  sequence._maximum = 1;
  sequence._buffer = element;
  sequence._release = false;
  return sequence;
}

}  // namespace

TransformMessage::TransformMessage(const SE3& T_parent_child, std::int64_t stamp_ns,
                                   const std::string& parent, const std::string& child)
    : parent_(parent), child_(child) {
  transform_.header = Header(stamp_ns, parent_);
  transform_.child_frame_id = Text(child_);
  transform_.transform = TransformOf(T_parent_child);
  message_.transforms =
      BorrowOne<dds_sequence_geometry_msgs_msg_dds__TransformStamped_>(&transform_);
}

PoseMessages::PoseMessages(const OdometryEstimate& estimate, std::int64_t stamp_ns,
                           const std::string& map_frame, const std::string& camera_frame)
    : map_frame_(map_frame),
      camera_frame_(camera_frame),
      transform_(estimate.T_wc, stamp_ns, map_frame, camera_frame) {
  odometry_.header = Header(stamp_ns, map_frame_);
  odometry_.child_frame_id = Text(camera_frame_);
  odometry_.pose.pose = PoseOf(estimate.T_wc);
  const Eigen::Vector3d& v = estimate.linear_velocity;
  const Eigen::Vector3d& w = estimate.angular_velocity;
  odometry_.twist.twist.linear = {v.x(), v.y(), v.z()};
  odometry_.twist.twist.angular = {w.x(), w.y(), w.z()};
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) {
      odometry_.pose.covariance[6 * r + c] = estimate.pose_covariance(r, c);
      odometry_.twist.covariance[6 * r + c] = estimate.twist_covariance(r, c);
    }
  }
  pose_.header = odometry_.header;
  pose_.pose = odometry_.pose.pose;
}

PointCloudMessage::PointCloudMessage(const DenseCloud& points, bool with_colour,
                                     std::int64_t stamp_ns, const std::string& frame)
    : frame_(frame), names_{"x", "y", "z", "rgb"} {
  const std::uint32_t step = with_colour ? 16 : 12;
  for (std::size_t i = 0; i < (with_colour ? 4u : 3u); ++i) {
    sensor_msgs_msg_dds__PointField_ field{};
    field.name = Text(names_[i]);
    field.offset = static_cast<std::uint32_t>(4 * i);
    field.datatype = point_field::kFloat32;
    field.count = 1;
    fields_.push_back(field);
  }
  data_.resize(points.size() * step);
  std::uint8_t* out = data_.data();
  for (const DensePoint& point : points) {
    std::memcpy(out, point.position.data(), 12);
    if (with_colour) {
      // PCL's packing: 0x00RRGGBB in the bits of a float, little endian.
      const std::uint32_t rgb = (static_cast<std::uint32_t>(point.r) << 16) |
                                (static_cast<std::uint32_t>(point.g) << 8) | point.b;
      std::memcpy(out + 12, &rgb, 4);
    }
    out += step;
  }
  message_.header = Header(stamp_ns, frame_);
  message_.height = 1;
  message_.width = static_cast<std::uint32_t>(points.size());
  message_.fields = BorrowSequence<dds_sequence_sensor_msgs_msg_dds__PointField_>(fields_);
  message_.is_bigendian = false;
  message_.point_step = step;
  message_.row_step = step * message_.width;
  message_.data = BorrowSequence<dds_sequence_octet>(data_);
  message_.is_dense = true;
}

GridMessage::GridMessage(const OccupancyGrid& grid, std::int64_t stamp_ns,
                         const std::string& grid_frame)
    : frame_(grid_frame) {
  cells_.reserve(grid.cells.size());
  for (GridCell cell : grid.cells) {
    cells_.push_back(cell == GridCell::kOccupied ? 100 : cell == GridCell::kFree ? 0 : -1);
  }
  message_.header = Header(stamp_ns, frame_);
  message_.info.map_load_time = message_.header.stamp;
  message_.info.resolution = static_cast<float>(grid.resolution);
  message_.info.width = static_cast<std::uint32_t>(grid.width);
  message_.info.height = static_cast<std::uint32_t>(grid.height);
  message_.info.origin.position = {grid.origin.x(), grid.origin.y(), 0.0};
  message_.info.origin.orientation = {0.0, 0.0, 0.0, 1.0};
  message_.data = BorrowSequence<dds_sequence_int8>(cells_);
}

MonoImageMessage::MonoImageMessage(const cv::Mat& mono, std::int64_t stamp_ns,
                                   const std::string& frame)
    : frame_(frame) {
  CV_Assert(mono.type() == CV_8UC1);
  data_.resize(mono.total());
  for (int row = 0; row < mono.rows; ++row) {
    std::memcpy(data_.data() + static_cast<std::size_t>(row) * mono.cols, mono.ptr(row),
                static_cast<std::size_t>(mono.cols));
  }
  message_.header = Header(stamp_ns, frame_);
  message_.height = static_cast<std::uint32_t>(mono.rows);
  message_.width = static_cast<std::uint32_t>(mono.cols);
  message_.encoding = Text(encoding_);
  message_.is_bigendian = 0;
  message_.step = static_cast<std::uint32_t>(mono.cols);
  message_.data = BorrowSequence<dds_sequence_octet>(data_);
}

cv::Mat MotionMaskImage(const DynamicFrameReport& report, cv::Size size) {
  cv::Mat mask(size, CV_8UC1, cv::Scalar(0));
  // Static objects first, so a moving one drawn over an overlap wins.
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t i = 0; i < report.instances.size(); ++i) {
      const Instance& instance = report.instances[i];
      const bool moving = i < report.objects.size() && report.objects[i].moving;
      if (moving != (pass == 1) || instance.mask.size() != size) continue;
      mask.setTo(cv::Scalar(moving ? 255 : 128), instance.mask);
    }
  }
  for (const MovingRegion& region : report.unlabelled) {
    const cv::Rect box = region.box & cv::Rect(0, 0, size.width, size.height);
    if (box.empty() || region.mask.size() != region.box.size()) continue;
    mask(box).setTo(cv::Scalar(255), region.mask(box - region.box.tl()));
  }
  return mask;
}

}  // namespace drvslam::ros2
