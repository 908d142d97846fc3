// RunBenchmark: runs every entry of a benchmark N times through RunSequence, in the mode users
// run (threaded unless the entry says otherwise), evaluates each run against the sequence's
// groundtruth.txt the TUM way (ATE RMSE after rigid alignment, RPE over 1 s) and aggregates the
// runs into the figures papers print. Each run writes into OUT/<entry>/run_<k>/; the tables
// (benchmark.md, benchmark.json, see benchmark_report.h) are rewritten after every run.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "drvslam/tools/eval/error_statistics.h"
#include "drvslam/tools/runner/benchmark_list.h"

namespace drvslam {

struct BenchmarkOptions {
  std::vector<BenchmarkEntry> entries;
  int runs = 5;  // per entry, unless the entry sets its own
  std::string out_dir = "benchmark_out";
  std::string command;  // the `drvslam benchmark` command line, quoted in the report
  // --strict-settings: every run treats an unknown settings key as an error (RunOptions), and
  // each entry's settings file is checked so before the first run starts.
  bool strict_settings = false;
};

enum class RunStatus { kOk, kFailed, kInterrupted };

// A viewer entry's run: the headless browser on the live viewer's page.
struct BrowserConnection {
  bool connected = false;       // the page opened its WebSocket and was sent messages
  double connect_s = 0.0;       // from starting the browser until the page connected
  std::size_t connections = 0;  // WebSocket connections the viewer accepted
  std::size_t messages = 0;     // messages the viewer sent the page
  std::uint64_t bytes = 0;
  std::string note;  // why it did not connect
};

struct BenchmarkRun {
  int index = 0;  // 1-based: run_<index>
  std::string out_dir;
  RunStatus status = RunStatus::kOk;
  std::string error;  // why the run failed (status kFailed)
  std::size_t frames = 0;
  std::size_t tracked = 0;
  double tracked_share = 0.0;  // tracked / frames
  std::size_t frames_lost = 0;
  std::optional<double> ate_rmse;  // m; unset when too few poses associate
  std::optional<double> ate_coverage;
  std::optional<double> rpe_trans_rmse;  // m over 1 s; unset when too few pairs
  std::optional<double> rpe_rot_rmse_deg;
  std::string eval_note;  // why ATE or RPE is missing
  // The three trajectories of the run (m): the saved one's jitter (its ATE is ate_rmse), and
  // the ATE and jitter (eval/jitter.h) of the causal poses (OnlineCameraTrajectory.txt) and of
  // the poses as tracked (TrackedCameraTrajectory.txt).
  std::optional<double> jitter;
  std::optional<double> causal_ate_rmse;
  std::optional<double> causal_jitter;
  std::optional<double> tracked_ate_rmse;
  std::optional<double> tracked_jitter;
  double wall_s = 0.0;           // the whole RunSequence call: start-up, frames, shutdown, outputs
  double fps = 0.0;              // frames / wall_s
  double track_median_ms = 0.0;  // stats stage "total": the tracking thread's time per frame
  double track_p95_ms = 0.0;
  double vocabulary_load_ms = 0.0;
  std::optional<std::size_t> frames_skipped;  // when the run's stats.json reports it
  // Realtime runs: from the camera's first frame until every thread drained (wall_s without
  // start-up, decoding ahead and writing the outputs).
  std::optional<double> camera_to_done_s;
  // Realtime runs: seconds the tracking thread was ready to run but waited for a core, first
  // frame to last (stats.json threads); unset where the OS does not report it.
  std::optional<double> tracking_wait_s;
  // Stats stage "observer": the tracking thread's time handing each frame to the live viewer
  // (outside "total"); unset when the run had no viewer.
  std::optional<double> observer_median_ms;
  std::optional<double> observer_p95_ms;
  std::optional<BrowserConnection> browser;  // viewer entries
};

// Statistics over the runs of one entry (numpy's median and population std).
struct BenchmarkAggregate {
  std::size_t runs = 0;            // runs attempted
  std::size_t finished = 0;        // status kOk
  std::size_t evaluated = 0;       // finished with an ATE
  ErrorStatistics ate_rmse;        // m, over evaluated runs
  ErrorStatistics rpe_trans_rmse;  // m, over runs with an RPE
  ErrorStatistics rpe_rot_rmse_deg;
  // BenchmarkRun's trajectory figures, each over the runs that have it.
  ErrorStatistics jitter;
  ErrorStatistics causal_ate_rmse;
  ErrorStatistics causal_jitter;
  ErrorStatistics tracked_ate_rmse;
  ErrorStatistics tracked_jitter;
  // The rest over finished runs.
  ErrorStatistics tracked_share;
  ErrorStatistics frames_lost;
  ErrorStatistics wall_s;
  ErrorStatistics fps;
  ErrorStatistics track_median_ms;
  ErrorStatistics track_p95_ms;
  std::optional<ErrorStatistics> frames_skipped;      // when every finished run reports it
  std::optional<ErrorStatistics> camera_to_done_s;    // likewise
  std::optional<ErrorStatistics> tracking_wait_s;     // likewise
  std::optional<ErrorStatistics> observer_median_ms;  // likewise (viewer entries)
  std::optional<ErrorStatistics> observer_p95_ms;
  std::size_t browser_connected = 0;  // finished runs whose browser connected
};

struct BenchmarkEntryResult {
  BenchmarkEntry entry;
  int runs_requested = 0;
  // The segmenter the runs use, resolved as `drvslam run` resolves it: "gt", "yolo", "masks",
  // "none"; `segmenter_used` is false when dynamic handling is off (the segmenter is not run).
  std::string segmenter;
  bool segmenter_used = false;
  bool dynamic_on = false;    // dynamic-object handling runs
  bool oracle = false;        // ground-truth masks feed the runs
  std::string model;          // yolo: the ONNX file the runs use
  std::string dynamic_setup;  // as the run describes it, e.g. "segmenter gt, dynamic on"
  std::string run_command;    // the equivalent `drvslam run` of run 1
  std::vector<BenchmarkRun> runs;
  BenchmarkAggregate aggregate;
};

struct MachineInfo {
  unsigned cores = 0;        // as nproc counts them (this process's CPU affinity)
  std::string cpu;           // /proc/cpuinfo model name
  std::string load_average;  // /proc/loadavg's 1, 5 and 15 minute averages at the start
  std::string date;          // UTC, at the start
  std::string working_directory;
};

struct BenchmarkReport {
  std::string command;
  MachineInfo machine;
  std::vector<BenchmarkEntryResult> entries;
  bool interrupted = false;
  std::size_t FailedRuns() const;
};

// Optional observers of a benchmark's progress.
struct BenchmarkProgress {
  std::function<void(const BenchmarkEntryResult&, int run)> run_started;
  std::function<void(std::size_t done, std::size_t total)> frame_done;
  std::function<void(const BenchmarkEntryResult&, const BenchmarkRun&)> run_finished;
};

inline constexpr double kBrowserConnectTimeoutS = 30.0;

BenchmarkAggregate AggregateRuns(const std::vector<BenchmarkRun>& runs);

MachineInfo DescribeMachine();

// Checks every entry and resolves its settings and segmenter before the first run (throws Error
// naming the entry then; a viewer entry also needs chromium, FindChromium). A viewer entry's
// run starts the live viewer on a free port and a headless Chromium on its page (its output in
// RUN_DIR/browser.log), waits up to kBrowserConnectTimeoutS for the page to connect before the
// first frame, and closes the browser when the run ends; a page that did not connect is
// recorded (BrowserConnection), not an error. A run that throws is recorded as failed, with its
// message, and the benchmark goes on; `stop` (may be null) ends it after the current frame, keeping
// what finished. Throws Error when the output folder or the tables cannot be written.
BenchmarkReport RunBenchmark(const BenchmarkOptions& options,
                             const BenchmarkProgress& progress = {},
                             const std::atomic<bool>* stop = nullptr);

}  // namespace drvslam
