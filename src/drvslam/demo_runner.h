// RunDemo: the embedded default job a new user runs first, with no download. It synthesizes a
// static and a dynamic version of the same camera path, runs SLAM on both, evaluates them
// against the exact ground truth and writes a report (report.md with plots).
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace drvslam {

struct DemoOptions {
  std::string out_dir = "demo_out";
  int frames = 240;
  unsigned seed = 1;
  // Scenarios to run, each synthesized into OUT/<scenario>/sequence.
  std::vector<std::string> scenarios = {"static_xyz", "walking_xyz"};
};

struct DemoResult {
  std::string scenario;
  std::size_t frames = 0;
  std::size_t tracked = 0;
  std::size_t keyframes = 0;
  std::size_t map_points = 0;
  double ate_rmse = 0.0;        // m
  double rpe_trans_rmse = 0.0;  // m per delta
  double rpe_rot_rmse_deg = 0.0;
  double median_ms = 0.0;  // per frame, whole TrackRGBD
  double p95_ms = 0.0;
  double synth_fps = 0.0;
  std::string plot_path;
};

// status(line) receives progress lines. Throws Error on failure.
std::vector<DemoResult> RunDemo(const DemoOptions& options,
                                const std::function<void(const std::string&)>& status = nullptr);

// The report as Markdown (what RunDemo writes to OUT/report.md).
std::string FormatDemoReport(const std::vector<DemoResult>& results);

}  // namespace drvslam
