// RunDemo: the embedded default job a new user runs first, with no download. It synthesizes a
// static and a dynamic version of the same camera path, runs SLAM on both (the dynamic one also
// with dynamic handling off: the plain ORB-SLAM2 baseline it improves on), evaluates every run
// against the exact ground truth and writes a report (report.md with plots, and index.html
// linking each run's self-contained report.html, the viewer page with the run inlined). Those
// runs use the
// sequences' ground-truth masks (an oracle); with a YOLO-seg model the walking scenarios are
// also synthesized with actors cut out of real photographs and run with the network.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace drvslam {

struct DemoOptions {
  std::string out_dir = "demo_out";
  int frames = 240;
  unsigned seed = 1;
  // Scenarios to run, each synthesized into OUT/<scenario>/sequence.
  std::vector<std::string> scenarios = {"static_xyz", "walking_xyz"};
  // Also run each scenario that has moving actors with --dynamic off, for comparison.
  bool baseline = true;
  // YOLO-seg ONNX model (--model); empty: no network-segmented rows. With it, every walking_*
  // scenario is also synthesized with cut-out actors (OUT/<scenario>_cutouts) and run with
  // --segmenter yolo (and, with baseline, --dynamic off).
  std::string model;
};

// What DemoResult::segmenter says for runs on ground-truth masks and for baselines.
inline constexpr char kOracleSegmenter[] = "ground-truth masks (oracle)";
inline constexpr char kNoSegmenter[] = "none (dynamic off)";

struct DemoResult {
  std::string scenario;
  std::string run;  // the run's name: the scenario, or "<scenario>, dynamic off"
  // Where the masks came from: kOracleSegmenter, kNoSegmenter or "yolo (<model file>)".
  std::string segmenter;
  std::size_t frames = 0;
  std::size_t tracked = 0;
  std::size_t keyframes = 0;
  std::size_t map_points = 0;
  double ate_rmse = 0.0;  // m
  // Undefined (n/a) when the run is too short for a pose pair 1 s apart.
  std::optional<double> rpe_trans_rmse;  // m per delta
  std::optional<double> rpe_rot_rmse_deg;
  double median_ms = 0.0;  // per frame, whole TrackRGBD
  double p95_ms = 0.0;
  double synth_fps = 0.0;
  std::string plot_path;
  std::string plot_in_report;  // plot_path relative to the report's folder
  // The run's self-contained HTML report (drvslam report), its size, and its path relative to
  // the demo's folder (where index.html links it).
  std::string html_report_path;
  std::size_t html_report_bytes = 0;
  std::string html_report_in_index;
};

// status(line) receives progress lines. Throws Error on failure; a bad model or a missing
// photograph for the cut-outs before anything runs, naming the file.
std::vector<DemoResult> RunDemo(const DemoOptions& options,
                                const std::function<void(const std::string&)>& status = nullptr);

// The report as Markdown (what RunDemo writes to OUT/report.md).
std::string FormatDemoReport(const std::vector<DemoResult>& results);

// OUT/index.html: the results table with a link to each run's report.html.
std::string FormatDemoIndexHtml(const std::vector<DemoResult>& results);

}  // namespace drvslam
