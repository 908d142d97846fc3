#include "drvslam/ros2/ros2_node.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <filesystem>
#include <future>
#include <memory>
#include <optional>
#include <utility>

#include "drvslam/core/error.h"
#include "drvslam/core/thread_name.h"
#include "drvslam/dense/dense_export.h"
#include "drvslam/dense/dense_octomap.h"
#include "drvslam/dense/grid_export.h"
#include "drvslam/dynamic/dynamic_front_end.h"
#include "drvslam/ros2/dds_entities.h"
#include "drvslam/ros2/image_messages.h"
#include "drvslam/ros2/output_messages.h"
#include "drvslam/ros2/stamp_pairing.h"
#include "drvslam/system.h"

namespace drvslam::ros2 {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr dds_duration_t kWaitStep = DDS_MSECS(100);
// How long the end of a run waits for subscribers to acknowledge the final messages.
constexpr dds_duration_t kFinalAcknowledgement = DDS_SECS(2);

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::int64_t Nanoseconds(double seconds) { return static_cast<std::int64_t>(seconds * 1e9); }

// The topics the node publishes, with ROS 2's usual QoS for each (docs/ros2.md lists them).
struct Publishers {
  Publishers(const DdsHandle& participant, const Ros2Topics& topics)
      : odometry(participant, topics.odometry, TopicQos::kReliable, 10),
        pose(participant, topics.pose, TopicQos::kReliable, 10),
        tf(participant, topics.tf, TopicQos::kReliable, 100),
        tf_static(participant, topics.tf_static, TopicQos::kLatched),
        map_points(participant, topics.map_points, TopicQos::kReliable, 1),
        dense_map(participant, topics.dense_map, TopicQos::kReliable, 1),
        moving_mask(participant, topics.moving_mask, TopicQos::kSensorData, 1),
        grid(participant, topics.grid, TopicQos::kLatched) {}

  std::map<std::string, std::size_t> Counts() const {
    return {{odometry.RosTopic(), odometry.Written()},
            {pose.RosTopic(), pose.Written()},
            {tf.RosTopic(), tf.Written()},
            {tf_static.RosTopic(), tf_static.Written()},
            {map_points.RosTopic(), map_points.Written()},
            {dense_map.RosTopic(), dense_map.Written()},
            {moving_mask.RosTopic(), moving_mask.Written()},
            {grid.RosTopic(), grid.Written()}};
  }

  // Gives reliable subscribers time to receive the last messages before the writers go.
  void WaitForAcknowledgements() {
    odometry.WaitForAcknowledgements(kFinalAcknowledgement);
    tf.WaitForAcknowledgements(kFinalAcknowledgement);
    tf_static.WaitForAcknowledgements(kFinalAcknowledgement);
    grid.WaitForAcknowledgements(kFinalAcknowledgement);
    dense_map.WaitForAcknowledgements(kFinalAcknowledgement);
  }

  TopicWriter<nav_msgs_msg_dds__Odometry_> odometry;
  TopicWriter<geometry_msgs_msg_dds__PoseStamped_> pose;
  TopicWriter<tf2_msgs_msg_dds__TFMessage_> tf;
  TopicWriter<tf2_msgs_msg_dds__TFMessage_> tf_static;
  TopicWriter<sensor_msgs_msg_dds__PointCloud2_> map_points;
  TopicWriter<sensor_msgs_msg_dds__PointCloud2_> dense_map;
  TopicWriter<sensor_msgs_msg_dds__Image_> moving_mask;
  TopicWriter<nav_msgs_msg_dds__OccupancyGrid_> grid;
};

// The dense map and, when asked, its occupancy grid, built off the tracking loop.
struct MapSnapshot {
  DenseCloud dense;
  std::optional<OccupancyGrid> grid;
};

MapSnapshot BuildSnapshot(DenseMapper* dense, GridOptions grid_options, bool with_grid) {
  NameCurrentThread("drv-ros-map");  // runs on a std::async thread of its own
  DenseMapRays rays = dense->AssembleRays();
  MapSnapshot snapshot;
  const double resolution = dense->Options().octomap_resolution;
  if (with_grid && grid_options.enabled && resolution > 0.0) {
    std::optional<GridExport> grid =
        BuildOccupancyGrid(rays, SampleDenseOctoMap(rays, resolution), grid_options);
    if (grid) snapshot.grid = std::move(grid->grid);
  }
  snapshot.dense = std::move(rays.cloud);
  return snapshot;
}

class Ros2Node {
 public:
  Ros2Node(const Ros2NodeOptions& options, Ros2NodeSummary* summary)
      : options_(options),
        summary_(summary),
        setup_(PrepareRun(options.run)),
        participant_(CreateParticipant(RosDomainId())),
        colour_(participant_, options.topics.colour, TopicQos::kSensorData, 5),
        depth_(participant_, options.topics.depth, TopicQos::kSensorData, 5),
        camera_info_(participant_, options.topics.camera_info, TopicQos::kSensorData, 1),
        publishers_(participant_, options.topics),
        waiter_(participant_),
        pairer_(Nanoseconds(options.pair_tolerance_s)) {
    CheckOptions();
    waiter_.Attach(colour_.Entity());
    waiter_.Attach(depth_.Entity());
    waiter_.Attach(camera_info_.Entity());
    summary_->domain = static_cast<std::int32_t>(RosDomainId());
    RunSummary& run = summary_->run;
    run.dataset = "ros2:" + options.topics.colour;
    run.settings_source = setup_.settings_source;
    run.dynamic_setup = setup_.dynamic.description;
    run.segmenter = setup_.dynamic.segmenter_label;
    run.paced = true;
    if (!options.run.config.empty()) {
      camera_ = setup_.settings.camera;
      summary_->camera_source = "settings " + options.run.config;
    }
  }

  void Run(const std::atomic<bool>* stop) {
    started_ = Clock::now();
    last_image_ = started_;
    try {
      while (!(stop && stop->load()) && !Finished()) Step();
    } catch (...) {
      try {
        Finish();
      } catch (const std::exception& error) {
        spdlog::error("could not write the outputs after the failure: {}", error.what());
      }
      throw;
    }
    Finish();
  }

 private:
  void CheckOptions() const {
    if (options_.run.sequential) throw Error("drvslam ros2 has no --sequential: it is live");
    if (!(options_.pair_tolerance_s > 0.0)) throw Error("--pair-tolerance must be positive");
    if (!(options_.cloud_period_s > 0.0) || !(options_.grid_period_s > 0.0)) {
      throw Error("--cloud-period and --grid-period must be positive");
    }
    if (options_.idle_exit_s < 0.0) throw Error("--idle-exit must not be negative");
  }

  bool Finished() const {
    if (options_.max_frames > 0 && summary_->pairs_tracked >= options_.max_frames) return true;
    const bool images_came = summary_->colour_received > 0 || summary_->depth_received > 0;
    return options_.idle_exit_s > 0.0 && images_came &&
           SecondsSince(last_image_) > options_.idle_exit_s;
  }

  void Step() {
    waiter_.Wait(kWaitStep);
    TakeMessages();
    if (!system_ && !StartSystem()) return;
    PublishSnapshotWhenReady();
    std::optional<RgbdPair> pair = pairer_.TakeNewest();
    if (!pair) return;
    Track(*pair);
    PublishPeriodicMaps(pair->stamp_ns);
  }

  void TakeMessages() {
    camera_info_.Take([this](const sensor_msgs_msg_dds__CameraInfo_& info) {
      if (camera_) return;
      Guard([&] {
        camera_ = CameraFromInfo(info, setup_.settings.camera, options_.topics.camera_info);
      });
      if (camera_) summary_->camera_source = "CameraInfo on " + options_.topics.camera_info;
    });
    colour_.Take([this](const sensor_msgs_msg_dds__Image_& image) {
      ++summary_->colour_received;
      last_image_ = Clock::now();
      Guard([&] {
        pairer_.AddColour(StampNanoseconds(image.header.stamp),
                          ColourImage(image, options_.topics.colour));
      });
    });
    depth_.Take([this](const sensor_msgs_msg_dds__Image_& image) {
      ++summary_->depth_received;
      last_image_ = Clock::now();
      Guard([&] {
        pairer_.AddDepth(StampNanoseconds(image.header.stamp),
                         DepthImageMetres(image, options_.topics.depth));
      });
    });
  }

  // Runs `convert`; an unusable message (an Error) is rejected.
  template <typename Convert>
  void Guard(const Convert& convert) {
    try {
      convert();
      consecutive_rejected_ = 0;
    } catch (const Error& error) {
      Reject(error);
    }
  }

  // Counts and warns about an unusable message; too many in a row (the limit `drvslam run`
  // applies to unreadable frames) end the run.
  void Reject(const Error& error) {
    ++summary_->images_rejected;
    if (++consecutive_rejected_ >= kMaxConsecutiveRejectedFrames) {
      throw Error(std::to_string(kMaxConsecutiveRejectedFrames) +
                  " messages in a row were unusable; the last: " + error.what());
    }
    if (summary_->images_rejected <= 5) spdlog::warn("skipped: {}", error.what());
  }

  // Builds the System once the intrinsics are known; false while they are not.
  bool StartSystem() {
    if (!camera_) {
      if (SecondsSince(last_waiting_note_) > 5.0) {
        spdlog::info("waiting for CameraInfo on {} (or give --config with the intrinsics)",
                     options_.topics.camera_info);
        last_waiting_note_ = Clock::now();
      }
      return false;
    }
    Settings settings = setup_.settings;
    settings.camera = *camera_;
    system_ = std::make_unique<System>(settings, setup_.tracker, setup_.system);
    spdlog::info("tracking {} x {} images (fx {:.1f}), camera from {}", camera_->width,
                 camera_->height, camera_->fx, summary_->camera_source);
    return true;
  }

  void Track(const RgbdPair& pair) {
    TrackResult result;
    try {
      result = system_->TrackRGBD(pair.bgr, pair.depth, static_cast<double>(pair.stamp_ns) * 1e-9);
      consecutive_rejected_ = 0;
    } catch (const Error& error) {
      Reject(error);
      return;
    }
    ++summary_->pairs_tracked;
    last_stamp_ns_ = pair.stamp_ns;
    if (result.pose_valid && result.quality == LocalizationQuality::kVerified) {
      OdometryEstimate estimate;
      estimate.T_wc = result.T_wc;
      estimate.linear_velocity = result.linear_velocity;
      estimate.angular_velocity = result.angular_velocity;
      estimate.pose_covariance = result.pose_covariance;
      estimate.twist_covariance = result.twist_covariance;
      const PoseMessages messages(estimate, pair.stamp_ns, options_.map_frame,
                                  options_.camera_frame);
      publishers_.odometry.Write(messages.Odometry());
      publishers_.pose.Write(messages.Pose());
      publishers_.tf.Write(messages.Transforms());
      ++summary_->poses_published;
    }
    if (system_->Dynamic() && publishers_.moving_mask.Subscribers() > 0) {
      const MonoImageMessage mask(
          MotionMaskImage(system_->Dynamic()->LastReport(), pair.bgr.size()), pair.stamp_ns,
          options_.camera_frame);
      publishers_.moving_mask.Write(mask.Message());
    }
  }

  void PublishPeriodicMaps(std::int64_t stamp_ns) {
    if (SecondsSince(last_clouds_) < options_.cloud_period_s) return;
    last_clouds_ = Clock::now();
    PublishMapPoints(stamp_ns);
    DenseMapper* dense = system_->Dense();
    if (dense == nullptr || snapshot_.valid()) return;
    const bool with_grid = SecondsSince(last_grid_) >= options_.grid_period_s;
    // Assembling the dense map costs CPU beside tracking: only for a grid or a subscriber.
    if (!with_grid && publishers_.dense_map.Subscribers() == 0) return;
    if (with_grid) last_grid_ = Clock::now();
    snapshot_stamp_ns_ = stamp_ns;
    snapshot_ = std::async(std::launch::async, BuildSnapshot, dense, setup_.grid, with_grid);
  }

  void PublishMapPoints(std::int64_t stamp_ns) {
    if (publishers_.map_points.Subscribers() == 0) return;
    const PointCloudMessage cloud(SparseMapCloud(system_->GetMap()), false, stamp_ns,
                                  options_.map_frame);
    publishers_.map_points.Write(cloud.Message());
  }

  void PublishSnapshotWhenReady() {
    if (!snapshot_.valid() ||
        snapshot_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
      return;
    }
    const MapSnapshot snapshot = snapshot_.get();
    PublishDense(snapshot.dense, snapshot_stamp_ns_);
    if (snapshot.grid) PublishGrid(*snapshot.grid, snapshot_stamp_ns_);
  }

  void PublishDense(const DenseCloud& cloud, std::int64_t stamp_ns) {
    if (publishers_.dense_map.Subscribers() == 0) return;
    const PointCloudMessage message(cloud, true, stamp_ns, options_.map_frame);
    publishers_.dense_map.Write(message.Message());
  }

  // The grid frame's pose goes on /tf_static first, so a subscriber can place the grid.
  void PublishGrid(const OccupancyGrid& grid, std::int64_t stamp_ns) {
    const TransformMessage placement(SE3::FromMatrix(grid.T_world_grid), stamp_ns,
                                     options_.map_frame, options_.grid_frame);
    publishers_.tf_static.Write(placement.Message());
    const GridMessage message(grid, stamp_ns, options_.grid_frame);
    publishers_.grid.Write(message.Message());
  }

  // Drains the pipeline, writes the run's files and publishes the final maps.
  void Finish() {
    if (finished_) return;
    finished_ = true;
    if (snapshot_.valid()) snapshot_.wait();
    RunSummary& run = summary_->run;
    run.frames_skipped = pairer_.Skipped();
    summary_->pairs_skipped = pairer_.Skipped();
    summary_->images_dropped = pairer_.Dropped();
    if (system_) {
      system_->Shutdown();
      run.wall_s = SecondsSince(started_);
      const fs::path out_dir =
          options_.run.out_dir.empty() ? fs::path(".") : fs::path(options_.run.out_dir);
      std::error_code error;
      fs::create_directories(out_dir, error);
      if (error || !fs::is_directory(out_dir))
        throw Error(out_dir.string() + ": cannot create output folder");
      if (DenseMapper* dense = system_->Dense()) {
        const DenseExport exported = ExportDenseMap(*dense, out_dir.string(), setup_.grid);
        if (exported.grid) PublishGrid(exported.grid->grid, last_stamp_ns_);
        if (publishers_.dense_map.Subscribers() > 0)
          PublishDense(dense->Assemble(), last_stamp_ns_);
      }
      PublishMapPoints(last_stamp_ns_);
      run.stats = system_->Stats();
      run.fps = run.wall_s > 0.0 ? run.stats.frames / run.wall_s : 0.0;
      run.sequence_frames = summary_->pairs_tracked;
      run.camera_trajectory_path =
          WriteRunTrajectories(*system_, out_dir.string(), run.trajectory_format);
      WriteStatsJson((out_dir / "stats.json").string(), run);
    }
    summary_->published = publishers_.Counts();
    publishers_.WaitForAcknowledgements();
  }

  const Ros2NodeOptions& options_;
  Ros2NodeSummary* summary_;
  const RunSetup setup_;
  DdsHandle participant_;
  TopicReader<sensor_msgs_msg_dds__Image_> colour_;
  TopicReader<sensor_msgs_msg_dds__Image_> depth_;
  TopicReader<sensor_msgs_msg_dds__CameraInfo_> camera_info_;
  Publishers publishers_;
  DataWaiter waiter_;
  StampPairer pairer_;
  std::optional<CameraOptions> camera_;
  std::unique_ptr<System> system_;
  std::future<MapSnapshot> snapshot_;
  std::int64_t snapshot_stamp_ns_ = 0;
  std::int64_t last_stamp_ns_ = 0;
  std::size_t consecutive_rejected_ = 0;
  bool finished_ = false;
  Clock::time_point started_;
  Clock::time_point last_image_;
  Clock::time_point last_waiting_note_{};
  Clock::time_point last_clouds_{};
  Clock::time_point last_grid_{};
};

}  // namespace

Ros2NodeSummary RunRos2Node(const Ros2NodeOptions& options, const std::atomic<bool>* stop,
                            const std::function<void(const std::string&)>& started) {
  Ros2NodeSummary summary;
  Ros2Node node(options, &summary);
  if (started) {
    started("DDS domain " + std::to_string(summary.domain) + ", subscribed to " +
            options.topics.colour + " and " + options.topics.depth);
  }
  node.Run(stop);
  return summary;
}

}  // namespace drvslam::ros2
