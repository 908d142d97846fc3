// `drvslam dense-eval --dataset SYNTH_DIR`: the dense map's acceptance measures on a synthetic
// sequence - ghosts in the space actors swept through, distance to the true surfaces, key-object
// density - for the dense map of a run (--map, aligned with --trajectory) or for one built with
// ground-truth poses and masks.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "command_registry.h"
#include "drvslam/core/error.h"
#include "drvslam/dense/dense_stats_json.h"
#include "drvslam/tools/truth/dense_evaluation.h"
#include "drvslam/tools/truth/dense_truth_json.h"
#include "progress_bar.h"

namespace drvslam::cli {
namespace {

struct DenseEvalArguments {
  DenseEvaluationOptions options;
  std::string json_path;
};

void RunDenseEval(const DenseEvalArguments& args) {
  ProgressBar bar("mapping");
  const DenseEvaluation evaluation = EvaluateDenseMap(
      args.options, [&bar](std::size_t done, std::size_t total) { bar.Update(done, total); });
  const DenseEvaluationOptions& o = args.options;
  std::printf("map:                 %s\n",
              o.map.empty() ? "built with ground-truth poses and masks" : o.map.c_str());
  if (!o.trajectory.empty()) std::printf("aligned with:        %s\n", o.trajectory.c_str());
  if (evaluation.stats) {
    const DenseMapStats& s = *evaluation.stats;
    std::printf("keyframes:           %zu (+%zu enhancement frames)\n", s.keyframes,
                s.enhancement_frames);
    std::printf("full resolution:     %zu points\n", s.full_resolution_points);
    std::printf("per keyframe:        median %.2f ms, p95 %.2f ms\n", s.keyframe_ms.median_ms,
                s.keyframe_ms.p95_ms);
  }
  std::printf("swept space:         %zu actor triangles over %d frames\n",
              evaluation.actor_triangles, evaluation.frames);
  std::printf("%s", FormatDenseTruthScores(evaluation.scores).c_str());
  if (evaluation.octomap_scores) {
    const DenseTruthScores& o = *evaluation.octomap_scores;
    std::printf("octomap:             %zu occupied %.3f m cells, %zu in swept space (%s)\n",
                o.points, evaluation.octomap_resolution, o.ghosts,
                o.ghost_share ? (std::to_string(100.0 * *o.ghost_share) + "%").c_str() : "n/a");
    if (o.mean_distance && o.p95_distance) {
      std::printf("  cell centres:      mean %.4f m, p95 %.4f m from the static surfaces\n",
                  *o.mean_distance, *o.p95_distance);
    } else {
      std::printf("  cell centres:      n/a (no occupied cell off the swept space)\n");
    }
  }
  if (!args.json_path.empty()) {
    nlohmann::json json;
    json["truth"] = DenseTruthScoresJson(evaluation.scores);
    if (evaluation.stats) json["dense"] = DenseStatsJson(*evaluation.stats);
    if (evaluation.octomap_scores) {
      json["octomap"] = DenseTruthScoresJson(*evaluation.octomap_scores);
      json["octomap"]["resolution"] = evaluation.octomap_resolution;
    }
    json["frames"] = evaluation.frames;
    json["map"] = o.map;
    json["trajectory"] = o.trajectory;
    std::ofstream out(args.json_path);
    if (!out) throw Error(args.json_path + ": cannot open for writing");
    out << json.dump(2) << "\n";
    if (!out) throw Error(args.json_path + ": write failed");
    std::printf("wrote %s\n", args.json_path.c_str());
  }
}

const bool kDenseEvalCommandRegistered = RegisterCommand("dense-eval", [](CLI::App& root) {
  auto args = std::make_shared<DenseEvalArguments>();
  DenseEvaluationOptions& o = args->options;
  CLI::App* cmd = root.add_subcommand(
      "dense-eval",
      "score a dense map against a synthetic sequence's true geometry: ghosts where actors "
      "walked, distance to the true surfaces, key-object density");
  cmd->add_option("--dataset", o.dataset, "a `drvslam synth` sequence folder")->required();
  cmd->add_option("--map", o.map,
                  "dense_map.ply of a run (default: build one with ground-truth poses and masks)");
  cmd->add_option("--trajectory", o.trajectory,
                  "the run's CameraTrajectory.txt, to align --map with the ground truth");
  cmd->add_option("--removal", o.removal,
                  "on|off: dynamic-object removal when building with ground truth (default: "
                  "DenseMap.removeDynamic)")
      ->check(CLI::IsMember({"on", "off"}));
  cmd->add_option("--keyframe-every", o.keyframe_every,
                  "ground-truth mapping: every n-th frame is a keyframe")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--max-frames", o.max_frames, "use the first N frames (0 = all)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--out", o.out_dir, "ground-truth mapping: write dense_map.ply/.pcd there");
  cmd->add_option("--ghost-margin", o.truth.ghost_margin,
                  "metres from an actor's surface that count as swept space")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--actor-stride", o.truth.actor_frame_stride,
                  "take actor geometry at every n-th frame")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--billboards", o.billboards,
                  "the actors' cut-out folder (Synth.Billboards) when the settings' relative path "
                  "does not resolve");
  cmd->add_option("--octomap", o.octomap,
                  "the run's dense_map.bt: score its occupied cells as well (aligned with "
                  "--trajectory)");
  cmd->add_option("--ghosts", o.ghosts_csv,
                  "write every ghost point and octomap cell in swept space as CSV (position in "
                  "the ground-truth frame, label, distance to the static scene, first frame an "
                  "actor was there)");
  cmd->add_option("--json", args->json_path, "write the numbers as JSON");
  cmd->callback([args] { RunDenseEval(*args); });
});

}  // namespace
}  // namespace drvslam::cli
