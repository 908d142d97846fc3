// Runs the built `drvslam eval` on files in a temporary folder: the contract is the exit status,
// the "error: ..." line and the JSON keys.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "drvslam/io/trajectory_formats.h"
#include "drvslam/io/trajectory_io.h"
#include "test_support/cli_run.h"
#include "test_support/missing_data.h"
#include "test_support/temp_folder.h"

namespace drvslam {
namespace {

using drvslam::testing::CliRun;
using drvslam::testing::RunCli;

namespace fs = std::filesystem;

class EvalCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(DRVSLAM_CLI)) DRVSLAM_MISSING_TEST_DATA() << "CLI not built at " << DRVSLAM_CLI;
    dir_ = drvslam::testing::UniqueTempFolder("drvslam_eval_cli");
    Trajectory gt, est;
    for (int k = 0; k < 150; ++k) {
      const double t = 1000.0 + k / 30.0;
      const Eigen::Vector3d p(std::cos(0.5 * t), std::sin(0.4 * t), 0.1 * std::sin(t));
      const Eigen::Quaterniond q(Eigen::AngleAxisd(0.2 * t, Eigen::Vector3d::UnitZ()));
      gt.push_back({t, SE3(q, p)});
      // 1 cm across the path, alternating, on a moved copy.
      const Eigen::Vector3d offset(0.0, 0.0, k % 2 == 0 ? 0.01 : -0.01);
      est.push_back({t + 0.004, SE3(q, p + offset)});
    }
    gt_ = (dir_ / "groundtruth.txt").string();
    est_ = (dir_ / "estimate.txt").string();
    WriteTumTrajectory(gt_, gt);
    WriteTumTrajectory(est_, est);
  }
  void TearDown() override {
    if (!dir_.empty()) fs::remove_all(dir_);
  }

  // `drvslam eval GT EST <options> --json FILE` into *run; FILE parsed (null when unreadable).
  nlohmann::json EvalJson(const std::string& options, CliRun* run) const {
    const std::string json_path = (dir_ / "eval.json").string();
    *run = RunCli("eval " + gt_ + " " + est_ + " " + options + " --json " + json_path);
    std::ifstream in(json_path);
    return nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  }

  // The command failed the way bad input must: exit status 2 and an "error: " line that names
  // `what` (the file or option at fault).
  static void ExpectErrorNaming(const CliRun& run, const std::string& what) {
    EXPECT_EQ(run.status, 2) << run.output;
    EXPECT_NE(run.output.find("error: "), std::string::npos) << run.output;
    EXPECT_NE(run.output.find(what), std::string::npos) << run.output;
  }

  fs::path dir_;
  std::string gt_, est_;
};

TEST_F(EvalCliTest, WritesJsonWithTheContractKeysAndAPlot) {
  const std::string json_path = (dir_ / "eval.json").string();
  const std::string plot_path = (dir_ / "eval.png").string();
  const CliRun run = RunCli("eval " + gt_ + " " + est_ + " --json " + json_path + " --plot " +
                            plot_path + " --rpe-delta 0.5");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("rmse"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("matched poses"), std::string::npos) << run.output;

  std::ifstream in(json_path);
  ASSERT_TRUE(in.good());
  const nlohmann::json json = nlohmann::json::parse(in);
  for (const char* key :
       {"rmse", "mean", "median", "std", "min", "max", "matched", "coverage", "scale"}) {
    EXPECT_TRUE(json["ate"].contains(key)) << key;
  }
  for (const char* key :
       {"trans_rmse", "rot_rmse_deg", "trans_mean", "rot_mean_deg", "pairs", "delta"}) {
    EXPECT_TRUE(json["rpe"].contains(key)) << key;
  }
  EXPECT_EQ(json["ate"]["matched"].get<int>(), 150);
  EXPECT_NEAR(json["ate"]["rmse"].get<double>(), 0.01, 0.002);
  EXPECT_DOUBLE_EQ(json["rpe"]["delta"].get<double>(), 0.5);
  EXPECT_GT(fs::file_size(plot_path), 10000u);
}

// Without a frame count, coverage is matched over ground-truth poses, and both outputs say so.
TEST_F(EvalCliTest, WithoutAFrameCountCoverageIsOfGroundTruthPoses) {
  CliRun run;
  const nlohmann::json json = EvalJson("", &run);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("of ground-truth poses"), std::string::npos) << run.output;
  EXPECT_EQ(json["ate"]["coverage_of"], "ground_truth_poses");
  EXPECT_NEAR(json["ate"]["coverage"].get<double>(), 1.0, 1e-12);
}

TEST_F(EvalCliTest, FramesMakeCoverageOfTheSequencesFrames) {
  CliRun run;
  const nlohmann::json json = EvalJson("--frames 300", &run);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("50.00 %  (of the sequence's frames)"), std::string::npos)
      << run.output;
  EXPECT_EQ(json["ate"]["coverage_of"], "sequence_frames");
  EXPECT_NEAR(json["ate"]["coverage"].get<double>(), 150.0 / 300.0, 1e-12);
}

// --dataset counts the frames `drvslam run` would process: the colour images paired with depth.
TEST_F(EvalCliTest, DatasetGivesTheSequencesFrameCount) {
  const fs::path sequence = dir_ / "sequence";
  fs::create_directories(sequence);
  std::ofstream rgb(sequence / "rgb.txt"), depth(sequence / "depth.txt");
  rgb << "# colour images\n";
  for (int k = 0; k < 200; ++k) {
    const std::string stamp = std::to_string(1000.0 + k / 30.0);
    rgb << stamp << " rgb/" << k << ".png\n";
    depth << stamp << " depth/" << k << ".png\n";
  }
  rgb.close();
  depth.close();
  CliRun run;
  const nlohmann::json json = EvalJson("--dataset " + sequence.string(), &run);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(json["ate"]["coverage_of"], "sequence_frames");
  EXPECT_NEAR(json["ate"]["coverage"].get<double>(), 150.0 / 200.0, 1e-12);
}

TEST_F(EvalCliTest, DatasetWithoutFrameListIsAnError) {
  const fs::path sequence = dir_ / "empty_sequence";
  fs::create_directories(sequence);
  const CliRun run = RunCli("eval " + gt_ + " " + est_ + " --dataset " + sequence.string());
  ExpectErrorNaming(run, "rgb.txt");
}

TEST_F(EvalCliTest, FewerFramesThanMatchedPosesIsAnError) {
  const CliRun run = RunCli("eval " + gt_ + " " + est_ + " --frames 100");
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("error: ATE: --frames 100 is fewer than the 150 matched poses"),
            std::string::npos)
      << run.output;
}

TEST_F(EvalCliTest, MissingFileIsAnError) {
  const CliRun run = RunCli("eval " + gt_ + " " + (dir_ / "no-such-file.txt").string());
  ExpectErrorNaming(run, "no-such-file.txt");
}

TEST_F(EvalCliTest, NegativeMaxDiffIsAnError) {
  const CliRun run = RunCli("eval " + gt_ + " " + est_ + " --max-diff -1");
  ExpectErrorNaming(run, "--max-diff");
}

TEST_F(EvalCliTest, UnwritableJsonPathIsAnError) {
  const CliRun run = RunCli("eval " + gt_ + " " + est_ + " --json /nonexistent-dir/eval.json");
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("error: /nonexistent-dir/eval.json"), std::string::npos) << run.output;
}

nlohmann::json ReadJson(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// The same estimate as KITTI (with its times file) and EuRoC files: the same matches and the same
// ATE as the TUM file, to the 9 decimals the formats keep; GT may be EuRoC too.
TEST_F(EvalCliTest, KittiAndEurocCopiesGiveTheSameAteAsTum) {
  const Trajectory estimate = ReadTumTrajectory(est_);
  const std::string kitti = (dir_ / "estimate_kitti.txt").string();
  const std::string euroc = (dir_ / "estimate.csv").string();
  const std::string gt_euroc = (dir_ / "groundtruth.csv").string();
  WriteTrajectory(kitti, estimate, TrajectoryFormat::kKitti);
  WriteTrajectory(euroc, estimate, TrajectoryFormat::kEuroc);
  WriteTrajectory(gt_euroc, ReadTumTrajectory(gt_), TrajectoryFormat::kEuroc);
  const std::string tum_json = (dir_ / "tum.json").string();
  ASSERT_EQ(RunCli("eval " + gt_ + " " + est_ + " --json " + tum_json).status, 0);
  const nlohmann::json tum = ReadJson(tum_json);
  struct Case {
    std::string gt, est, says;
  };
  for (const Case& c : {Case{gt_, kitti, "poses, kitti)"}, Case{gt_, euroc, "poses, euroc)"},
                        Case{gt_euroc, kitti, "poses, kitti)"}}) {
    const std::string json_path = (dir_ / "other.json").string();
    const CliRun run = RunCli("eval " + c.gt + " " + c.est + " --json " + json_path);
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find(c.says), std::string::npos) << run.output;
    const nlohmann::json other = ReadJson(json_path);
    EXPECT_EQ(other["ate"]["matched"], tum["ate"]["matched"]) << c.est;
    EXPECT_NEAR(other["ate"]["rmse"].get<double>(), tum["ate"]["rmse"].get<double>(), 1e-9);
    EXPECT_NEAR(other["rpe"]["trans_rmse"].get<double>(), tum["rpe"]["trans_rmse"].get<double>(),
                1e-9);
  }
}

// An explicit format overrides detection: a KITTI file read as TUM fails on its first line.
TEST_F(EvalCliTest, FormatOptionOverridesDetection) {
  const std::string kitti = (dir_ / "estimate_kitti.txt").string();
  WriteTrajectory(kitti, ReadTumTrajectory(est_), TrajectoryFormat::kKitti);
  const CliRun run = RunCli("eval " + gt_ + " " + kitti + " --est-format tum");
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("error: " + kitti + ":1: expected 8 values"), std::string::npos)
      << run.output;
  const CliRun bad = RunCli("eval " + gt_ + " " + kitti + " --format csv");
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("--format"), std::string::npos) << bad.output;
}

TEST_F(EvalCliTest, BadEurocLineIsOneErrorNamingFileAndLine) {
  const std::string path = (dir_ / "bad.csv").string();
  std::ofstream(path) << "#timestamp [ns],p_x,p_y,p_z,q_w,q_x,q_y,q_z\n"
                      << "1000000000,0,0,0,1,0,0,0\n"
                      << "1033333333,0,0,zero,1,0,0,0\n";
  const CliRun run = RunCli("eval " + gt_ + " " + path);
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("error: " + path + ":3: 'zero' is not a number"), std::string::npos)
      << run.output;
}

}  // namespace
}  // namespace drvslam
