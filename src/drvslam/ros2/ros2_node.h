// RunRos2Node: `drvslam ros2`, the realtime pipeline as a ROS 2 node on the wire (Cyclone DDS,
// no ROS 2 install). It subscribes to a camera's colour and depth images (and CameraInfo when
// the settings give no intrinsics), pairs them by stamp, tracks the newest pair as a live
// camera run does (frames that arrive while tracking is busy are skipped and counted), and
// publishes the camera's pose, /tf, the sparse and dense maps, the moving-object mask and the
// occupancy grid. When stopped it writes what `drvslam run` writes (trajectories, stats.json,
// the dense map, map.yaml + map.pgm) and publishes the final maps. docs/ros2.md describes the
// topics, their QoS and frames.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include "drvslam/tools/runner/sequence_runner.h"

namespace drvslam::ros2 {

struct Ros2Topics {
  // Subscribed (the RealSense ROS 2 wrapper's defaults with aligned depth).
  std::string colour = "/camera/camera/color/image_raw";
  std::string depth = "/camera/camera/aligned_depth_to_color/image_raw";
  std::string camera_info = "/camera/camera/color/camera_info";
  // Published.
  std::string odometry = "/drvslam/odometry";
  std::string pose = "/drvslam/pose";
  std::string tf = "/tf";
  std::string tf_static = "/tf_static";
  std::string map_points = "/drvslam/map_points";
  std::string dense_map = "/drvslam/dense_map";
  std::string moving_mask = "/drvslam/moving_mask";
  std::string grid = "/drvslam/grid";
};

struct Ros2NodeOptions {
  // Settings file, segmenter (yolo or none), --dynamic, --dense, --loop, output folder and
  // --strict-settings, as for `drvslam run`; no dataset, never sequential.
  RunOptions run;
  Ros2Topics topics;
  std::string map_frame = "map";                // drvslam's world: the first camera's optical frame
  std::string camera_frame = "drvslam_camera";  // the camera's optical frame as tracked
  std::string grid_frame = "drvslam_grid";      // the floor-aligned frame of the grid
  double pair_tolerance_s = 0.02;  // colour and depth stamps at most this far apart pair
  double cloud_period_s = 2.0;     // map point and dense clouds at most this often
  double grid_period_s = 5.0;      // the occupancy grid at most this often (it builds an OctoMap)
  double idle_exit_s = 0.0;        // stop after this long without images, once some came; 0: never
  std::size_t max_frames = 0;      // stop after tracking this many pairs; 0: never
};

struct Ros2NodeSummary {
  RunSummary run;  // what `drvslam run` reports (stats.json holds it)
  std::int32_t domain = 0;
  std::string camera_source;  // "settings FILE" or "CameraInfo on TOPIC"
  std::size_t colour_received = 0;
  std::size_t depth_received = 0;
  std::size_t pairs_tracked = 0;    // pairs given to tracking
  std::size_t pairs_skipped = 0;    // colour images passed over for a newer pair
  std::size_t images_dropped = 0;   // images whose partner never came
  std::size_t images_rejected = 0;  // unusable messages (encoding, size, data)
  std::size_t poses_published = 0;  // verified poses (tentative and lost ones are not published)
  std::map<std::string, std::size_t> published;  // messages per topic
};

// Runs until `stop` becomes true, idle_exit_s passes without images, or max_frames pairs were
// tracked. `started` (may be empty) is called once the node's topics exist, with the domain.
// Throws Error for bad options, settings or environment (ROS_DOMAIN_ID), and when 30 images in a
// row are unusable; outputs computed so far are written first.
Ros2NodeSummary RunRos2Node(const Ros2NodeOptions& options, const std::atomic<bool>* stop,
                            const std::function<void(const std::string&)>& started = nullptr);

}  // namespace drvslam::ros2
