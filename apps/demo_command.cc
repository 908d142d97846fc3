// drvslam demo: the embedded default (synthesize, run, evaluate, report), no download needed;
// --model adds rows segmented by the network.
#include <cstdio>

#include "command_registry.h"
#include "drvslam/tools/runner/demo_runner.h"

namespace drvslam::cli {
namespace {

const bool kDemoCommandRegistered = RegisterCommand("demo", [](CLI::App& root) {
  auto options = std::make_shared<DemoOptions>();
  CLI::App* command = root.add_subcommand(
      "demo", "synthesize static and dynamic sequences, run SLAM, evaluate, write a report");
  command->add_option("--out", options->out_dir, "output folder")->capture_default_str();
  command->add_option("--frames", options->frames, "frames per sequence")
      ->capture_default_str()
      ->check(CLI::Range(10, 100000));
  command->add_option("--seed", options->seed, "synthetic scene seed")->capture_default_str();
  command->add_option("--scenarios", options->scenarios, "synthetic scenarios to run")
      ->capture_default_str();
  command->add_option("--model", options->model,
                      "YOLOv8/YOLO11-seg ONNX model: also run the walking scenarios with actors "
                      "cut out of the opencv-doc photographs, segmented by this network (e.g. "
                      "../shared/models/yolov8n-seg-320x256.onnx)");
  command->callback([options] {
    const auto results =
        RunDemo(*options, [](const std::string& line) { std::printf("%s\n", line.c_str()); });
    std::printf("\n%s", FormatDemoReport(results).c_str());
    std::printf("report: %s/report.md\n", options->out_dir.c_str());
    std::printf("html:   %s/index.html (one self-contained report.html per run:",
                options->out_dir.c_str());
    for (const DemoResult& result : results) {
      std::printf(" %.2f MB", result.html_report_bytes / (1024.0 * 1024.0));
    }
    std::printf(")\n");
  });
});

}  // namespace
}  // namespace drvslam::cli
