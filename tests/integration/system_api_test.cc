// System as a library user meets it: TrackRGBD returns each frame's pose and state; it takes
// raw 16-bit depth scaled by DepthMapFactor as well as metres; a frame it rejects (wrong size,
// empty image, wrong depth type, no timestamp) throws drvslam::Error naming the problem and
// changes no state, so the next good frame is tracked.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/core/settings.h"
#include "drvslam/core/settings_file.h"
#include "drvslam/io/tum_dataset.h"
#include "drvslam/system.h"
#include "drvslam/system_options.h"
#include "drvslam/system_stats.h"
#include "drvslam/tools/truth/ground_truth_segmenter.h"
#include "drvslam/tracking/tracker_options.h"
#include "synthesized_sequence.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kFrames = 20;

// A short synthetic walking sequence and a sequential System over it with the dynamic stage on
// (ground-truth masks): the dynamic stage keeps per-frame state that a rejected frame must not
// leave half begun.
class SystemApiTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(test::SynthesizeInFreshFolder(
        "drvslam_integration_system_api",
        "--scenario walking_xyz --frames " + std::to_string(kFrames) + " --seed 1", &root_));
    sequence_ = (root_ / "seq").string();
    const SettingsFile file(sequence_ + "/settings.yaml");
    settings_ = LoadSettings(file);
    tracker_options_ = LoadTrackerOptions(file);
    TumDatasetOptions dataset_options;
    dataset_options.depth_map_factor = settings_.depth.depth_map_factor;
    dataset_ = std::make_unique<TumDataset>(sequence_, dataset_options);
    ASSERT_EQ(dataset_->Size(), kFrames);
  }

  // with_dynamic: the dynamic stage on ground-truth masks; else plain ORB-SLAM2 tracking.
  std::unique_ptr<System> MakeSystem(bool with_dynamic = true) const {
    SystemOptions options;
    options.sequential = true;
    options.relocalization.enabled = false;
    options.loop.enabled = false;
    if (with_dynamic) {
      DynamicFrontEndConfig dynamic;
      dynamic.segmenter = std::make_shared<GroundTruthSegmenter>(sequence_);
      options.dynamic = dynamic;
    }
    return std::make_unique<System>(settings_, tracker_options_, options);
  }

  fs::path root_;
  std::string sequence_;
  Settings settings_;
  TrackerOptions tracker_options_;
  std::unique_ptr<TumDataset> dataset_;
};

struct BadFrame {
  std::string name;
  cv::Mat bgr;
  cv::Mat depth;
  std::string expected_message;  // a part of the Error's text
};

TEST_F(SystemApiTest, RejectedFrameLeavesTheSystemAbleToTrackTheNextOne) {
  const std::unique_ptr<System> system = MakeSystem();
  std::size_t next = 0;
  for (; next < 3; ++next) {
    const RgbdFrame frame = dataset_->Read(next);
    system->TrackRGBD(frame.bgr, frame.depth, frame.timestamp);
  }
  const RgbdFrame sample = dataset_->Read(next);
  cv::Mat small_bgr, small_depth, depth64, bgr16;
  cv::resize(sample.bgr, small_bgr, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
  cv::resize(sample.depth, small_depth, cv::Size(), 0.5, 0.5, cv::INTER_NEAREST);
  sample.depth.convertTo(depth64, CV_64F);
  sample.bgr.convertTo(bgr16, CV_16U, 256.0);
  const std::vector<BadFrame> bad = {
      {"colour image of the wrong size", small_bgr, small_depth, "colour image is 320x240"},
      {"empty colour image", cv::Mat(), sample.depth, "colour image is empty"},
      {"depth of the wrong type", sample.bgr, depth64, "depth image is 64-bit float 1-channel"},
      {"depth of the wrong size", sample.bgr, small_depth, "depth image is 320x240"},
      {"colour image of the wrong type", bgr16, sample.depth,
       "colour image is 16-bit unsigned 3-channel"},
      {"timestamp that is not a number", sample.bgr, sample.depth, "timestamp is nan"},
  };
  for (const BadFrame& frame : bad) {
    SCOPED_TRACE(frame.name);
    const RgbdFrame good = dataset_->Read(next++);
    const double stamp = frame.expected_message == "timestamp is nan"
                             ? std::numeric_limits<double>::quiet_NaN()
                             : good.timestamp;
    try {
      system->TrackRGBD(frame.bgr, frame.depth, stamp);
      ADD_FAILURE() << "no Error for a " << frame.name;
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find(frame.expected_message), std::string::npos)
          << error.what();
    }
    // The rejected frame never happened: its stamp comes again, with good images.
    TrackingState state = TrackingState::kNotInitialized;
    ASSERT_NO_THROW(state = system->TrackRGBD(good.bgr, good.depth, good.timestamp).state);
    EXPECT_EQ(state, TrackingState::kOk);
  }
  system->Shutdown();
  // Only the good frames count: the rejected ones left no trace in the trajectory.
  EXPECT_EQ(system->Stats().frames, next);
  EXPECT_EQ(system->Stats().tracked, next);
}

TEST_F(SystemApiTest, TrackResultGivesEachFramesPoseAndState) {
  const std::unique_ptr<System> system = MakeSystem();
  const Trajectory& truth = dataset_->GroundTruth();
  ASSERT_EQ(truth.size(), kFrames);
  // Without depth nothing can start a map: no pose.
  const RgbdFrame first = dataset_->Read(0);
  const TrackResult blind = system->TrackRGBD(first.bgr, cv::Mat(), first.timestamp);
  EXPECT_EQ(blind.state, TrackingState::kNotInitialized);
  EXPECT_FALSE(blind.pose_valid);
  EXPECT_EQ(blind.frame_id, 0);
  EXPECT_TRUE(blind.T_cw.Matrix().isIdentity(0.0));

  // From frame 1 on the map's world frame is camera 1; the ground truth, moved there, is what
  // the returned poses must match.
  const SE3 T_w1 = truth[1].T_wc.Inverse();
  double worst_m = 0.0;
  int keyframes = 0;
  for (std::size_t i = 1; i < kFrames; ++i) {
    SCOPED_TRACE("frame " + std::to_string(i));
    const RgbdFrame frame = dataset_->Read(i);
    const TrackResult result = system->TrackRGBD(frame.bgr, frame.depth, frame.timestamp);
    EXPECT_EQ(result.timestamp, frame.timestamp);
    EXPECT_EQ(result.frame_id, static_cast<long>(i));
    ASSERT_EQ(result.state, TrackingState::kOk);
    ASSERT_TRUE(result.pose_valid);
    EXPECT_TRUE((result.T_wc * result.T_cw).Matrix().isIdentity(1e-12));
    if (i == 1) {
      // The first frame of a map is its origin, and a keyframe.
      EXPECT_TRUE(result.T_wc.Matrix().isIdentity(0.0));
      EXPECT_NE(result.new_keyframe, nullptr);
      EXPECT_GT(result.inliers, 100);
    }
    if (result.new_keyframe) ++keyframes;
    const SE3 expected = T_w1 * truth[i].T_wc;
    worst_m = std::max(worst_m, (result.T_wc.Translation() - expected.Translation()).norm());
    // The trajectory the System records holds the same pose (mapping may since have refined
    // the reference keyframe by a little); the smoothed one holds the same frames.
    const Trajectory recorded = system->TrackedCameraTrajectory();
    ASSERT_EQ(recorded.size(), i);
    ASSERT_EQ(system->CameraTrajectory().size(), i);
    EXPECT_EQ(recorded.back().timestamp, frame.timestamp);
    EXPECT_LT((recorded.back().T_wc.Translation() - result.T_wc_tracked.Translation()).norm(),
              0.005);
    // The causal pose (the one returned to act on) stays near the pose as tracked.
    EXPECT_LT((result.T_wc.Translation() - result.T_wc_tracked.Translation()).norm(), 0.01);
  }
  EXPECT_LT(worst_m, 0.03) << "largest distance from the ground truth";
  EXPECT_GE(keyframes, 2);
}

// Raw sensor depth (CV_16UC1, DepthMapFactor per metre, as in the sequence's PNG files) gives
// the same poses, to the last bit, as the metres the dataset reader makes of the same files.
TEST_F(SystemApiTest, SixteenBitDepthTracksExactlyAsTheReadersMetres) {
  const std::unique_ptr<System> metres = MakeSystem(/*with_dynamic=*/false);
  const std::unique_ptr<System> raw = MakeSystem(/*with_dynamic=*/false);
  double moved_metres = 0.0;
  for (std::size_t i = 0; i < kFrames; ++i) {
    SCOPED_TRACE("frame " + std::to_string(i));
    const RgbdFrame frame = dataset_->Read(i);
    const cv::Mat depth16 = cv::imread(frame.depth_path, cv::IMREAD_UNCHANGED);
    ASSERT_EQ(depth16.type(), CV_16UC1);
    const TrackResult a = metres->TrackRGBD(frame.bgr, frame.depth, frame.timestamp);
    const TrackResult b = raw->TrackRGBD(frame.bgr, depth16, frame.timestamp);
    ASSERT_EQ(a.state, TrackingState::kOk);
    ASSERT_EQ(b.state, a.state);
    EXPECT_EQ(b.inliers, a.inliers);
    EXPECT_TRUE(b.T_cw.Matrix() == a.T_cw.Matrix());
    moved_metres = a.T_wc.Translation().norm();
  }
  // A wrong factor would scale the map: the same check must then see other poses.
  Settings halved = settings_;
  halved.depth.depth_map_factor /= 2.0;
  SystemOptions options;
  options.sequential = true;
  options.relocalization.enabled = false;
  options.loop.enabled = false;
  System scaled(halved, tracker_options_, options);
  double moved_scaled = 0.0;
  for (std::size_t i = 0; i < kFrames; ++i) {
    const RgbdFrame frame = dataset_->Read(i);
    const cv::Mat depth16 = cv::imread(frame.depth_path, cv::IMREAD_UNCHANGED);
    const TrackResult result = scaled.TrackRGBD(frame.bgr, depth16, frame.timestamp);
    ASSERT_TRUE(result.pose_valid);
    moved_scaled = result.T_wc.Translation().norm();
  }
  // Depth read twice as large: the camera seems to move twice as far.
  EXPECT_NEAR(moved_scaled / moved_metres, 2.0, 0.2);
}

}  // namespace
}  // namespace drvslam
