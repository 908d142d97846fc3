// `drvslam eval GT EST`: ATE and RPE of an estimated trajectory against ground truth, computed as
// the TUM RGB-D benchmark scripts do; prints a table and optionally writes JSON and a plot.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "command_registry.h"
#include "drvslam/io/trajectory_formats.h"
#include "drvslam/io/trajectory_io.h"
#include "drvslam/io/tum_dataset.h"
#include "drvslam/tools/eval/ate.h"
#include "drvslam/tools/eval/eval_report.h"
#include "drvslam/tools/eval/rpe.h"
#include "drvslam/tools/eval/trajectory_plot.h"

namespace {

struct EvalArguments {
  std::string ground_truth;
  std::string estimate;
  drvslam::AteOptions ate;
  double rpe_delta = 1.0;
  std::string json_path;
  std::string plot_path;
  std::string dataset;  // sequence folder whose frames coverage counts against
  // tum|kitti|euroc, or empty: detected from the file's content (--format sets both).
  std::string format;
  std::string gt_format;
  std::string est_format;
  // KITTI times files (default: <stem>_times.txt or times.txt beside the poses).
  std::string gt_times;
  std::string est_times;
  bool no_align = false;
  std::string alignment_from;  // an eval --json file whose alignment is used
};

// How one file is read: its format (given, else detected) and KITTI times file.
struct TrajectoryInput {
  drvslam::TrajectoryReadOptions read;
  std::string label;  // "tum", "kitti (times: FILE)", ...
};

TrajectoryInput ResolveInput(const std::string& path, const std::string& format,
                             const std::string& option, const std::string& times) {
  TrajectoryInput input;
  input.read.format = format.empty() ? drvslam::DetectTrajectoryFormat(path)
                                     : drvslam::ParseTrajectoryFormat(format, option);
  input.read.kitti_times = times;
  input.label = drvslam::ToString(*input.read.format);
  if (!format.empty()) input.label += ", as " + option + " says";
  return input;
}

// The frames `drvslam run` processes in the sequence: colour images paired with depth.
std::size_t SequenceFrames(const std::string& dataset) {
  return drvslam::TumDataset(dataset).Size();
}

void RunEval(EvalArguments args) {
  // Check every option before reading files, so a typo is reported at once.
  args.ate.Check();
  if (!args.dataset.empty()) args.ate.sequence_frames = SequenceFrames(args.dataset);
  if (args.no_align) args.ate.fixed_alignment = drvslam::Alignment();
  if (!args.alignment_from.empty()) {
    args.ate.fixed_alignment = drvslam::ReadEvalAlignment(args.alignment_from);
  }
  drvslam::RpeOptions rpe_options;
  rpe_options.delta = args.rpe_delta;
  rpe_options.offset = args.ate.offset;
  rpe_options.Check();

  const std::string gt_format = args.gt_format.empty() ? args.format : args.gt_format;
  const std::string est_format = args.est_format.empty() ? args.format : args.est_format;
  const std::string gt_option = args.gt_format.empty() ? "--format" : "--gt-format";
  const std::string est_option = args.est_format.empty() ? "--format" : "--est-format";
  const TrajectoryInput gt_input =
      ResolveInput(args.ground_truth, gt_format, gt_option, args.gt_times);
  const TrajectoryInput est_input =
      ResolveInput(args.estimate, est_format, est_option, args.est_times);
  const drvslam::Trajectory gt = drvslam::ReadTrajectory(args.ground_truth, gt_input.read);
  const drvslam::Trajectory est = drvslam::ReadTrajectory(args.estimate, est_input.read);
  const drvslam::AteResult ate = drvslam::ComputeAte(gt, est, args.ate);
  // With --scale the estimate's relative motions are compared at the scale ATE found.
  rpe_options.scale = ate.alignment.scale;
  // An estimate shorter than --rpe-delta has no RPE (n/a), but still its ATE.
  const std::optional<drvslam::RpeResult> rpe =
      drvslam::ComputeRpeIfLongEnough(gt, est, rpe_options);

  std::cout << "ground truth: " << args.ground_truth << " (" << gt.size() << " poses, "
            << gt_input.label << ")\n"
            << "estimate:     " << args.estimate << " (" << est.size() << " poses, "
            << est_input.label << ")\n"
            << drvslam::FormatEvalTable(ate, rpe);
  if (!args.json_path.empty()) {
    drvslam::WriteEvalReportJson(args.json_path, ate, rpe);
    std::cout << "wrote " << args.json_path << "\n";
  }
  if (!args.plot_path.empty()) {
    drvslam::WriteTrajectoryPlot(args.plot_path, gt, est, ate);
    std::cout << "wrote " << args.plot_path << "\n";
  }
}

const bool kEvalCommandRegistered = drvslam::cli::RegisterCommand("eval", [](CLI::App& root) {
  auto args = std::make_shared<EvalArguments>();
  CLI::App* cmd = root.add_subcommand(
      "eval",
      "ATE and RPE of an estimated trajectory against ground truth, the TUM RGB-D benchmark's "
      "way (evaluate_ate.py, evaluate_rpe.py --fixed_delta)");
  cmd->add_option("GT", args->ground_truth, "ground-truth trajectory (tum, kitti or euroc)")
      ->required();
  cmd->add_option("EST", args->estimate, "estimated trajectory (tum, kitti or euroc)")->required();
  const auto formats = CLI::IsMember({"tum", "kitti", "euroc"});
  cmd->add_option("--format", args->format,
                  "tum|kitti|euroc: format of both files (default: detected from each file's "
                  "content)")
      ->check(formats);
  cmd->add_option("--gt-format", args->gt_format, "format of GT only (overrides --format)")
      ->check(formats);
  cmd->add_option("--est-format", args->est_format, "format of EST only (overrides --format)")
      ->check(formats);
  cmd->add_option("--gt-times", args->gt_times,
                  "KITTI times file of GT (default: <stem>_times.txt or times.txt beside it; "
                  "without one the poses are stamped 0, 1, 2, ...)");
  cmd->add_option("--est-times", args->est_times, "KITTI times file of EST (as --gt-times)");
  cmd->add_option("--max-diff", args->ate.max_difference,
                  "largest time difference (s) for two stamps to associate")
      ->capture_default_str();
  cmd->add_option("--offset", args->ate.offset, "time offset (s) added to the estimate's stamps")
      ->capture_default_str();
  cmd->add_flag("--scale", args->ate.with_scale,
                "similarity alignment: also estimate a scale (for monocular systems; RGB-D "
                "evaluation is rigid)");
  cmd->add_option("--rpe-delta", args->rpe_delta, "time (s) between the poses RPE compares")
      ->capture_default_str();
  auto* frames =
      cmd->add_option("--frames", args->ate.sequence_frames,
                      "frames of the sequence: coverage is matched poses over them (default: "
                      "over the ground-truth poses)")
          ->check(CLI::PositiveNumber);
  cmd->add_option("--dataset", args->dataset,
                  "sequence folder (TUM layout): its frame count, as --frames")
      ->excludes(frames);
  auto* no_align = cmd->add_flag(
      "--no-align", args->no_align,
      "fit no alignment: the estimate is compared in its own frame (it must already be in the "
      "ground truth's)");
  cmd->add_option("--alignment-from", args->alignment_from,
                  "fit no alignment; use the one in this --json file of an earlier eval (e.g. "
                  "of the run whose map this run localized in)")
      ->excludes(no_align)
      ->excludes("--scale");
  cmd->add_option("--json", args->json_path, "write the results as JSON to this file");
  cmd->add_option("--plot", args->plot_path,
                  "write a PNG: top view of ground truth and aligned estimate, ATE over time");
  cmd->callback([args] { RunEval(*args); });
});

}  // namespace
