#include "drvslam/tools/runner/demo_runner.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "drvslam/core/error.h"
#include "drvslam/semantic/yolo_segmenter.h"
#include "drvslam/tools/eval/ate.h"
#include "drvslam/tools/eval/eval_report.h"
#include "drvslam/tools/eval/rpe.h"
#include "drvslam/tools/eval/trajectory_plot.h"
#include "drvslam/tools/runner/cutout_sequence.h"
#include "drvslam/tools/runner/sequence_runner.h"
#include "drvslam/tools/synth/synth_generator.h"
#include "drvslam/tools/viewer/run_report.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

std::string Format(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, value);
  return buffer;
}

// How one run is segmented: the choice given to RunSequence and its name in the report.
struct SegmenterChoice {
  DynamicRunChoice choice;
  std::string label;
};

SegmenterChoice Choose(const std::string& segmenter, const std::string& dynamic,
                       const std::string& label, const std::string& model = "") {
  SegmenterChoice chosen;
  chosen.choice.segmenter = segmenter;
  chosen.choice.model = model;
  chosen.choice.dynamic = dynamic;
  chosen.label = label;
  return chosen;
}

SegmenterChoice OracleMasks() { return Choose("gt", "on", kOracleSegmenter); }

SegmenterChoice DynamicOff() { return Choose("none", "off", kNoSegmenter); }

SegmenterChoice Network(const std::string& model) {
  return Choose("yolo", "on", "yolo (" + fs::path(model).filename().string() + ")", model);
}

// Runs SLAM on a synthesized sequence into `folder` and evaluates it.
DemoResult RunAndEvaluate(const fs::path& sequence, const fs::path& folder, const std::string& name,
                          const SegmenterChoice& segmenter,
                          const std::function<void(const std::string&)>& status) {
  if (status) status("running SLAM: " + name + " (segmenter: " + segmenter.label + ")");
  RunOptions run_options;
  run_options.dataset = sequence.string();
  run_options.out_dir = folder.string();
  run_options.dynamic = segmenter.choice;
  const RunSummary run = RunSequence(run_options);

  DemoResult result;
  result.run = name;
  result.segmenter = segmenter.label;
  result.frames = run.stats.frames;
  result.tracked = run.stats.tracked;
  result.keyframes = run.stats.keyframes;
  result.map_points = run.stats.map_points;
  const auto total = run.stats.stages.find("total");
  if (total != run.stats.stages.end()) {
    result.median_ms = total->second.median_ms;
    result.p95_ms = total->second.p95_ms;
  }
  const Trajectory gt = ReadTumTrajectory((sequence / "groundtruth.txt").string());
  const Trajectory est = ReadTumTrajectory(run.camera_trajectory_path, /*allow_empty=*/true);
  if (est.size() >= 3) {
    AteOptions ate_options;
    ate_options.sequence_frames = run.sequence_frames;
    const AteResult ate = ComputeAte(gt, est, ate_options);
    const std::optional<RpeResult> rpe = ComputeRpeIfLongEnough(gt, est, RpeOptions{});
    result.ate_rmse = ate.errors.rmse;
    if (rpe) result.rpe_trans_rmse = rpe->trans_rmse;
    if (rpe) result.rpe_rot_rmse_deg = rpe->rot_rmse_deg;
    WriteEvalReportJson((folder / "eval.json").string(), ate, rpe);
    result.plot_path = (folder / "trajectory.png").string();
    WriteTrajectoryPlot(result.plot_path, gt, est, ate);
  } else {
    result.ate_rmse = -1.0;  // too few tracked frames to evaluate
  }
  RunDataOptions report_options;
  report_options.dense_budget = kReportDenseBudget;
  report_options.ground_truth = (sequence / "groundtruth.txt").string();
  result.html_report_path = (folder / "report.html").string();
  result.html_report_bytes =
      WriteRunReport(folder.string(), result.html_report_path, report_options);
  if (status) {
    status(name + ": tracked " + std::to_string(result.tracked) + "/" +
           std::to_string(result.frames) + ", ATE RMSE " +
           (result.ate_rmse >= 0 ? Format("%.2f cm", 100 * result.ate_rmse) : "n/a"));
  }
  return result;
}

// Synthesizes the scenario and runs it (and, with actors and options.baseline, its baseline).
std::vector<DemoResult> RunScenario(const DemoOptions& options, const std::string& scenario,
                                    const std::function<void(const std::string&)>& status) {
  const fs::path folder = fs::path(options.out_dir) / scenario;
  const fs::path sequence = folder / "sequence";
  synth::SynthOptions synth_options;
  synth_options.scenario = scenario;
  synth_options.frames = options.frames;
  synth_options.seed = options.seed;
  if (status)
    status("synthesizing " + scenario + " (" + std::to_string(options.frames) + " frames)");
  const synth::SynthSummary synth_summary =
      synth::GenerateSequence(synth_options, sequence.string());

  std::vector<DemoResult> results;
  results.push_back(RunAndEvaluate(sequence, folder, scenario, OracleMasks(), status));
  if (options.baseline && synth_summary.actors > 0) {
    results.push_back(RunAndEvaluate(sequence, folder / "dynamic_off", scenario + ", dynamic off",
                                     DynamicOff(), status));
  }
  for (DemoResult& result : results) {
    result.scenario = scenario;
    result.synth_fps = synth_summary.render_fps;
  }
  return results;
}

bool IsWalking(const std::string& scenario) { return scenario.rfind("walking_", 0) == 0; }

// The walking scenario again, its actors cut out of photographs by the network, run with the
// network (and, with options.baseline, with dynamic handling off).
std::vector<DemoResult> RunCutoutScenario(const DemoOptions& options, Segmenter& cutter,
                                          const std::string& scenario,
                                          const std::function<void(const std::string&)>& status) {
  const fs::path folder = fs::path(options.out_dir) / (scenario + "_cutouts");
  CutoutSequenceOptions cutout_options;
  cutout_options.synth.scenario = scenario;
  cutout_options.synth.frames = options.frames;
  cutout_options.synth.seed = options.seed;
  if (status) {
    status("synthesizing " + scenario + " with actors cut out of photographs by the network (" +
           std::to_string(options.frames) + " frames)");
  }
  const CutoutSequence made = MakeCutoutSequence(cutter, cutout_options, folder.string());
  const std::string name = scenario + ", cut-out actors";
  std::vector<DemoResult> results;
  results.push_back(
      RunAndEvaluate(made.sequence_dir, folder, name, Network(options.model), status));
  if (options.baseline) {
    results.push_back(RunAndEvaluate(made.sequence_dir, folder / "dynamic_off",
                                     name + ", dynamic off", DynamicOff(), status));
  }
  for (DemoResult& result : results) {
    result.scenario = scenario;
    result.synth_fps = made.synth.render_fps;
  }
  return results;
}

// Loads the model (the cut-outs' segmenter) and checks the photographs, so a bad path fails
// before anything runs. nullptr without a model.
std::unique_ptr<YoloSegmenter> OpenCutoutSegmenter(const DemoOptions& options) {
  if (options.model.empty()) return nullptr;
  std::error_code error;
  if (!fs::is_regular_file(options.model, error)) {
    throw Error("--model " + options.model + ": model file not found");
  }
  CutoutPhotoPaths(CutoutSequenceOptions{});
  SegmentationOptions segmentation;
  segmentation.backend = SegmenterBackend::kYolo;
  segmentation.model = options.model;
  segmentation.Check();
  return std::make_unique<YoloSegmenter>(segmentation);
}

// The command that adds the network rows, for a report made without a model.
std::string NetworkRowsHowTo() {
  return "No row here is segmented by a network. `drvslam demo --model MODEL.onnx` adds them: "
         "people are cut out of the opencv-doc photographs by the model (`drvslam segment "
         "--cutouts`), drawn as the actors of walking_xyz (`drvslam synth --billboards`), and "
         "that sequence is run with `--segmenter yolo` and with `--dynamic off`. In this "
         "project:\n\n"
         "    build/bin/drvslam demo --model ../shared/models/yolov8n-seg-320x256.onnx\n\n"
         "(the model is in `../shared/models`); any YOLOv8/YOLO11-seg ONNX export works too, "
         "e.g. Ultralytics' `yolo export model=yolov8n-seg.pt format=onnx`.\n\n";
}

// The sentences under the table that say what each kind of segmenter row shows.
std::string SegmenterNotes(const std::vector<DemoResult>& results) {
  bool oracle = false;
  bool network = false;
  for (const DemoResult& r : results) {
    oracle = oracle || r.segmenter == kOracleSegmenter;
    network = network || r.segmenter.rfind("yolo", 0) == 0;
  }
  std::string text;
  if (oracle) {
    text += std::string("**Oracle rows.** Rows whose segmenter is \"") + kOracleSegmenter +
            "\" are segmented with the synthetic sequence's exact instance masks, not by a "
            "network: they show the upper bound of the pipeline, not what a camera gets.\n\n";
  }
  if (network) {
    text +=
        "Rows segmented by `yolo` run the real pipeline: the network segments every frame "
        "of a sequence whose actors are people cut out of real photographs by the same "
        "network.\n\n";
  } else {
    text += NetworkRowsHowTo();
  }
  return text;
}

}  // namespace

std::vector<DemoResult> RunDemo(const DemoOptions& options,
                                const std::function<void(const std::string&)>& status) {
  if (options.frames < 10) throw Error("demo: --frames must be at least 10");
  const std::unique_ptr<YoloSegmenter> cutter = OpenCutoutSegmenter(options);
  std::error_code error;
  fs::create_directories(options.out_dir, error);
  if (error) throw Error(options.out_dir + ": cannot create output folder");
  std::vector<DemoResult> results;
  for (const std::string& scenario : options.scenarios) {
    for (DemoResult& result : RunScenario(options, scenario, status)) {
      results.push_back(std::move(result));
    }
  }
  for (const std::string& scenario : options.scenarios) {
    if (!cutter || !IsWalking(scenario)) continue;
    for (DemoResult& result : RunCutoutScenario(options, *cutter, scenario, status)) {
      results.push_back(std::move(result));
    }
  }
  for (DemoResult& result : results) {
    if (!result.plot_path.empty()) {
      result.plot_in_report = fs::relative(result.plot_path, options.out_dir).generic_string();
    }
    result.html_report_in_index =
        fs::relative(result.html_report_path, options.out_dir).generic_string();
  }
  const std::string report_path = (fs::path(options.out_dir) / "report.md").string();
  std::ofstream report(report_path);
  if (!report) throw Error(report_path + ": cannot open for writing");
  report << FormatDemoReport(results);
  const std::string index_path = (fs::path(options.out_dir) / "index.html").string();
  std::ofstream index(index_path);
  if (!index) throw Error(index_path + ": cannot open for writing");
  index << FormatDemoIndexHtml(results);
  if (!index) throw Error(index_path + ": write failed");
  return results;
}

std::string FormatDemoReport(const std::vector<DemoResult>& results) {
  std::string text =
      "# drvslam demo\n\n"
      "Synthetic sequences with exact ground truth (`drvslam synth`), processed by `drvslam run`\n"
      "and evaluated the TUM benchmark's way (ATE after rigid alignment, RPE over 1 s). Runs\n"
      "marked \"dynamic off\" track the same sequence without dynamic-object handling: plain\n"
      "ORB-SLAM2 behaviour, the baseline.\n\n"
      "| run | segmenter | tracked | keyframes | map points | ATE RMSE | RPE trans | RPE rot | "
      "median ms/frame | p95 ms/frame |\n"
      "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const DemoResult& r : results) {
    text += "| " + r.run + " | " + r.segmenter + " | " + std::to_string(r.tracked) + "/" +
            std::to_string(r.frames) + " | " + std::to_string(r.keyframes) + " | " +
            std::to_string(r.map_points) + " | " +
            (r.ate_rmse >= 0 ? Format("%.2f cm", 100 * r.ate_rmse) : "n/a") + " | " +
            (r.rpe_trans_rmse ? Format("%.2f cm", 100 * *r.rpe_trans_rmse) : "n/a") + " | " +
            (r.rpe_rot_rmse_deg ? Format("%.3f deg", *r.rpe_rot_rmse_deg) : "n/a") + " | " +
            Format("%.1f", r.median_ms) + " | " + Format("%.1f", r.p95_ms) + " |\n";
  }
  text += "\n";
  text += SegmenterNotes(results);
  for (const DemoResult& r : results) {
    if (r.plot_in_report.empty()) continue;
    text += "## " + r.run + "\n\n![" + r.run + "](" + r.plot_in_report + ")\n\n";
  }
  text +=
      "Each run also has a self-contained `report.html` (3-D map, trajectory, error over time,\n"
      "stats; opens offline), linked from `index.html`.\n";
  return text;
}

namespace {

std::string EscapeHtml(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace

std::string FormatDemoIndexHtml(const std::vector<DemoResult>& results) {
  std::string html =
      "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<title>drvslam demo</title>\n<style>body{font:14px sans-serif;margin:24px}"
      "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:4px 8px;"
      "text-align:right}td:first-child,th:first-child{text-align:left}</style>\n</head>\n"
      "<body>\n<h1>drvslam demo</h1>\n<p>Synthetic sequences with exact ground truth; runs on "
      "ground-truth masks are an ORACLE (the upper bound of the pipeline). Each report is one "
      "file that opens offline.</p>\n<table>\n<tr><th>run</th><th>segmenter</th><th>tracked</th>"
      "<th>ATE RMSE</th><th>report</th><th>size</th></tr>\n";
  for (const DemoResult& r : results) {
    html += "<tr><td>" + EscapeHtml(r.run) + "</td><td>" + EscapeHtml(r.segmenter) + "</td><td>" +
            std::to_string(r.tracked) + "/" + std::to_string(r.frames) + "</td><td>" +
            (r.ate_rmse >= 0 ? Format("%.2f cm", 100 * r.ate_rmse) : "n/a") +
            "</td><td><a href=\"" + EscapeHtml(r.html_report_in_index) +
            "\">report.html</a></td><td>" +
            Format("%.2f MB", r.html_report_bytes / (1024.0 * 1024.0)) + "</td></tr>\n";
  }
  html += "</table>\n</body>\n</html>\n";
  return html;
}

}  // namespace drvslam
