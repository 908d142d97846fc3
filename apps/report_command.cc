// drvslam report: one self-contained report.html for a finished run.
#include <cstdio>
#include <filesystem>
#include <string>

#include "command_registry.h"
#include "drvslam/tools/viewer/run_report.h"

namespace drvslam::cli {
namespace {

struct ReportOptions {
  std::string run_dir;
  std::string out;  // empty: RUN_DIR/report.html
  RunDataOptions data;
};

const bool kReportCommandRegistered = RegisterCommand("report", [](CLI::App& root) {
  auto options = std::make_shared<ReportOptions>();
  options->data.dense_budget = kReportDenseBudget;
  CLI::App* command = root.add_subcommand(
      "report", "write one self-contained report.html (plots, 3-D map, stats) for a finished run");
  command->add_option("RUN_DIR", options->run_dir, "output folder of drvslam run")->required();
  command->add_option("--out", options->out, "the HTML file (default: RUN_DIR/report.html)");
  command->add_option("--ground-truth", options->data.ground_truth,
                      "TUM ground truth to plot and score against (default: the run's "
                      "DATASET/groundtruth.txt when stats.json names it)");
  command
      ->add_option("--dense-budget", options->data.dense_budget,
                   "dense points inlined at most; a larger map is decimated")
      ->capture_default_str();
  command->callback([options] {
    const std::string out = options->out.empty()
                                ? (std::filesystem::path(options->run_dir) / "report.html").string()
                                : options->out;
    const std::size_t bytes = WriteRunReport(options->run_dir, out, options->data);
    std::printf("wrote %s (%.2f MB)\n", out.c_str(), bytes / (1024.0 * 1024.0));
  });
});

}  // namespace
}  // namespace drvslam::cli
