// `drvslam benchmark`: the statistics over runs, the list file and its errors, the tables and the
// viewer entries (the runs through the CLI: benchmark_end_to_end_test.cc).
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

// A folder that passes the list checks: it exists and has a groundtruth.txt.
fs::path FakeSequence(const fs::path& path) {
  WriteText(path / "groundtruth.txt", "0 0 0 0 0 0 0 1\n");
  return path;
}

BenchmarkRun FinishedRun(int index, std::optional<double> ate, double tracked_share) {
  BenchmarkRun run;
  run.index = index;
  run.ate_rmse = ate;
  run.rpe_trans_rmse = ate ? std::optional<double>(*ate / 2) : std::nullopt;
  run.tracked_share = tracked_share;
  run.frames = 100;
  run.tracked = static_cast<std::size_t>(100 * tracked_share);
  run.frames_lost = 100 - run.tracked;
  run.wall_s = 10.0 + index;
  run.fps = 100 / run.wall_s;
  run.track_median_ms = 20.0 + index;
  run.track_p95_ms = 40.0 + index;
  return run;
}

TEST(BenchmarkAggregateTest, MedianMinMaxAndPopulationStdOverTheEvaluatedRuns) {
  std::vector<BenchmarkRun> runs = {FinishedRun(1, 0.01, 1.0), FinishedRun(2, 0.03, 0.98),
                                    FinishedRun(3, 0.02, 0.99), FinishedRun(4, 0.05, 0.97),
                                    FinishedRun(5, std::nullopt, 0.10)};
  BenchmarkRun failed;
  failed.index = 6;
  failed.status = RunStatus::kFailed;
  failed.error = "cannot decode";
  runs.push_back(failed);

  const BenchmarkAggregate a = AggregateRuns(runs);
  EXPECT_EQ(a.runs, 6u);
  EXPECT_EQ(a.finished, 5u);
  EXPECT_EQ(a.evaluated, 4u);
  EXPECT_EQ(a.ate_rmse.count, 4u);
  EXPECT_DOUBLE_EQ(a.ate_rmse.median, 0.025);  // even count: mean of the middle two
  EXPECT_DOUBLE_EQ(a.ate_rmse.min, 0.01);
  EXPECT_DOUBLE_EQ(a.ate_rmse.max, 0.05);
  EXPECT_NEAR(a.ate_rmse.mean, 0.0275, 1e-12);
  EXPECT_NEAR(a.ate_rmse.std, std::sqrt(8.75e-4 / 4), 1e-12);  // divides by n, as numpy
  EXPECT_DOUBLE_EQ(a.rpe_trans_rmse.median, 0.0125);
  // Tracked share, lost frames and timings count every finished run, the unevaluated one too.
  EXPECT_EQ(a.tracked_share.count, 5u);
  EXPECT_DOUBLE_EQ(a.tracked_share.median, 0.98);
  EXPECT_DOUBLE_EQ(a.tracked_share.min, 0.10);
  EXPECT_DOUBLE_EQ(a.frames_lost.max, 90.0);
  EXPECT_DOUBLE_EQ(a.wall_s.median, 13.0);
  EXPECT_DOUBLE_EQ(a.track_median_ms.median, 23.0);
  EXPECT_DOUBLE_EQ(a.track_p95_ms.median, 43.0);
  EXPECT_FALSE(a.frames_skipped.has_value());
}

TEST(BenchmarkAggregateTest, FramesSkippedOnlyWhenEveryFinishedRunReportsThem) {
  std::vector<BenchmarkRun> runs = {FinishedRun(1, 0.01, 1.0), FinishedRun(2, 0.01, 1.0),
                                    FinishedRun(3, 0.01, 1.0)};
  runs[0].frames_skipped = 4;
  runs[1].frames_skipped = 0;
  EXPECT_FALSE(AggregateRuns(runs).frames_skipped.has_value());
  runs[2].frames_skipped = 9;
  const BenchmarkAggregate a = AggregateRuns(runs);
  ASSERT_TRUE(a.frames_skipped.has_value());
  EXPECT_DOUBLE_EQ(a.frames_skipped->median, 4.0);
  EXPECT_DOUBLE_EQ(a.frames_skipped->max, 9.0);
}

// A YOLO entry with dynamic handling on and `runs` finished runs.
BenchmarkEntryResult YoloEntry(const std::string& name, const std::string& mode, int runs) {
  BenchmarkEntryResult entry;
  entry.entry.name = name;
  entry.entry.mode = mode;
  entry.segmenter = "yolo";
  entry.segmenter_used = entry.dynamic_on = true;
  entry.runs_requested = runs;
  for (int i = 1; i <= runs; ++i) entry.runs.push_back(FinishedRun(i, 0.012 + 0.001 * i, 0.95));
  return entry;
}

TEST(BenchmarkReportTest, RealtimeTablesShowHowLongTrackingWaitedForACore) {
  BenchmarkEntryResult realtime = YoloEntry("crowd_realtime", "realtime", 3);
  const double waits[] = {4.2, 3.1, 5.4};
  for (std::size_t i = 0; i < 3; ++i) {
    realtime.runs[i].frames_skipped = 10 + i;
    realtime.runs[i].camera_to_done_s = 16.0;
    realtime.runs[i].tracking_wait_s = waits[i];
  }
  realtime.aggregate = AggregateRuns(realtime.runs);
  ASSERT_TRUE(realtime.aggregate.tracking_wait_s.has_value());
  EXPECT_DOUBLE_EQ(realtime.aggregate.tracking_wait_s->median, 4.2);
  EXPECT_DOUBLE_EQ(realtime.aggregate.tracking_wait_s->max, 5.4);
  BenchmarkReport report;
  report.command = "drvslam benchmark --dataset d --mode realtime --runs 3 --out o";
  report.machine = DescribeMachine();
  report.entries = {realtime};
  const std::string md = FormatBenchmarkMarkdown(report);
  EXPECT_NE(md.find("tracking waited (s)"), std::string::npos) << md;
  EXPECT_NE(md.find("| 4.2 (max 5.4) |"), std::string::npos) << md;  // summary row
  // Run 3's row: frames skipped, camera to done, tracking waited.
  EXPECT_NE(md.find("| 12 | 16.0 | 5.4 |"), std::string::npos) << md;
  ExpectRectangularTables(md);
  const nlohmann::json json = BenchmarkJson(report);
  EXPECT_DOUBLE_EQ(json["entries"][0]["aggregate"]["tracking_wait_s"]["median"].get<double>(), 4.2);
  EXPECT_DOUBLE_EQ(json["entries"][0]["runs"][1]["tracking_wait_s"].get<double>(), 3.1);
}

TEST(BenchmarkListTest, ReadsEntriesWithPathsRelativeToTheListFile) {
  const fs::path root = test::FreshTempFolder("drvslam_benchmark_list");
  FakeSequence(root / "data" / "walking_xyz");
  WriteText(root / "lists" / "bench.json", R"({"entries": [
      {"dataset": "../data/walking_xyz"},
      {"name": "walking-yolo", "dataset": "../data/walking_xyz/", "config": "../data/s.yaml",
       "segmenter": "yolo", "model": "/models/m.onnx", "dynamic": "on", "mode": "realtime",
       "dense": "off", "loop": "on", "max_frames": 120, "runs": 3}]})");
  const std::vector<BenchmarkEntry> entries =
      ReadBenchmarkList((root / "lists" / "bench.json").string());
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[0].name, "walking_xyz");
  EXPECT_EQ(entries[0].dataset, (root / "data" / "walking_xyz").string());
  EXPECT_EQ(entries[0].mode, "threaded");
  EXPECT_FALSE(entries[0].runs.has_value());
  EXPECT_EQ(entries[1].name, "walking-yolo");
  EXPECT_EQ(entries[1].config, (root / "data" / "s.yaml").string());
  EXPECT_EQ(entries[1].model, "/models/m.onnx");
  EXPECT_EQ(entries[1].segmenter, "yolo");
  EXPECT_EQ(entries[1].mode, "realtime");
  EXPECT_EQ(entries[1].dense, "off");
  EXPECT_EQ(entries[1].loop, "on");
  EXPECT_EQ(entries[1].max_frames, 120u);
  EXPECT_EQ(entries[1].runs, 3);

  const RunOptions run = ToRunOptions(entries[1], "out/walking-yolo/run_1");
  EXPECT_FALSE(run.sequential);
  EXPECT_TRUE(run.dynamic.realtime);
  EXPECT_EQ(run.max_frames, 120u);
  EXPECT_EQ(FormatRunCommand(run),
            "drvslam run --dataset " + entries[1].dataset + " --config " + entries[1].config +
                " --out out/walking-yolo/run_1 --realtime --max-frames 120 --segmenter yolo "
                "--model /models/m.onnx --dynamic on --dense off --loop on");
  fs::remove_all(root);
}

TEST(BenchmarkListTest, ListErrorsNameTheFileTheEntryAndTheKey) {
  const fs::path root = test::FreshTempFolder("drvslam_benchmark_list_errors");
  FakeSequence(root / "seq");
  const auto read = [&root](const std::string& text) {
    WriteText(root / "bench.json", text);
    return ErrorOf([&root] { ReadBenchmarkList((root / "bench.json").string()); });
  };
  const std::string file = (root / "bench.json").string();
  std::string message =
      read(R"({"entries": [{"dataset": "seq"}, {"dataset": "seq", "mdoe": "x"}]})");
  EXPECT_NE(message.find(file + ": entry 2"), std::string::npos) << message;
  EXPECT_NE(message.find("unknown key 'mdoe'"), std::string::npos) << message;
  message = read(R"({"entries": [{"dataset": "seq", "runs": "5"}]})");
  EXPECT_NE(message.find("entry 1: key 'runs' must be an integer"), std::string::npos) << message;
  message = read(R"({"entries": [{"dataset": 3}]})");
  EXPECT_NE(message.find("key 'dataset' must be a string"), std::string::npos) << message;
  message = read(R"({"entries": [{"name": "x"}]})");
  EXPECT_NE(message.find("key 'dataset' is missing"), std::string::npos) << message;
  message = read(R"({"entries": [{"dataset": "seq", "max_frames": -1}]})");
  EXPECT_NE(message.find("max_frames = -1"), std::string::npos) << message;
  message = read(R"({"entries": [{"dataset": "seq"},]})");
  EXPECT_NE(message.find(file + ": not valid JSON"), std::string::npos) << message;
  message = read(R"({"entries": [], "runs": 3})");
  EXPECT_NE(message.find("unknown key 'runs'"), std::string::npos) << message;
  message = read(R"({"entries": []})");
  EXPECT_NE(message.find("'entries' is empty"), std::string::npos) << message;
  message = ErrorOf([&root] { ReadBenchmarkList((root / "absent.json").string()); });
  EXPECT_NE(message.find("absent.json: cannot open"), std::string::npos) << message;
  fs::remove_all(root);
}

TEST(BenchmarkListTest, EntriesThatCannotRunAreRejectedBeforeAnyRun) {
  const fs::path root = test::FreshTempFolder("drvslam_benchmark_check");
  FakeSequence(root / "seq");
  fs::create_directories(root / "no_gt");
  const auto check = [&root](const std::string& entry_json) {
    WriteText(root / "bench.json", "{\"entries\": [" + entry_json + "]}");
    return ErrorOf(
        [&root] { CheckBenchmarkEntries(ReadBenchmarkList((root / "bench.json").string())); });
  };
  std::string message = check(R"({"dataset": "absent"})");
  EXPECT_NE(message.find("entry 1 (absent): dataset folder"), std::string::npos) << message;
  EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
  message = check(R"({"dataset": "no_gt"})");
  EXPECT_NE(message.find("has no groundtruth.txt"), std::string::npos) << message;
  message = check(R"({"dataset": "seq", "mode": "fast"})");
  EXPECT_NE(message.find("mode = 'fast' must be threaded, sequential or realtime"),
            std::string::npos)
      << message;
  message = check(R"({"dataset": "seq", "segmenter": "sam"})");
  EXPECT_NE(message.find("segmenter = 'sam'"), std::string::npos) << message;
  message = check(R"({"dataset": "seq", "dynamic": "yes"})");
  EXPECT_NE(message.find("dynamic = 'yes' must be on or off"), std::string::npos) << message;
  message = check(R"({"dataset": "seq", "runs": 0})");
  EXPECT_NE(message.find("entry 1 (seq): runs = 0 must be at least 1"), std::string::npos)
      << message;
  message = check(R"({"dataset": "seq", "config": "absent.yaml"})");
  EXPECT_NE(message.find("config file"), std::string::npos) << message;
  message = check(R"({"dataset": "seq", "name": "a/b"})");
  EXPECT_NE(message.find("name 'a/b' must be"), std::string::npos) << message;
  message = check(R"({"dataset": "seq"}, {"dataset": "seq"})");
  EXPECT_NE(message.find("entry 2 (seq): name 'seq' is already used by"), std::string::npos)
      << message;
  WriteText(root / "bench.json",
            R"({"entries": [{"dataset": "seq", "name": "a"}, {"dataset": "seq", "name": "b"}]})");
  EXPECT_NO_THROW(CheckBenchmarkEntries(ReadBenchmarkList((root / "bench.json").string())));

  // --runs below 1 is refused before any folder is made.
  BenchmarkShortcut shortcut;
  shortcut.datasets = {(root / "seq").string()};
  BenchmarkOptions options;
  options.entries = EntriesFromShortcut(shortcut);
  options.runs = 0;
  options.out_dir = (root / "out").string();
  message = ErrorOf([&options] { RunBenchmark(options); });
  EXPECT_NE(message.find("--runs = 0 must be at least 1"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(root / "out"));
  fs::remove_all(root);
}

TEST(BenchmarkListTest, ShortcutNamesEachEntryAfterItsFolderUniquely) {
  BenchmarkShortcut shortcut;
  shortcut.datasets = {"data/walking_xyz/", "other/walking_xyz", "static xyz"};
  shortcut.mode = "sequential";
  shortcut.segmenter = "gt";
  const std::vector<BenchmarkEntry> entries = EntriesFromShortcut(shortcut);
  ASSERT_EQ(entries.size(), 3u);
  EXPECT_EQ(entries[0].name, "walking_xyz");
  EXPECT_EQ(entries[1].name, "walking_xyz_2");
  EXPECT_EQ(entries[2].name, "static_xyz");
  EXPECT_EQ(entries[2].origin, "--dataset static xyz");
  EXPECT_EQ(entries[1].mode, "sequential");
  EXPECT_EQ(entries[1].segmenter, "gt");
  EXPECT_EQ(ShellQuote("static xyz"), "'static xyz'");
  EXPECT_EQ(ShellQuote("it's"), "'it'\\''s'");
  EXPECT_EQ(ShellQuote("a/b_c-1.json"), "a/b_c-1.json");
}

TEST(BenchmarkReportTest, TablesLabelOracleMasksAndShowFailedRuns) {
  BenchmarkReport report;
  report.command = "drvslam benchmark --list b.json --runs 2 --out o";
  report.machine = DescribeMachine();
  BenchmarkEntryResult oracle;
  oracle.entry.name = "walking_gt";
  oracle.entry.mode = "threaded";
  oracle.segmenter = "gt";
  oracle.segmenter_used = oracle.dynamic_on = oracle.oracle = true;
  oracle.runs_requested = 2;
  oracle.runs = {FinishedRun(1, 0.0123, 1.0), FinishedRun(2, 0.0125, 0.99)};
  oracle.runs[1].frames_skipped = 3;  // only one run reports it: no column
  oracle.aggregate = AggregateRuns(oracle.runs);
  BenchmarkEntryResult yolo;
  yolo.entry.name = "walking_yolo";
  yolo.entry.mode = "realtime";
  yolo.segmenter = "yolo";
  yolo.model = "/m/yolov8n-seg-320x256.onnx";
  yolo.segmenter_used = yolo.dynamic_on = true;
  yolo.runs_requested = 2;
  BenchmarkRun failed;
  failed.index = 1;
  failed.status = RunStatus::kFailed;
  failed.error = "rgb/1.png: cannot decode colour image | corrupt";
  yolo.runs = {failed, FinishedRun(2, std::nullopt, 0.02)};
  yolo.runs[1].eval_note = "ATE n/a: too few";
  yolo.aggregate = AggregateRuns(yolo.runs);
  BenchmarkEntryResult off;
  off.entry.name = "walking_off";
  off.entry.mode = "sequential";
  off.segmenter = "gt";
  off.runs_requested = 2;
  report.entries = {oracle, yolo, off};

  const std::string md = FormatBenchmarkMarkdown(report);
  ExpectRectangularTables(md);
  EXPECT_NE(md.find("| walking_gt | gt (ORACLE masks) | on | threaded | 2/2 | 100 | 1.24 | 1.23 | "
                    "1.25 | 0.01 | 0.62 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("**ORACLE masks:**"), std::string::npos) << md;
  EXPECT_NE(md.find("| walking_yolo | yolo (yolov8n-seg-320x256.onnx) | on | realtime | 1/2 (1 "
                    "FAILED) | 100 | n/a | n/a | n/a | n/a | n/a |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| walking_off | none (dynamic off) | off | sequential | 0/2 | n/a |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("1 run FAILED"), std::string::npos) << md;
  EXPECT_NE(md.find("- walking_yolo run 1: rgb/1.png: cannot decode"), std::string::npos) << md;
  EXPECT_NE(md.find("| walking_yolo | 1 | **FAILED** |"), std::string::npos) << md;
  EXPECT_EQ(md.find("frames skipped"), std::string::npos) << md;
  EXPECT_NE(md.find("load average at the start " + report.machine.load_average), std::string::npos)
      << md;

  const nlohmann::json json = BenchmarkJson(report);
  EXPECT_EQ(json["failed_runs"], 1);
  EXPECT_EQ(json["entries"][0]["segmenter_label"], "gt (ORACLE masks)");
  EXPECT_EQ(json["entries"][0]["oracle"], true);
  EXPECT_EQ(json["entries"][1]["oracle"], false);
  EXPECT_EQ(json["entries"][1]["runs"][0]["status"], "failed");
  EXPECT_TRUE(json["entries"][1]["aggregate"]["ate_rmse_m"].is_null());
  EXPECT_TRUE(json["entries"][1]["runs"][1]["ate_rmse_m"].is_null());
  EXPECT_DOUBLE_EQ(json["entries"][0]["aggregate"]["ate_rmse_m"]["median"].get<double>(), 0.0124);
  EXPECT_GT(json["machine"]["cores"].get<int>(), 0);
}

// An environment variable set (or unset, for nullptr) for one scope.
class ScopedEnvironment {
 public:
  ScopedEnvironment(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value) {
      setenv(name, value, 1);
    } else {
      unsetenv(name);
    }
  }
  ~ScopedEnvironment() {
    if (old_) {
      setenv(name_.c_str(), old_->c_str(), 1);
    } else {
      unsetenv(name_.c_str());
    }
  }

 private:
  std::string name_;
  std::optional<std::string> old_;
};

TEST(BenchmarkViewerListTest, ViewerKeyIsReadAndABadValueNamesTheFileAndTheKey) {
  const fs::path root = test::FreshTempFolder("drvslam_benchmark_viewer_list");
  FakeSequence(root / "walking_xyz");
  WriteText(root / "bench.json", R"({"entries": [
      {"name": "off", "dataset": "walking_xyz"},
      {"name": "on", "dataset": "walking_xyz", "viewer": true},
      {"name": "said_off", "dataset": "walking_xyz", "viewer": false}]})");
  const std::vector<BenchmarkEntry> entries = ReadBenchmarkList((root / "bench.json").string());
  ASSERT_EQ(entries.size(), 3u);
  EXPECT_FALSE(entries[0].viewer);
  EXPECT_TRUE(entries[1].viewer);
  EXPECT_FALSE(entries[2].viewer);
  // A viewer run serves on any free port, as `drvslam run --viewer 0` does.
  const RunOptions on = ToRunOptions(entries[1], "out/on/run_1");
  ASSERT_TRUE(on.viewer_port.has_value());
  EXPECT_EQ(*on.viewer_port, 0);
  EXPECT_EQ(FormatRunCommand(on),
            "drvslam run --dataset " + entries[1].dataset + " --out out/on/run_1 --viewer 0");
  EXPECT_FALSE(ToRunOptions(entries[0], "out/off/run_1").viewer_port.has_value());

  for (const char* bad : {R"("yes")", "1", "null"}) {
    const fs::path list = root / "bad.json";
    WriteText(list,
              std::string(R"({"entries": [{"dataset": "walking_xyz", "viewer": )") + bad + "}]}");
    const std::string message = ErrorOf([&] { ReadBenchmarkList(list.string()); });
    EXPECT_NE(message.find(list.string() + ": entry 1"), std::string::npos) << message;
    EXPECT_NE(message.find("key 'viewer' must be true or false"), std::string::npos) << message;
  }
  fs::remove_all(root);
}

TEST(BenchmarkViewerListTest, ViewerPairsAddAViewerTwinAfterEachEntryWithoutOne) {
  BenchmarkEntry plain;
  plain.name = "walking";
  plain.dataset = "seq/walking";
  plain.segmenter = "gt";
  plain.origin = "--dataset seq/walking";
  BenchmarkEntry watched = plain;
  watched.name = "watched";
  watched.viewer = true;
  const std::vector<BenchmarkEntry> paired = WithViewerTwins({plain, watched});
  ASSERT_EQ(paired.size(), 3u);
  EXPECT_EQ(paired[0].name, "walking");
  EXPECT_FALSE(paired[0].viewer);
  EXPECT_EQ(paired[1].name, "walking_viewer");
  EXPECT_TRUE(paired[1].viewer);
  EXPECT_EQ(paired[1].segmenter, "gt");
  EXPECT_EQ(paired[1].dataset, "seq/walking");
  EXPECT_EQ(paired[2].name, "watched");
  EXPECT_TRUE(paired[2].viewer);
}

TEST(BenchmarkViewerListTest, AMissingChromiumIsAnErrorNamingWhatIsMissing) {
  const fs::path root = test::FreshTempFolder("drvslam_benchmark_no_chromium");
  {
    const ScopedEnvironment chosen("DRVSLAM_CHROMIUM", (root / "no-such-browser").c_str());
    const std::string message = ErrorOf([] { FindChromium(); });
    EXPECT_NE(message.find("DRVSLAM_CHROMIUM = " + (root / "no-such-browser").string() +
                           " is not an executable file"),
              std::string::npos)
        << message;
  }
  {
    const ScopedEnvironment chosen("DRVSLAM_CHROMIUM", nullptr);
    const ScopedEnvironment path("PATH", root.c_str());  // a folder without any browser
    const std::string message = ErrorOf([] { FindChromium(); });
    EXPECT_NE(message.find("chromium is missing"), std::string::npos) << message;
    EXPECT_NE(message.find("neither `chromium` nor `chromium-browser` is on PATH"),
              std::string::npos)
        << message;
  }
  fs::remove_all(root);
}

BenchmarkEntryResult ViewerCostEntry(const std::string& name, bool viewer,
                                     std::vector<BenchmarkRun> runs) {
  BenchmarkEntryResult entry;
  entry.entry.name = name;
  entry.entry.viewer = viewer;
  entry.segmenter = "gt";
  entry.segmenter_used = entry.dynamic_on = entry.oracle = true;
  entry.runs_requested = static_cast<int>(runs.size());
  entry.runs = std::move(runs);
  entry.aggregate = AggregateRuns(entry.runs);
  return entry;
}

TEST(BenchmarkReportTest, ViewerEntriesGetTheTrackingCostTableWithTheBrowserConnection) {
  BenchmarkRun off_1 = FinishedRun(1, 0.012, 1.0);
  BenchmarkRun off_2 = FinishedRun(2, 0.014, 1.0);
  BenchmarkRun on_1 = FinishedRun(1, 0.013, 1.0);
  on_1.observer_median_ms = 0.25;
  on_1.observer_p95_ms = 0.75;
  on_1.browser = BrowserConnection{true, 2.5, 1, 420, 3200000, ""};
  BenchmarkRun on_2 = FinishedRun(2, 0.015, 1.0);
  on_2.observer_median_ms = 0.35;
  on_2.observer_p95_ms = 0.95;
  on_2.browser = BrowserConnection{};
  on_2.browser->note = "the page did not connect within 30 s (see browser.log)";
  BenchmarkReport report;
  report.command = "drvslam benchmark --list b.json --viewer-pairs";
  report.entries = {ViewerCostEntry("walking", false, {off_1, off_2}),
                    ViewerCostEntry("walking_viewer", true, {on_1, on_2})};
  EXPECT_EQ(report.entries[1].aggregate.browser_connected, 1u);
  ASSERT_TRUE(report.entries[1].aggregate.observer_median_ms.has_value());
  EXPECT_DOUBLE_EQ(report.entries[1].aggregate.observer_median_ms->median, 0.30);
  EXPECT_FALSE(report.entries[0].aggregate.observer_median_ms.has_value());

  const std::string md = FormatBenchmarkMarkdown(report);
  ExpectRectangularTables(md);
  EXPECT_NE(md.find("## Tracking-thread cost of the live viewer"), std::string::npos) << md;
  // FinishedRun: track median 20 + run, p95 40 + run; the medians over two runs.
  EXPECT_NE(md.find("| walking | gt (ORACLE masks) | threaded | 2/2 | off | - | - | - | 21.50 | "
                    "41.50 | 1.30 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| walking_viewer | gt (ORACLE masks) | threaded | 2/2 | on | **NOT "
                    "connected** in 1 of 2 runs | 0.300 | 0.850 | 21.50 | 41.50 | 1.40 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("- walking_viewer run 1: the page connected 2.5 s after chromium started; "
                    "420 messages (3.2 MB) sent to it"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("- walking_viewer run 2: **the browser did not connect**: the page did not "
                    "connect within 30 s (see browser.log)"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("browser did not connect: the page did not connect within 30 s"),
            std::string::npos)
      << md;  // the run's note in the runs table

  const nlohmann::json json = BenchmarkJson(report);
  EXPECT_EQ(json["entries"][0]["viewer"], false);
  EXPECT_EQ(json["entries"][1]["viewer"], true);
  EXPECT_EQ(json["entries"][0]["runs"][0]["browser"], nullptr);
  EXPECT_EQ(json["entries"][0]["runs"][0]["observer_median_ms"], nullptr);
  EXPECT_EQ(json["entries"][1]["runs"][0]["browser"]["connected"], true);
  EXPECT_EQ(json["entries"][1]["runs"][0]["browser"]["messages"], 420);
  EXPECT_EQ(json["entries"][1]["runs"][1]["browser"]["connected"], false);
  EXPECT_DOUBLE_EQ(json["entries"][1]["aggregate"]["observer_p95_ms"]["median"].get<double>(),
                   0.85);

  // Without viewer entries the report has no such section.
  report.entries.pop_back();
  EXPECT_EQ(FormatBenchmarkMarkdown(report).find("Tracking-thread cost"), std::string::npos);
}
}  // namespace
}  // namespace drvslam
