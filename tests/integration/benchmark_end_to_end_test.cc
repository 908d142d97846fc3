// `drvslam benchmark` end to end: a short synthetic sequence through the CLI (sequential, so
// that its two runs must agree exactly), strict settings, stopping, and a viewer entry with a
// connected browser.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "benchmark_test_util.h"
#include "drvslam/core/error.h"
#include "drvslam/tools/runner/benchmark_list.h"
#include "drvslam/tools/runner/benchmark_report.h"
#include "drvslam/tools/runner/benchmark_runner.h"
#include "drvslam/tools/viewer/headless_browser.h"
#include "synthesized_sequence.h"
#include "test_support/missing_data.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

using test::ErrorOf;
using test::ExpectRectangularTables;
using test::WriteText;

class BenchmarkEndToEndTest : public ::testing::Test {
 protected:
  static constexpr int kFrames = 60;
  static void SetUpTestSuite() {
    root_ = test::FreshTempFolder("drvslam_benchmark_e2e");
    const std::string failure = test::SynthesizeSequence(
        root_, "--scenario walking_xyz --frames " + std::to_string(kFrames) + " --seed 1");
    ASSERT_TRUE(failure.empty()) << failure;
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }
  static fs::path root_;
};

fs::path BenchmarkEndToEndTest::root_;

// The n-th (from 1) colour image listed in the sequence's rgb.txt.
fs::path ListedImage(const fs::path& sequence, int n) {
  std::ifstream list(sequence / "rgb.txt");
  int seen = 0;
  for (std::string line; std::getline(list, line);) {
    if (line.empty() || line[0] == '#') continue;
    if (++seen == n) return sequence / line.substr(line.find(' ') + 1);
  }
  return {};
}

TEST_F(BenchmarkEndToEndTest, TwoSequentialRunsAgreeAndAFailedRunIsRecordedAndReported) {
  // A copy whose images 20 to 50 are corrupt: a run skips a bad frame, but 31 in a row make the
  // sequence unreadable and the run fails there; the benchmark goes on.
  const fs::path broken = root_ / "broken";
  fs::copy(root_ / "seq", broken, fs::copy_options::recursive);
  for (int n = 20; n <= 50; ++n) {
    const fs::path image = ListedImage(broken, n);
    ASSERT_TRUE(fs::exists(image)) << image;
    WriteText(image, "not a png");
  }
  WriteText(root_ / "bench.json", R"({"entries": [
      {"name": "broken", "dataset": "broken", "segmenter": "gt", "mode": "sequential",
       "dense": "off", "runs": 1},
      {"name": "walking_gt", "dataset": "seq", "segmenter": "gt", "mode": "sequential",
       "dense": "off"}]})");
  const fs::path out = root_ / "out";
  const std::string command = std::string(DRVSLAM_CLI) + " --log-level warn benchmark --list " +
                              (root_ / "bench.json").string() + " --runs 2 --out " + out.string() +
                              " > " + (root_ / "log.txt").string() + " 2>&1";
  const int status = std::system(command.c_str());
  const std::string log = test::ReadFile(root_ / "log.txt");
  ASSERT_TRUE(WIFEXITED(status)) << log;
  EXPECT_EQ(WEXITSTATUS(status), 2) << log;  // a run failed
  EXPECT_NE(log.find("broken 1/1: FAILED: "), std::string::npos) << log;
  EXPECT_NE(log.find("walking_gt 1/2: ATE "), std::string::npos) << log;
  EXPECT_NE(log.find("walking_gt 2/2: ATE "), std::string::npos) << log;
  EXPECT_NE(log.find("error: 1 of 3 runs failed"), std::string::npos) << log;

  std::ifstream json_file(out / "benchmark.json");
  const nlohmann::json json = nlohmann::json::parse(json_file);
  EXPECT_EQ(json["failed_runs"], 1);
  EXPECT_EQ(json["interrupted"], false);
  ASSERT_EQ(json["entries"].size(), 2u);
  const nlohmann::json& broken_entry = json["entries"][0];
  EXPECT_EQ(broken_entry["runs"][0]["status"], "failed");
  EXPECT_NE(broken_entry["runs"][0]["error"].get<std::string>().find("cannot decode"),
            std::string::npos);
  const nlohmann::json& walking = json["entries"][1];
  EXPECT_EQ(walking["segmenter"], "gt");
  EXPECT_EQ(walking["segmenter_label"], "gt (ORACLE masks)");
  EXPECT_EQ(walking["oracle"], true);
  EXPECT_EQ(walking["dynamic_setup"], "segmenter gt, dynamic on");
  EXPECT_EQ(walking["mode"], "sequential");
  ASSERT_EQ(walking["runs"].size(), 2u);
  const nlohmann::json& first = walking["runs"][0];
  const nlohmann::json& second = walking["runs"][1];
  EXPECT_EQ(first["status"], "ok");
  EXPECT_EQ(first["frames"], kFrames);
  EXPECT_GE(first["tracked_share"].get<double>(), 0.95);
  const double ate = first["ate_rmse_m"].get<double>();
  EXPECT_GT(ate, 0.0);
  EXPECT_LT(ate, 0.05);
  // Sequential runs are bit-identical: the same ATE and RPE, so no spread.
  EXPECT_EQ(second["ate_rmse_m"].get<double>(), ate);
  EXPECT_EQ(second["rpe_trans_rmse_m"].get<double>(), first["rpe_trans_rmse_m"].get<double>());
  const nlohmann::json& aggregate = walking["aggregate"];
  EXPECT_EQ(aggregate["evaluated"], 2);
  EXPECT_EQ(aggregate["ate_rmse_m"]["median"].get<double>(), ate);
  EXPECT_EQ(aggregate["ate_rmse_m"]["std"].get<double>(), 0.0);
  for (const char* key : {"rpe_trans_rmse_m", "rpe_rot_rmse_deg", "tracked_share", "frames_lost",
                          "wall_s", "fps", "track_median_ms", "track_p95_ms"}) {
    EXPECT_EQ(aggregate[key]["count"], 2) << key;
  }
  EXPECT_GT(aggregate["track_median_ms"]["median"].get<double>(), 0.0);
  EXPECT_GT(aggregate["fps"]["median"].get<double>(), 0.0);
  const std::string run_dir = (out / "walking_gt" / "run_2").string();
  EXPECT_EQ(second["out_dir"], run_dir);
  for (const char* file : {"CameraTrajectory.txt", "stats.json", "eval.json", "frames.tsv"}) {
    EXPECT_TRUE(fs::exists(fs::path(run_dir) / file)) << file;
  }
  // The run's frame log: a header and one line per frame.
  const std::string frame_log = test::ReadFile(fs::path(run_dir) / "frames.tsv");
  EXPECT_EQ(std::count(frame_log.begin(), frame_log.end(), '\n'), kFrames + 1);
  // frames_skipped is the run's own stats.json figure where it reports one, else null.
  std::ifstream stats_file(fs::path(run_dir) / "stats.json");
  const nlohmann::json stats = nlohmann::json::parse(stats_file);
  EXPECT_EQ(second["frames_skipped"],
            stats.contains("frames_skipped") ? stats["frames_skipped"] : nlohmann::json(nullptr));
  std::ifstream eval_file(fs::path(run_dir) / "eval.json");
  EXPECT_EQ(nlohmann::json::parse(eval_file)["ate"]["rmse"].get<double>(), ate);

  const std::string md = test::ReadFile(out / "benchmark.md");
  ExpectRectangularTables(md);
  char ate_cell[32];
  std::snprintf(ate_cell, sizeof(ate_cell), "%.2f", 100 * ate);
  EXPECT_NE(md.find("| walking_gt | gt (ORACLE masks) | on | sequential | 2/2 | 60 | " +
                    std::string(ate_cell) + " | " + ate_cell + " | " + ate_cell + " | 0.00 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| broken | gt (ORACLE masks) | on | sequential | 0/1 (1 FAILED) |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("**ORACLE masks:**"), std::string::npos) << md;
  EXPECT_NE(md.find("drvslam benchmark --list " + (root_ / "bench.json").string() +
                    " --runs 2 --out " + out.string()),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("`drvslam run --dataset " + (root_ / "seq").string() + " --out " +
                    (out / "walking_gt" / "run_1").string() +
                    " --sequential --segmenter gt --dense off`"),
            std::string::npos)
      << md;
}

TEST_F(BenchmarkEndToEndTest, StrictSettingsStopsATypoBeforeAnyRunAndReachesEveryRun) {
  const fs::path typo = root_ / "typo.yaml";
  WriteText(typo, "%YAML:1.0\nDynamic.largeshare: 0.4\n");
  const fs::path clean = root_ / "clean.yaml";
  WriteText(clean, "%YAML:1.0\nDynamic.largeShare: 0.4\n");
  BenchmarkShortcut shortcut;
  shortcut.datasets = {(root_ / "seq").string()};
  shortcut.mode = "sequential";
  shortcut.dense = "off";
  shortcut.max_frames = 5;
  BenchmarkOptions options;
  options.runs = 1;
  options.strict_settings = true;
  int started = 0;
  BenchmarkProgress progress;
  progress.run_started = [&started](const BenchmarkEntryResult&, int) { ++started; };

  shortcut.config = typo.string();
  options.entries = EntriesFromShortcut(shortcut);
  options.out_dir = (root_ / "strict_typo").string();
  const std::string message = ErrorOf([&] { RunBenchmark(options, progress); });
  EXPECT_NE(message.find("--dataset " + (root_ / "seq").string()), std::string::npos) << message;
  EXPECT_NE(message.find("unknown setting Dynamic.largeshare (did you mean Dynamic.largeShare?)"),
            std::string::npos)
      << message;
  EXPECT_EQ(started, 0);

  // Without the flag the typo is a warning and the run goes ahead.
  options.strict_settings = false;
  options.out_dir = (root_ / "lenient_typo").string();
  const BenchmarkReport lenient = RunBenchmark(options, progress);
  ASSERT_EQ(lenient.entries.size(), 1u);
  EXPECT_EQ(lenient.FailedRuns(), 0u);
  EXPECT_EQ(lenient.entries[0].run_command.find("--strict-settings"), std::string::npos);

  // A clean file runs, and each run is the strict `drvslam run` the report quotes.
  shortcut.config = clean.string();
  options.entries = EntriesFromShortcut(shortcut);
  options.strict_settings = true;
  options.out_dir = (root_ / "strict_clean").string();
  const BenchmarkReport strict = RunBenchmark(options, progress);
  ASSERT_EQ(strict.entries.size(), 1u);
  ASSERT_EQ(strict.entries[0].runs.size(), 1u);
  EXPECT_EQ(strict.entries[0].runs[0].status, RunStatus::kOk) << strict.entries[0].runs[0].error;
  EXPECT_NE(strict.entries[0].run_command.find(" --strict-settings"), std::string::npos)
      << strict.entries[0].run_command;
  EXPECT_EQ(started, 2);

  // Through the CLI: the flag is accepted, and the typo ends the command with status 2.
  const std::string log = (root_ / "strict_cli.txt").string();
  const std::string command = std::string(DRVSLAM_CLI) + " benchmark --strict-settings --dataset " +
                              (root_ / "seq").string() + " --config " + typo.string() +
                              " --runs 1 --out " + (root_ / "strict_cli").string() + " > " + log +
                              " 2>&1";
  const int status = std::system(command.c_str());
  const std::string output = test::ReadFile(log);
  ASSERT_TRUE(WIFEXITED(status)) << output;
  EXPECT_EQ(WEXITSTATUS(status), 2) << output;
  EXPECT_NE(output.find("error: "), std::string::npos) << output;
  EXPECT_NE(output.find("unknown setting Dynamic.largeshare"), std::string::npos) << output;
}

TEST_F(BenchmarkEndToEndTest, StoppingKeepsTheTablesOfWhatFinished) {
  BenchmarkOptions options;
  BenchmarkShortcut shortcut;
  shortcut.datasets = {(root_ / "seq").string()};
  shortcut.mode = "sequential";
  shortcut.dense = "off";
  options.entries = EntriesFromShortcut(shortcut);
  options.runs = 3;
  options.out_dir = (root_ / "stopped").string();
  std::atomic<bool> stop{false};
  BenchmarkProgress progress;
  int started = 0;
  progress.run_started = [&started](const BenchmarkEntryResult&, int) { ++started; };
  progress.frame_done = [&stop](std::size_t done, std::size_t) {
    if (done == 10) stop = true;  // Ctrl-C during the first run
  };
  const BenchmarkReport report = RunBenchmark(options, progress, &stop);
  EXPECT_TRUE(report.interrupted);
  EXPECT_EQ(started, 1);
  ASSERT_EQ(report.entries.size(), 1u);
  ASSERT_EQ(report.entries[0].runs.size(), 1u);
  EXPECT_EQ(report.entries[0].runs[0].status, RunStatus::kInterrupted);
  EXPECT_EQ(report.entries[0].runs[0].frames, 10u);
  EXPECT_EQ(report.entries[0].aggregate.finished, 0u);
  EXPECT_EQ(report.FailedRuns(), 0u);
  const std::string md = test::ReadFile(root_ / "stopped" / "benchmark.md");
  EXPECT_NE(md.find("status: interrupted (Ctrl-C)"), std::string::npos) << md;
  EXPECT_NE(md.find("| seq | 1 | interrupted |"), std::string::npos) << md;
  std::ifstream json_file(root_ / "stopped" / "benchmark.json");
  EXPECT_EQ(nlohmann::json::parse(json_file)["interrupted"], true);
}

TEST_F(BenchmarkEndToEndTest, AViewerEntryRunsWithAConnectedBrowserBesideItsViewerOffTwin) {
  std::string chromium;
  try {
    chromium = FindChromium();
  } catch (const Error& e) {
    DRVSLAM_MISSING_TEST_DATA() << e.what();
  }
  WriteText(root_ / "viewer.json", R"({"entries": [
      {"name": "walking", "dataset": "seq", "segmenter": "gt", "dense": "off",
       "max_frames": 40}]})");
  const fs::path out = root_ / "viewer_out";
  const std::string command = std::string(DRVSLAM_CLI) + " --log-level warn benchmark --list " +
                              (root_ / "viewer.json").string() + " --viewer-pairs --runs 1 --out " +
                              out.string() + " > " + (root_ / "viewer_log.txt").string() + " 2>&1";
  const int status = std::system(command.c_str());
  const std::string log = test::ReadFile(root_ / "viewer_log.txt");
  ASSERT_TRUE(WIFEXITED(status)) << log;
  ASSERT_EQ(WEXITSTATUS(status), 0) << log;
  EXPECT_NE(log.find("walking_viewer 1/1: ATE "), std::string::npos) << log;
  EXPECT_NE(log.find(", browser connected ("), std::string::npos) << log;

  std::ifstream json_file(out / "benchmark.json");
  const nlohmann::json json = nlohmann::json::parse(json_file);
  ASSERT_EQ(json["entries"].size(), 2u);
  const nlohmann::json& off = json["entries"][0]["runs"][0];
  const nlohmann::json& on = json["entries"][1]["runs"][0];
  EXPECT_EQ(json["entries"][1]["name"], "walking_viewer");
  EXPECT_EQ(off["browser"], nullptr);
  EXPECT_EQ(off["observer_median_ms"], nullptr);  // no viewer, no observer stage
  EXPECT_EQ(on["status"], "ok");
  EXPECT_EQ(on["frames"], 40);
  EXPECT_EQ(on["browser"]["connected"], true) << on.dump(2);
  EXPECT_EQ(on["browser"]["connections"], 1);
  // Every tracked pose reaches the page, in batches: at least a handful of messages.
  EXPECT_GE(on["browser"]["messages"].get<int>(), 10);
  EXPECT_GT(on["browser"]["bytes"].get<double>(), 1000.0);
  EXPECT_GT(on["observer_median_ms"].get<double>(), 0.0);
  EXPECT_GE(on["observer_p95_ms"].get<double>(), on["observer_median_ms"].get<double>());
  EXPECT_GT(on["ate_rmse_m"].get<double>(), 0.0);
  EXPECT_LT(on["ate_rmse_m"].get<double>(), 0.05);
  EXPECT_TRUE(fs::exists(out / "walking_viewer" / "run_1" / "browser.log"));

  const std::string md = test::ReadFile(out / "benchmark.md");
  ExpectRectangularTables(md);
  EXPECT_NE(md.find("| walking | gt (ORACLE masks) | threaded | 1/1 | off | - | - | - | "),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| walking_viewer | gt (ORACLE masks) | threaded | 1/1 | on | connected "
                    "(1/1 runs) | "),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("- walking_viewer run 1: the page connected "), std::string::npos) << md;
  EXPECT_NE(md.find("--viewer 0`"), std::string::npos) << md;
}

}  // namespace
}  // namespace drvslam
