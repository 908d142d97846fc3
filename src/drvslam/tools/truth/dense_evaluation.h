// EvaluateDenseMap: what `drvslam dense-eval` runs. On a `drvslam synth` sequence it scores
// either the dense map of a SLAM run (aligned into the ground-truth frame through the run's
// estimated trajectory) or a dense map built here with ground-truth poses, masks and moving
// flags, against the scene's true geometry (ghosts, distance to the true surfaces, key-object
// density; see dense_truth.h). Ghosts come from the actors' true surfaces at every frame, so a
// run made with any segmenter (YOLO, masks, ground truth) is scored the same way.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "drvslam/dense/dense_mapper.h"
#include "drvslam/tools/truth/dense_truth.h"

namespace drvslam {

struct DenseEvaluationOptions {
  std::string dataset;     // a `drvslam synth` folder
  std::string map;         // dense_map.ply of a run; empty: build one with ground truth
  std::string trajectory;  // the run's CameraTrajectory.txt; empty: `map` is in the GT frame
  // Ground-truth mapping: "on"/"off" overrides DenseMap.removeDynamic of the settings.
  std::string removal;
  int keyframe_every = 10;
  std::size_t max_frames = 0;  // 0 = all (ground-truth mapping; actors of these frames count)
  std::string out_dir;         // ground-truth mapping: writes dense_map.ply/.pcd there
  // The real-photo cut-outs of the actors (Synth.Billboards) when the settings' path does not
  // resolve; empty: the settings' path, from the working folder, the dataset or its parents.
  std::string billboards;
  // A run's dense_map.bt: its occupied leaves (centres at the tree's resolution) are scored
  // like map points, aligned with `trajectory` as the map is.
  std::string octomap;
  // Writes every ghost (and octomap cell in swept space) as CSV here: where it lies, how far
  // from the static scene, and the first frame an actor came within the ghost margin.
  std::string ghosts_csv;
  DenseTruthOptions truth;
};

struct DenseEvaluation {
  DenseTruthScores scores;
  std::optional<DenseMapStats> stats;              // ground-truth mapping only
  std::optional<DenseTruthScores> octomap_scores;  // with options.octomap
  double octomap_resolution = 0.0;
  int frames = 0;  // frames whose actors count as swept space
  std::size_t actor_triangles = 0;
  double seconds = 0.0;  // evaluation time (scene rebuild and scoring)
};

// Throws Error naming the file or option at fault; progress(done, total) follows the frames of
// ground-truth mapping.
DenseEvaluation EvaluateDenseMap(
    const DenseEvaluationOptions& options,
    const std::function<void(std::size_t, std::size_t)>& progress = nullptr);

}  // namespace drvslam
