// `drvslam ros2` end to end over DDS on the loopback interface only: this test plays a synthetic
// sequence (a static room: the accuracy of geometry-only motion handling among people is the
// benchmark's to measure, not this transport test's) as a camera driver would (sensor_msgs/Image
// colour rgb8 and depth 16UC1 in millimetres, and CameraInfo, stamped with the wall clock at 30
// Hz), the real CLI runs as the node in a child process (intrinsics from CameraInfo, no segmenter,
// geometry-only dynamic handling), and this test subscribes to its odometry, /tf and occupancy grid
// as a ROS 2 node would. It checks the poses against the ground truth (ATE), the message counts,
// the grid, and the files the node writes when it stops; it reports the latency from image stamp to
// received odometry without asserting it (timing is not a test's to judge).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/imgproc.hpp>
#include <thread>
#include <vector>

#include "drvslam/core/settings.h"
#include "drvslam/core/settings_file.h"
#include "drvslam/io/trajectory_io.h"
#include "drvslam/io/tum_dataset.h"
#include "drvslam/ros2/dds_entities.h"
#include "drvslam/ros2/image_messages.h"
#include "integration/synthesized_sequence.h"
#include "test_support/sanitizer_build.h"

namespace drvslam::ros2 {
namespace {

namespace fs = std::filesystem;
using SystemClock = std::chrono::system_clock;

constexpr std::size_t kFrames = 240;  // 8 s at 30 Hz
// The odometry's twist agrees with the ground truth's central differences within these RMSE
// bounds (the synthetic camera moves at about 0.2 m/s rms; a difference of two poses that
// scatter by a millimetre would be off by 0.05 m/s). Frames before kTwistWarmUpFrames are left
// out: the filter starts with the velocity unknown.
constexpr double kMaxTwistLinearRmse = 0.05;  // m/s
constexpr double kMaxTwistAngularRmse = 0.1;  // rad/s
constexpr std::size_t kTwistWarmUpFrames = 30;
// A domain of its own (ros2_msgs_test uses 171), loopback only, no multicast: without
// multicast, participants find each other by unicast to the peer 127.0.0.1, on the ports of
// participant indices 0..MaxAutoParticipantIndex (each process takes the first free one).
constexpr int kDomain = 172;
constexpr const char* kLoopbackConfig =
    "<CycloneDDS><Domain><General><Interfaces><NetworkInterface name=\"lo\"/></Interfaces>"
    "<AllowMulticast>false</AllowMulticast></General><Discovery>"
    "<ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>30</MaxAutoParticipantIndex>"
    "<Peers><Peer address=\"127.0.0.1\"/></Peers></Discovery></Domain></CycloneDDS>";
// The node tracks the newest pair and skips what arrives while it is busy: on an idle 2-core
// machine it tracked 233 of 240 frames, but ctest runs other tests beside it, and under a
// sanitizer it runs many times slower. The share is a floor against a node that stalls, not a
// speed figure.
constexpr double kMinPublishedShare = test::kSanitizedBuild ? 0.05 : 0.3;
// The causal filter starts afresh, with no velocity, after a gap of more than half a second
// between tracked frames (tracking/causal_pose_filter.cc): twists are compared where the node
// tracked the two frames before within that gap of each other.
constexpr std::int64_t kFilterRestartGapNs = 500'000'000;

std::int64_t NowNanoseconds() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(SystemClock::now().time_since_epoch())
      .count();
}

// One frame as a driver publishes it.
struct DriverFrame {
  double sequence_timestamp = 0.0;
  std::vector<std::uint8_t> rgb;    // rgb8
  std::vector<std::uint8_t> depth;  // 16UC1 millimetres, little endian
};

std::vector<DriverFrame> LoadFrames(const TumDataset& dataset) {
  std::vector<DriverFrame> frames;
  for (std::size_t i = 0; i < dataset.Size(); ++i) {
    const RgbdFrame frame = dataset.Read(i);
    DriverFrame out;
    out.sequence_timestamp = frame.timestamp;
    // Whole-image conversions: a loop over pixels here took 200 s of the address job's test run
    // (test sources are compiled at -O0 there).
    cv::Mat rgb, millimetres;
    cv::cvtColor(frame.bgr, rgb, cv::COLOR_BGR2RGB);
    frame.depth.convertTo(millimetres, CV_16U, 1000.0);
    out.rgb.assign(rgb.datastart, rgb.dataend);
    const std::size_t pixels = millimetres.total();
    const auto* millimetre = millimetres.ptr<std::uint16_t>();
    out.depth.resize(2 * pixels);
    for (std::size_t p = 0; p < pixels; ++p) {
      out.depth[2 * p] = static_cast<std::uint8_t>(millimetre[p] & 0xff);
      out.depth[2 * p + 1] = static_cast<std::uint8_t>(millimetre[p] >> 8);
    }
    frames.push_back(std::move(out));
  }
  return frames;
}

// The node as a child process; its output goes to `log`.
pid_t StartNode(const fs::path& out_dir, const fs::path& log) {
  const std::string command = std::string("exec ") + DRVSLAM_CLI +
                              " --log-level warn ros2 --segmenter none --dynamic on --loop off"
                              " --idle-exit 3 --cloud-period 0.5 --grid-period 1 --out '" +
                              out_dir.string() + "' > '" + log.string() + "' 2>&1";
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

// Waits up to `timeout` for the child; its exit status, or -1 (killed after the timeout).
int WaitForExit(pid_t pid, std::chrono::seconds timeout, const std::function<void()>& meanwhile) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    meanwhile();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  return -1;
}

double Percentile(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(q * (values.size() - 1))];
}

TEST(Ros2NodeTest, TracksImageTopicsAndPublishesPosesTfAndGrid) {
  ASSERT_EQ(setenv("CYCLONEDDS_URI", kLoopbackConfig, 1), 0);
  ASSERT_EQ(setenv("ROS_DOMAIN_ID", std::to_string(kDomain).c_str(), 1), 0);
  fs::path root;
  ASSERT_TRUE(test::SynthesizeInFreshFolder(
      "drvslam_ros2_node",
      "--scenario static_xyz --frames " + std::to_string(kFrames) + " --seed 3", &root));
  const fs::path sequence = root / "seq";
  const Settings settings = LoadSettings((sequence / "settings.yaml").string());
  TumDatasetOptions dataset_options;
  dataset_options.depth_map_factor = settings.depth.depth_map_factor;
  const TumDataset dataset(sequence.string(), dataset_options);
  ASSERT_EQ(dataset.Size(), kFrames);
  std::vector<DriverFrame> frames = LoadFrames(dataset);
  const CameraOptions& camera = settings.camera;

  const DdsHandle participant = CreateParticipant(kDomain);
  TopicWriter<sensor_msgs_msg_dds__Image_> colour(participant, "/camera/camera/color/image_raw",
                                                  TopicQos::kSensorData, 1);
  TopicWriter<sensor_msgs_msg_dds__Image_> depth(
      participant, "/camera/camera/aligned_depth_to_color/image_raw", TopicQos::kSensorData, 1);
  TopicWriter<sensor_msgs_msg_dds__CameraInfo_> info(
      participant, "/camera/camera/color/camera_info", TopicQos::kSensorData, 1);
  TopicReader<nav_msgs_msg_dds__Odometry_> odometry(participant, "/drvslam/odometry",
                                                    TopicQos::kReliable, 1000);
  TopicReader<tf2_msgs_msg_dds__TFMessage_> tf(participant, "/tf", TopicQos::kReliable, 1000);
  TopicReader<nav_msgs_msg_dds__OccupancyGrid_> grid(participant, "/drvslam/grid",
                                                     TopicQos::kLatched, 1);

  const fs::path out_dir = root / "out";
  const pid_t node = StartNode(out_dir, root / "node.log");
  ASSERT_GT(node, 0);
  // A failed assertion returns early: the node must not outlive the test.
  struct KillOnExit {
    pid_t pid;
    bool reaped = false;
    ~KillOnExit() {
      if (reaped) return;
      kill(pid, SIGKILL);
      waitpid(pid, nullptr, 0);
    }
  } node_guard{node};

  std::map<std::int64_t, double> sequence_time_of_stamp;
  std::map<std::int64_t, SE3> poses;  // by stamp
  // The twist (linear, angular; child frame) by stamp, and whether each covariance was nonzero.
  std::map<std::int64_t, std::pair<Eigen::Vector3d, Eigen::Vector3d>> twists;
  std::size_t with_pose_covariance = 0, with_twist_covariance = 0;
  std::vector<double> latency_ms;
  std::size_t tf_messages = 0;
  std::size_t grids = 0;
  nav_msgs_msg_dds__MapMetaData_ last_grid{};
  std::string last_grid_frame;
  std::vector<std::int8_t> last_cells;
  std::string odometry_frames;
  const auto receive = [&] {
    odometry.Take([&](const nav_msgs_msg_dds__Odometry_& message) {
      const std::int64_t stamp = StampNanoseconds(message.header.stamp);
      latency_ms.push_back((NowNanoseconds() - stamp) * 1e-6);
      const auto& p = message.pose.pose;
      poses[stamp] = SE3(
          Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z),
          Eigen::Vector3d(p.position.x, p.position.y, p.position.z));
      odometry_frames = std::string(message.header.frame_id) + " -> " + message.child_frame_id;
      const auto& twist = message.twist.twist;
      twists[stamp] = {Eigen::Vector3d(twist.linear.x, twist.linear.y, twist.linear.z),
                       Eigen::Vector3d(twist.angular.x, twist.angular.y, twist.angular.z)};
      const auto positive_diagonal = [](const double* covariance) {
        for (int i = 0; i < 6; ++i) {
          if (!(covariance[7 * i] > 0.0)) return false;
        }
        return true;
      };
      with_pose_covariance += positive_diagonal(message.pose.covariance);
      with_twist_covariance += positive_diagonal(message.twist.covariance);
    });
    tf_messages += tf.Take([](const tf2_msgs_msg_dds__TFMessage_&) {});
    grid.Take([&](const nav_msgs_msg_dds__OccupancyGrid_& message) {
      ++grids;
      last_grid = message.info;
      last_grid_frame = message.header.frame_id;
      last_cells.assign(message.data._buffer, message.data._buffer + message.data._length);
    });
  };

  // The node subscribes within seconds of starting (its settings load first).
  const auto subscribe_deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (colour.Subscribers() == 0 || depth.Subscribers() == 0) {
    ASSERT_LT(std::chrono::steady_clock::now(), subscribe_deadline) << "the node never subscribed";
    int status = 0;
    ASSERT_NE(waitpid(node, &status, WNOHANG), node) << "the node exited early:\n"
                                                     << test::ReadFile(root / "node.log");
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }

  std::string rgb8 = "rgb8", mono16 = "16UC1", frame_id = "camera_color_optical_frame";
  std::string plumb_bob = "plumb_bob";
  std::vector<double> no_distortion(5, 0.0);
  const auto first = std::chrono::steady_clock::now();
  for (DriverFrame& frame : frames) {
    const auto due = first + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                 std::chrono::duration<double>(frame.sequence_timestamp -
                                                               frames.front().sequence_timestamp));
    while (std::chrono::steady_clock::now() < due) {
      receive();
      std::this_thread::sleep_until(
          std::min(due, std::chrono::steady_clock::now() + std::chrono::milliseconds(5)));
    }
    const std::int64_t stamp = NowNanoseconds();
    sequence_time_of_stamp[stamp] = frame.sequence_timestamp;

    sensor_msgs_msg_dds__CameraInfo_ camera_info{};
    camera_info.header.stamp = StampFromNanoseconds(stamp);
    camera_info.header.frame_id = frame_id.data();
    camera_info.width = static_cast<std::uint32_t>(camera.width);
    camera_info.height = static_cast<std::uint32_t>(camera.height);
    camera_info.distortion_model = plumb_bob.data();
    camera_info.d = BorrowSequence<dds_sequence_double>(no_distortion);
    const double k[9] = {camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1};
    std::copy(k, k + 9, camera_info.k);
    info.Write(camera_info);

    sensor_msgs_msg_dds__Image_ image{};
    image.header = camera_info.header;
    image.width = camera_info.width;
    image.height = camera_info.height;
    image.encoding = rgb8.data();
    image.step = 3 * image.width;
    image.data = BorrowSequence<dds_sequence_octet>(frame.rgb);
    colour.Write(image);
    image.encoding = mono16.data();
    image.step = 2 * image.width;
    image.data = BorrowSequence<dds_sequence_octet>(frame.depth);
    depth.Write(image);
  }

  // The node stops 3 s after the last image (--idle-exit), writes its files and publishes the
  // final grid.
  const int status = WaitForExit(node, std::chrono::seconds(300), receive);
  node_guard.reaped = true;
  receive();
  const std::string log = test::ReadFile(root / "node.log");
  ASSERT_EQ(status, 0) << log;
  std::printf("%s", log.c_str());

  // Poses, in the sequence's time, against the ground truth: the received odometry, and the
  // trajectory the node wrote (local BA refined, then smoothed), both stamped with the wall clock.
  const auto sequence_time = [&](double stamp_s) {
    const auto at =
        sequence_time_of_stamp.lower_bound(static_cast<std::int64_t>(stamp_s * 1e9) - 1000000);
    EXPECT_TRUE(at != sequence_time_of_stamp.end() && std::abs(at->first * 1e-9 - stamp_s) < 1e-3)
        << "a pose at " << stamp_s << " s matches no published stamp";
    return at == sequence_time_of_stamp.end() ? 0.0 : at->second;
  };
  Trajectory received;
  for (const auto& [stamp, pose] : poses) received.push_back({sequence_time(stamp * 1e-9), pose});
  Trajectory written = ReadTumTrajectory((out_dir / "CameraTrajectory.txt").string());
  for (StampedPose& pose : written) pose.timestamp = sequence_time(pose.timestamp);
  const fs::path trajectory = root / "received_odometry.txt";
  const fs::path written_trajectory = root / "written_trajectory.txt";
  WriteTumTrajectory(trajectory.string(), received);
  WriteTumTrajectory(written_trajectory.string(), written);
  const AteResult ate = test::AteAgainstGroundTruth(sequence, trajectory.string());
  const AteResult written_ate = test::AteAgainstGroundTruth(sequence, written_trajectory.string());
  std::printf("ATE of the node's CameraTrajectory.txt (after local BA, smoothed): %.2f cm RMSE\n",
              100.0 * written_ate.errors.rmse);
  std::printf(
      "frames published: %zu; odometry received: %zu (%zu distinct stamps), /tf: %zu, grids: %zu\n"
      "ATE of received odometry: %.2f cm RMSE over %zu poses\n"
      "latency stamp -> odometry received: median %.1f ms, p95 %.1f ms\n",
      frames.size(), latency_ms.size(), poses.size(), tf_messages, grids, 100.0 * ate.errors.rmse,
      ate.matched, latency_ms.empty() ? 0.0 : Percentile(latency_ms, 0.5),
      latency_ms.empty() ? 0.0 : Percentile(latency_ms, 0.95));
  RecordProperty("odometry_received", static_cast<int>(latency_ms.size()));
  if (!latency_ms.empty()) {
    RecordProperty("latency_median_ms", std::to_string(Percentile(latency_ms, 0.5)));
    RecordProperty("latency_p95_ms", std::to_string(Percentile(latency_ms, 0.95)));
  }

  EXPECT_GE(static_cast<double>(poses.size()), kMinPublishedShare * kFrames);
  EXPECT_EQ(latency_ms.size(), poses.size()) << "one odometry message per tracked stamp";
  EXPECT_EQ(tf_messages, latency_ms.size()) << "one /tf message per odometry message";
  EXPECT_EQ(odometry_frames, "map -> drvslam_camera");
  EXPECT_LT(ate.errors.rmse, 0.02);
  EXPECT_LT(written_ate.errors.rmse, 0.02);

  // The twist against the ground truth's central differences, in the camera frame, over the
  // received frames after the first second (the filter learns the velocity from the first).
  const Trajectory& truth = dataset.GroundTruth();
  double linear_sum = 0.0, angular_sum = 0.0, speed_sum = 0.0;
  std::size_t compared = 0;
  std::int64_t previous_stamp = 0, second_previous_stamp = 0;
  for (const auto& [stamp, twist] : twists) {
    const bool filter_running = second_previous_stamp > 0 &&
                                stamp - previous_stamp <= kFilterRestartGapNs &&
                                previous_stamp - second_previous_stamp <= kFilterRestartGapNs;
    second_previous_stamp = previous_stamp;
    previous_stamp = stamp;
    if (!filter_running) continue;
    const double t = sequence_time(stamp * 1e-9);
    const auto at = std::lower_bound(
        truth.begin(), truth.end(), t,
        [](const StampedPose& pose, double time) { return pose.timestamp < time - 1e-6; });
    const std::size_t i = static_cast<std::size_t>(at - truth.begin());
    if (i < kTwistWarmUpFrames || i + 1 >= truth.size()) continue;
    const double span = truth[i + 1].timestamp - truth[i - 1].timestamp;
    const Eigen::Matrix3d R = truth[i].T_wc.Rotation();
    const Eigen::Vector3d linear =
        R.transpose() * (truth[i + 1].T_wc.Translation() - truth[i - 1].T_wc.Translation()) / span;
    const Eigen::AngleAxisd turn(truth[i - 1].T_wc.Rotation().transpose() *
                                 truth[i + 1].T_wc.Rotation());
    const Eigen::Vector3d angular = turn.angle() * turn.axis() / span;
    linear_sum += (twist.first - linear).squaredNorm();
    angular_sum += (twist.second - angular).squaredNorm();
    speed_sum += linear.squaredNorm();
    ++compared;
  }
  EXPECT_EQ(with_pose_covariance, latency_ms.size() - 1)
      << "every odometry but the map's origin (exact by definition) carries a pose covariance";
  EXPECT_EQ(with_twist_covariance, latency_ms.size());
  if (compared == 0 && test::kSanitizedBuild) {
    // A sanitized node on a loaded machine may track no three frames within the gap; the
    // ordinary build tracks most frames and always compares.
    std::printf("twist not compared: no two successive gaps under 0.5 s between tracked frames\n");
  } else {
    ASSERT_GT(compared, 0u);
    const double linear_rmse = std::sqrt(linear_sum / compared);
    const double angular_rmse = std::sqrt(angular_sum / compared);
    std::printf(
        "twist against the ground truth's central differences over %zu frames: linear RMSE %.3f "
        "m/s (the camera's rms speed %.3f m/s), angular RMSE %.3f rad/s\n",
        compared, linear_rmse, std::sqrt(speed_sum / compared), angular_rmse);
    EXPECT_LT(linear_rmse, kMaxTwistLinearRmse);
    EXPECT_LT(angular_rmse, kMaxTwistAngularRmse);
  }

  ASSERT_GE(grids, 1u) << "no occupancy grid received";
  EXPECT_EQ(last_grid_frame, "drvslam_grid");
  EXPECT_FLOAT_EQ(last_grid.resolution, 0.05f);
  ASSERT_EQ(last_cells.size(), static_cast<std::size_t>(last_grid.width) * last_grid.height);
  const auto count = [&](std::int8_t value) {
    return std::count(last_cells.begin(), last_cells.end(), value);
  };
  EXPECT_GT(count(100), 0) << "no occupied cell";
  EXPECT_GT(count(0), 0) << "no free cell";
  EXPECT_EQ(count(100) + count(0) + count(-1), static_cast<long>(last_cells.size()));

  EXPECT_TRUE(fs::is_regular_file(out_dir / "CameraTrajectory.txt"));
  EXPECT_TRUE(fs::is_regular_file(out_dir / "stats.json"));
  EXPECT_TRUE(fs::is_regular_file(out_dir / "map.yaml"));
  fs::remove_all(root);
}

}  // namespace
}  // namespace drvslam::ros2
