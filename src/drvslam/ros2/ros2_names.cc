#include <stdexcept>

#include "drvslam/ros2/ros2_msgs.h"

namespace drvslam::ros2 {
namespace {

bool IsNameCharacter(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

[[noreturn]] void Reject(std::string_view ros_topic, const char* why) {
  throw std::invalid_argument("ROS 2 topic name '" + std::string(ros_topic) + "': " + why);
}

}  // namespace

std::string DdsTopicName(std::string_view ros_topic) {
  std::string_view name = ros_topic;
  // A relative name resolves against the root namespace, so both spellings give one topic.
  if (!name.empty() && name.front() == '/') {
    name.remove_prefix(1);
  }
  if (name.empty()) {
    Reject(ros_topic, "empty");
  }
  bool token_start = true;
  for (char c : name) {
    if (c == '~') {
      Reject(ros_topic, "'~' needs a node name to expand");
    }
    if (c == '/') {
      if (token_start) {
        Reject(ros_topic, "empty token (doubled '/')");
      }
      token_start = true;
      continue;
    }
    if (!IsNameCharacter(c)) {
      Reject(ros_topic, "only letters, digits, '_' and '/' are allowed");
    }
    if (token_start && c >= '0' && c <= '9') {
      Reject(ros_topic, "a token may not start with a digit");
    }
    token_start = false;
  }
  if (token_start) {
    Reject(ros_topic, "trailing '/'");
  }
  return "rt/" + std::string(name);
}

}  // namespace drvslam::ros2
