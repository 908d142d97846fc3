// The ROS 2 message types on DDS, without ROS 2: the C types idlc generates from idl/ (named
// pkg_msg_dds__Name_, registered as "pkg::msg::dds_::Name_", as ROS 2's rmw layer names them),
// the traits that tie each topic type to its descriptor and ROS 2 name, and ROS 2's topic-name
// mapping. Only built with Cyclone DDS (cmake/DrvslamDds.cmake).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "builtin_interfaces.h"
#include "geometry_msgs.h"
#include "nav_msgs.h"
#include "sensor_msgs.h"
#include "std_msgs.h"
#include "tf2_msgs.h"

namespace drvslam::ros2 {

// ROS 2 maps topic "/a/b" (or "a/b", relative to the root namespace) to the DDS topic "rt/a/b".
// Throws std::invalid_argument for a name ROS 2 would reject: empty, a trailing or doubled '/',
// a '~' (needs a node name), a character other than [A-Za-z0-9_/], or a token that starts with
// a digit.
std::string DdsTopicName(std::string_view ros_topic);

// A DDS sequence (the generated dds_sequence_* types) over `elements` without copying: the
// sequence does not own them (_release false), so `elements` must outlive every use of it.
template <typename Sequence, typename Element>
Sequence BorrowSequence(std::vector<Element>& elements) {
  Sequence sequence{};
  sequence._length = static_cast<std::uint32_t>(elements.size());
  sequence._maximum = sequence._length;
  sequence._buffer = elements.data();
  sequence._release = false;
  return sequence;
}

// sensor_msgs/PointField's datatype constants (not in the IDL: idlc reads INT8 as the keyword).
namespace point_field {
inline constexpr std::uint8_t kInt8 = 1;
inline constexpr std::uint8_t kUint8 = 2;
inline constexpr std::uint8_t kInt16 = 3;
inline constexpr std::uint8_t kUint16 = 4;
inline constexpr std::uint8_t kInt32 = 5;
inline constexpr std::uint8_t kUint32 = 6;
inline constexpr std::uint8_t kFloat32 = 7;
inline constexpr std::uint8_t kFloat64 = 8;
}  // namespace point_field

// MessageTraits<T> for each type drvslam sends or receives as a topic: Descriptor() for
// dds_create_topic and the ROS 2 name ("sensor_msgs/msg/Image") that ROS 2 tools show.
template <typename Message>
struct MessageTraits;

#define DRVSLAM_ROS2_MESSAGE(pkg, name)                                                         \
  template <>                                                                                   \
  struct MessageTraits<pkg##_msg_dds__##name##_> {                                              \
    static const dds_topic_descriptor_t& Descriptor() { return pkg##_msg_dds__##name##__desc; } \
    static constexpr const char* kRosName = #pkg "/msg/" #name;                                 \
  };

DRVSLAM_ROS2_MESSAGE(std_msgs, Header)
DRVSLAM_ROS2_MESSAGE(sensor_msgs, Image)
DRVSLAM_ROS2_MESSAGE(sensor_msgs, CameraInfo)
DRVSLAM_ROS2_MESSAGE(sensor_msgs, PointCloud2)
DRVSLAM_ROS2_MESSAGE(geometry_msgs, PoseStamped)
DRVSLAM_ROS2_MESSAGE(geometry_msgs, TransformStamped)
DRVSLAM_ROS2_MESSAGE(nav_msgs, Odometry)
DRVSLAM_ROS2_MESSAGE(nav_msgs, OccupancyGrid)
DRVSLAM_ROS2_MESSAGE(tf2_msgs, TFMessage)

#undef DRVSLAM_ROS2_MESSAGE

}  // namespace drvslam::ros2
