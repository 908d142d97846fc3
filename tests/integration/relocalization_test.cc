// Relocalization end to end: a synthetic sequence whose camera is blinded for a stretch of frames
// (black colour, no depth) and comes back upside down, looking at an earlier part of the room.
// Tracking must pick up again, in the same map, within a couple of frames of the view returning.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <set>
#include <string>
#include <vector>

#include "drvslam/core/settings.h"
#include "drvslam/core/settings_file.h"
#include "drvslam/io/text_lines.h"
#include "drvslam/io/trajectory_io.h"
#include "drvslam/tools/eval/ate.h"
#include "drvslam/tools/runner/sequence_runner.h"
#include "synthesized_sequence.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

// The kidnapped sequence: source frames [0, kRun), kBlank blinded frames, then source frames
// [kReturnFirst, kReturnFirst + kReturnCount) seen by the camera rolled upside down (180 degrees
// about its optical axis): a jump no pose prior survives, so only relocalization can find it.
constexpr int kSourceFrames = 60;
constexpr int kRun = 50;
constexpr int kBlank = 8;
constexpr int kReturnFirst = 3;
constexpr int kReturnCount = 25;
constexpr int kFrames = kRun + kBlank + kReturnCount;
constexpr int kMaxFramesToRecover = 2;

struct SourceFrame {
  std::string rgb, depth;    // absolute image paths
  std::vector<double> pose;  // tx ty tz qx qy qz qw (T_wc); empty when unknown
};

std::vector<SourceFrame> ReadSource(const fs::path& seq) {
  // Ground truth by timestamp field: synth writes one pose per frame, at the frame's stamp.
  std::map<std::string, std::vector<double>> poses;
  ForEachDataLine((seq / "groundtruth.txt").string(),
                  [&](int, const std::vector<std::string>& fields) {
                    std::vector<double> pose;
                    for (std::size_t i = 1; i < fields.size(); ++i) {
                      pose.push_back(ParseNumber(fields[i], "groundtruth.txt"));
                    }
                    poses[fields[0]] = pose;
                  });
  std::vector<SourceFrame> frames;
  ForEachDataLine((seq / "associations.txt").string(),
                  [&](int, const std::vector<std::string>& fields) {
                    SourceFrame frame{(seq / fields[1]).string(), (seq / fields[3]).string(), {}};
                    if (poses.count(fields[0]) > 0) frame.pose = poses[fields[0]];
                    frames.push_back(frame);
                  });
  return frames;
}

// The image of a camera rolled by 180 degrees about its optical axis: u' = 2 cx - u,
// v' = 2 cy - v.
cv::Mat Roll(const cv::Mat& image, const CameraOptions& camera) {
  const cv::Matx23d flip(-1, 0, 2 * camera.cx, 0, -1, 2 * camera.cy);
  cv::Mat rolled;
  cv::warpAffine(image, rolled, flip, image.size(), cv::INTER_NEAREST, cv::BORDER_CONSTANT);
  return rolled;
}

// Writes the kidnapped sequence (blind and rolled frames as new images, the rest shared with
// the source). Returns the timestamp of every frame.
std::vector<double> WriteKidnapped(const fs::path& seq, const fs::path& out) {
  const std::vector<SourceFrame> source = ReadSource(seq);
  const CameraOptions camera = LoadSettings(SettingsFile((seq / "settings.yaml").string())).camera;
  fs::create_directories(out / "rolled");
  fs::copy_file(seq / "settings.yaml", out / "settings.yaml");
  const cv::Mat first = cv::imread(source.front().rgb, cv::IMREAD_COLOR);
  const std::string black = (out / "black.png").string();
  const std::string empty = (out / "empty_depth.png").string();
  cv::imwrite(black, cv::Mat(first.size(), CV_8UC3, cv::Scalar::all(0)));
  cv::imwrite(empty, cv::Mat(first.size(), CV_16UC1, cv::Scalar(0)));
  std::ofstream rgb(out / "rgb.txt"), depth(out / "depth.txt"), pairs(out / "associations.txt"),
      truth(out / "groundtruth.txt");
  std::vector<double> stamps;
  for (int k = 0; k < kFrames; ++k) {
    char stamp[32];
    std::snprintf(stamp, sizeof(stamp), "%.6f", 1000.0 + k / 30.0);
    stamps.push_back(std::stod(stamp));
    std::string r = black, d = empty;
    std::vector<double> pose;
    if (k < kRun) {
      r = source[k].rgb;
      d = source[k].depth;
      pose = source[k].pose;
    } else if (k >= kRun + kBlank) {
      const SourceFrame& from = source[kReturnFirst + (k - kRun - kBlank)];
      r = (out / "rolled" / ("rgb_" + std::to_string(k) + ".png")).string();
      d = (out / "rolled" / ("depth_" + std::to_string(k) + ".png")).string();
      cv::imwrite(r, Roll(cv::imread(from.rgb, cv::IMREAD_COLOR), camera));
      cv::imwrite(d, Roll(cv::imread(from.depth, cv::IMREAD_UNCHANGED), camera));
      if (from.pose.size() == 7) {
        // T_wc' = T_wc * Rz(pi).
        const Eigen::Quaterniond q(from.pose[6], from.pose[3], from.pose[4], from.pose[5]);
        const Eigen::Quaterniond rolled =
            q * Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()));
        pose = {from.pose[0], from.pose[1], from.pose[2], rolled.x(),
                rolled.y(),   rolled.z(),   rolled.w()};
      }
    }
    rgb << stamp << " " << r << "\n";
    depth << stamp << " " << d << "\n";
    pairs << stamp << " " << r << " " << stamp << " " << d << "\n";
    if (pose.size() == 7) {
      truth << stamp;
      for (const double value : pose) truth << " " << std::setprecision(12) << value;
      truth << "\n";
    }
  }
  return stamps;
}

class RelocalizationTest : public test::SequenceSuite<RelocalizationTest> {
 protected:
  static void SetUpTestSuite() {
    ASSERT_TRUE(test::SynthesizeInFreshFolder(
        "drvslam_integration_relocalization",
        "--scenario static_rpy --frames " + std::to_string(kSourceFrames) + " --seed 3", &root_));
    stamps_ = WriteKidnapped(root_ / "seq", root_ / "kidnapped");
  }

  // Runs over the kidnapped sequence made from the synthesized one.
  static RunSummary Run(const std::string& out_name, const std::string& config) {
    RunOptions options = SequentialRunOptions(out_name);
    options.dataset = (root_ / "kidnapped").string();
    options.config = config;
    return RunSequence(options);
  }

  static std::vector<double> stamps_;
};

std::vector<double> RelocalizationTest::stamps_;

TEST_F(RelocalizationTest, TracksAgainWithinTwoFramesOfTheViewReturning) {
  const RunSummary summary = Run("reloc", "");
  ASSERT_EQ(summary.stats.frames, static_cast<std::size_t>(kFrames));
  EXPECT_GE(summary.stats.relocalizations, 1);
  // The blind frames are lost, and at most kMaxFramesToRecover after them.
  EXPECT_GE(summary.stats.frames_lost, static_cast<std::size_t>(kBlank));
  EXPECT_LE(summary.stats.frames_lost, static_cast<std::size_t>(kBlank + kMaxFramesToRecover));
  std::printf("frames lost: %zu (%d blind), relocalizations: %d, attempts: %d\n",
              summary.stats.frames_lost, kBlank, summary.stats.relocalizations,
              summary.stats.relocalization_attempts);

  const Trajectory estimate = ReadTumTrajectory(summary.camera_trajectory_path);
  std::set<double> tracked;
  for (const StampedPose& pose : estimate) tracked.insert(pose.timestamp);
  // Every frame from kMaxFramesToRecover after the return on is tracked.
  for (int k = kRun + kBlank + kMaxFramesToRecover; k < kFrames; ++k) {
    EXPECT_EQ(tracked.count(stamps_[k]), 1u) << "frame " << k << " not tracked";
  }
  // In the same map: one rigid alignment fits the poses before and after the loss.
  const Trajectory truth = ReadTumTrajectory((root_ / "kidnapped" / "groundtruth.txt").string());
  const AteResult ate = ComputeAte(truth, estimate, AteOptions{});
  EXPECT_EQ(ate.matched, estimate.size());
  EXPECT_LT(ate.errors.rmse, 0.01) << "ATE RMSE " << ate.errors.rmse << " m";
  const std::string stats = test::ReadFile(root_ / "reloc" / "stats.json");
  EXPECT_NE(stats.find("\"frames_lost\""), std::string::npos) << stats;
  EXPECT_NE(stats.find("\"relocalizations\""), std::string::npos) << stats;
}

TEST_F(RelocalizationTest, WithoutRelocalizationTheRolledViewIsNotFound) {
  const RunSummary with = Run("with", "");
  const fs::path config = root_ / "no_relocalization.yaml";
  fs::copy_file(root_ / "kidnapped" / "settings.yaml", config,
                fs::copy_options::overwrite_existing);
  std::ofstream(config, std::ios::app) << "\nRelocalization.enabled: 0\n";
  const RunSummary without = Run("without", config.string());
  EXPECT_EQ(without.stats.relocalization_attempts, 0);
  // The fallback (the last reference keyframe, from the last pose) cannot turn the camera over.
  EXPECT_GT(without.stats.frames_lost, with.stats.frames_lost + 10);
  std::printf("frames lost: %zu with relocalization, %zu without\n", with.stats.frames_lost,
              without.stats.frames_lost);
}

}  // namespace
}  // namespace drvslam
