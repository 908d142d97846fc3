// drvslam ros2: the realtime pipeline as a ROS 2 node over Cyclone DDS (docs/ros2.md). Built
// only with Cyclone DDS (cmake/DrvslamDds.cmake); without it the command exists only to say so.
#include <csignal>
#include <cstdio>
#include <memory>
#include <string>

#include "command_registry.h"
#include "drvslam/core/error.h"

#if defined(DRVSLAM_HAS_ROS2_NODE)
#include "drvslam/ros2/ros2_node.h"
#endif

namespace drvslam::cli {
namespace {

#if defined(DRVSLAM_HAS_ROS2_NODE)

std::atomic<bool> g_ros2_stop_requested{false};

void RequestRos2Stop(int) { g_ros2_stop_requested = true; }

void PrintSummary(const ros2::Ros2NodeSummary& summary, const std::string& out_dir) {
  const SystemStats& s = summary.run.stats;
  std::printf("domain:      %d\n", summary.domain);
  std::printf("camera:      %s\n", summary.camera_source.empty() ? "(no CameraInfo came)"
                                                                 : summary.camera_source.c_str());
  std::printf("segmenter:   %s\n", summary.run.segmenter.c_str());
  std::printf("received:    %zu colour, %zu depth images (%zu unusable)\n", summary.colour_received,
              summary.depth_received, summary.images_rejected);
  std::printf(
      "tracked:     %zu of %zu pairs given to tracking; %zu pairs skipped (tracking was "
      "busy), %zu images never paired\n",
      s.tracked, summary.pairs_tracked, summary.pairs_skipped, summary.images_dropped);
  std::printf("published:   %zu verified poses\n", summary.poses_published);
  for (const auto& [topic, count] : summary.published) {
    std::printf("             %-28s %zu\n", topic.c_str(), count);
  }
  std::printf("keyframes:   %zu, map points %zu\n", s.keyframes, s.map_points);
  if (summary.pairs_tracked > 0) {
    std::printf(
        "wrote:       %s/{CameraTrajectory.txt,TrackedCameraTrajectory.txt,"
        "OnlineCameraTrajectory.txt,KeyFrameTrajectory.txt,stats.json}%s\n",
        out_dir.c_str(), s.dense ? " and the dense map, map.yaml, map.pgm" : "");
  }
}

#endif

const bool kRos2CommandRegistered = RegisterCommand("ros2", [](CLI::App& root) {
  CLI::App* command = root.add_subcommand(
      "ros2", "run as a ROS 2 node over DDS: camera topics in, pose, /tf and maps out");
#if defined(DRVSLAM_HAS_ROS2_NODE)
  auto options = std::make_shared<ros2::Ros2NodeOptions>();
  options->run.out_dir = "out";
  ros2::Ros2Topics& topics = options->topics;
  command->add_option("--config", options->run.config,
                      "settings file (default: TUM fr3 settings with the intrinsics of the first "
                      "CameraInfo message)");
  command->add_option("--out", options->run.out_dir, "output folder, written when the node stops")
      ->capture_default_str();
  command
      ->add_option("--segmenter", options->run.dynamic.segmenter,
                   "yolo|none (default: yolo with --model, else Segmentation.backend)")
      ->check(CLI::IsMember({"yolo", "none"}));
  command->add_option("--model", options->run.dynamic.model, "YOLO segmentation ONNX file");
  command->add_option("--dynamic", options->run.dynamic.dynamic, "on|off: dynamic-object handling")
      ->check(CLI::IsMember({"on", "off"}));
  command->add_option("--dense", options->run.dense, "on|off: dense map, clouds and grid")
      ->check(CLI::IsMember({"on", "off"}));
  command->add_option("--loop", options->run.loop, "on|off: loop closing")
      ->check(CLI::IsMember({"on", "off"}));
  command->add_flag("--strict-settings", options->run.strict_settings,
                    "unknown keys in drvslam's settings sections are errors");
  command->add_option("--colour-topic", topics.colour, "sensor_msgs/Image, rgb8 or bgr8")
      ->capture_default_str();
  command->add_option("--depth-topic", topics.depth, "sensor_msgs/Image, 16UC1 (mm) or 32FC1 (m)")
      ->capture_default_str();
  command->add_option("--camera-info-topic", topics.camera_info, "sensor_msgs/CameraInfo")
      ->capture_default_str();
  command->add_option("--odometry-topic", topics.odometry)->capture_default_str();
  command->add_option("--pose-topic", topics.pose)->capture_default_str();
  command->add_option("--map-points-topic", topics.map_points)->capture_default_str();
  command->add_option("--dense-map-topic", topics.dense_map)->capture_default_str();
  command->add_option("--moving-mask-topic", topics.moving_mask)->capture_default_str();
  command->add_option("--grid-topic", topics.grid)->capture_default_str();
  command
      ->add_option("--tf-topic", topics.tf,
                   "the camera pose's transform; another name keeps it out of the /tf tree")
      ->capture_default_str();
  command->add_option("--map-frame", options->map_frame, "frame of poses and clouds")
      ->capture_default_str();
  command->add_option("--camera-frame", options->camera_frame, "child frame of the camera pose")
      ->capture_default_str();
  command->add_option("--grid-frame", options->grid_frame, "floor-aligned frame of the grid")
      ->capture_default_str();
  command
      ->add_option("--pair-tolerance", options->pair_tolerance_s,
                   "seconds: colour and depth stamps at most this far apart pair")
      ->capture_default_str();
  command->add_option("--cloud-period", options->cloud_period_s, "seconds between clouds")
      ->capture_default_str();
  command->add_option("--grid-period", options->grid_period_s, "seconds between grids")
      ->capture_default_str();
  command
      ->add_option("--idle-exit", options->idle_exit_s,
                   "stop after this many seconds without images, once images came (0: never)")
      ->capture_default_str();
  command->add_option("--max-frames", options->max_frames, "stop after tracking N pairs (0: never)")
      ->check(CLI::NonNegativeNumber);
  command->callback([options] {
    std::signal(SIGINT, RequestRos2Stop);
    std::signal(SIGTERM, RequestRos2Stop);
    const ros2::Ros2NodeSummary summary =
        ros2::RunRos2Node(*options, &g_ros2_stop_requested, [](const std::string& line) {
          std::printf("ros2 node: %s\n", line.c_str());
          std::fflush(stdout);
        });
    PrintSummary(summary, options->run.out_dir);
  });
#else
  command->allow_extras();
  command->callback([] {
    throw Error(
        "this drvslam was built without Cyclone DDS, so it has no ROS 2 node: install "
        "cyclonedds-dev and cyclonedds-tools (scripts/install-deps.sh) and rebuild");
  });
#endif
});

}  // namespace
}  // namespace drvslam::cli
