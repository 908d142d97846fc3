// `drvslam segment --model ONNX IMAGE|VIDEO...`: instance segmentation of photos or videos with a
// YOLO-seg ONNX model; prints what it finds and optionally writes a JSON list of instances,
// overlay pictures and RGBA cut-outs of people (billboard actors for `drvslam synth`).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "command_registry.h"
#include "drvslam/core/settings_file.h"
#include "drvslam/core/thread_budget.h"
#include "drvslam/semantic/segment_job.h"
#include "drvslam/semantic/segmentation_options.h"
#include "drvslam/semantic/yolo_segmenter.h"

namespace {

struct SegmentArguments {
  std::string model;
  std::string config;
  double score = -1.0;
  int threads = 0;
  drvslam::SegmentJobOptions job;
};

std::string Describe(const drvslam::SegmentedImage& result) {
  std::string line = result.source;
  if (result.frame >= 0) line += " #" + std::to_string(result.frame);
  char text[160];
  std::snprintf(text, sizeof(text), ": %zu instance(s), %.1f ms",
                result.segmentation.instances.size(), result.segment_ms);
  line += text;
  for (const drvslam::Instance& instance : result.segmentation.instances) {
    std::snprintf(text, sizeof(text), "\n  %-14s %.2f  box %d,%d %dx%d",
                  instance.class_name.c_str(), instance.score, instance.box.x, instance.box.y,
                  instance.box.width, instance.box.height);
    line += text;
  }
  return line;
}

void RunSegment(SegmentArguments& args) {
  args.job.Check();
  drvslam::SegmentationOptions options;
  if (!args.config.empty()) {
    options = drvslam::LoadSegmentationOptions(drvslam::SettingsFile(args.config));
  }
  options.backend = drvslam::SegmenterBackend::kYolo;
  options.model = args.model;
  if (args.score >= 0.0) options.score_threshold = args.score;
  if (args.threads > 0) options.dnn_threads = args.threads;
  options.Check();
  // One thread segments here, so OpenCV keeps every core unless --threads says otherwise.
  drvslam::ApplyOpenCvThreadBudget(drvslam::ChooseOpenCvThreads(options.dnn_threads, true));

  drvslam::YoloSegmenter segmenter(options);
  std::cout << "model: " << args.model << " (input " << segmenter.InputSize().width << "x"
            << segmenter.InputSize().height << ", " << segmenter.NumClasses() << " classes, "
            << segmenter.Device() << ")\n";
  const drvslam::SegmentJobSummary summary = drvslam::RunSegmentJob(
      segmenter, args.job,
      [](const drvslam::SegmentedImage& result) { std::cout << Describe(result) << "\n"; });
  char text[200];
  std::snprintf(
      text, sizeof(text), "%zu image(s), %zu instance(s); segmentation ms median %.1f, p95 %.1f",
      summary.images, summary.instances, summary.segment_ms.median, summary.segment_ms.p95);
  std::cout << text << "\n";
  if (!args.job.json_path.empty()) std::cout << "wrote " << args.job.json_path << "\n";
  if (!args.job.overlay_dir.empty())
    std::cout << "wrote overlays to " << args.job.overlay_dir << "\n";
  if (!args.job.cutouts_dir.empty()) {
    std::cout << "wrote " << summary.cutouts << " cut-out(s) to " << args.job.cutouts_dir << "\n";
  }
}

const bool kSegmentCommandRegistered = drvslam::cli::RegisterCommand("segment", [](CLI::App& root) {
  auto args = std::make_shared<SegmentArguments>();
  CLI::App* cmd = root.add_subcommand(
      "segment", "instance segmentation of images or videos with a YOLOv8/YOLO11-seg ONNX model");
  cmd->add_option("INPUT", args->job.inputs, "image or video files")->required();
  cmd->add_option("--model", args->model, "YOLO segmentation model (ONNX)")->required();
  cmd->add_option("--json", args->job.json_path,
                  "write a JSON list of the instances (image, frame, class, score, box, "
                  "mask_area) to this file");
  cmd->add_option("--overlay", args->job.overlay_dir,
                  "write each image with its masks, boxes and labels drawn as a PNG here");
  cmd->add_option("--cutouts", args->job.cutouts_dir,
                  "write RGBA cut-outs (crop to the box, alpha = mask) of detected objects of "
                  "the --cutout-class classes here");
  // One value per use (comma-separated lists allowed), so it never swallows the inputs.
  cmd->add_option("--cutout-class", args->job.cutout_classes,
                  "classes to cut out (comma-separated, or repeat the option)")
      ->delimiter(',')
      ->allow_extra_args(false)
      ->capture_default_str();
  cmd->add_option("--every", args->job.every, "videos: segment every N-th frame")
      ->capture_default_str();
  cmd->add_option("--max-frames", args->job.max_frames,
                  "videos: segment at most this many frames each (0: all)")
      ->capture_default_str();
  cmd->add_option("--config", args->config,
                  "settings file whose Segmentation.* keys set thresholds and device");
  cmd->add_option("--score", args->score, "score threshold (default 0.25 or the settings')");
  cmd->add_option("--threads", args->threads, "OpenCV threads (default: OpenCV's choice)");
  cmd->callback([args] { RunSegment(*args); });
});

}  // namespace
