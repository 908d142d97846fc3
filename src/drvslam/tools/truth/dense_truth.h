// Dense-map accuracy against synthetic ground truth (the acceptance measures of the dense
// mapping thread): ghosts - map points in space that actors swept through - and the distance
// of map points to the true static surfaces, plus the point density on key objects against the
// background. Geometry comes from the SynthSequence the dataset was generated from, rebuilt
// from the Synth.* keys of its settings.yaml.
#pragma once

#include <optional>
#include <set>
#include <string>
#include <vector>

#include "drvslam/core/settings_file.h"
#include "drvslam/dense/dense_point.h"
#include "drvslam/io/trajectory_io.h"
#include "drvslam/tools/synth/scene.h"
#include "drvslam/tools/synth/synth_options.h"
#include "drvslam/tools/synth/synth_sequence.h"

namespace drvslam {

struct DenseTruthOptions {
  // A point within ghost_margin of an actor's surface at some frame, and farther than that
  // from every static surface, is a ghost (metres).
  double ghost_margin = 0.05;
  // Distances to the static scene are capped here (metres).
  double max_distance = 0.25;
  // Density is counted as points per occupied cube of this edge (metres).
  double density_cell = 0.05;
  // Actor geometry is taken at every n-th frame (1 = all).
  int actor_frame_stride = 1;
};

// A ratio or statistic over no points is undefined (nullopt), not 0: an empty map has no ghosts
// to count and no distance to measure, and must not score as a perfect one.
struct DenseTruthScores {
  std::size_t points = 0;
  std::size_t ghosts = 0;
  std::optional<double> ghost_share;
  // Distance to the nearest static surface (capped at max_distance).
  std::optional<double> mean_distance;
  std::optional<double> median_distance;
  std::optional<double> p95_distance;
  // The same over the points that are not ghosts.
  std::optional<double> static_mean_distance;
  std::optional<double> static_p95_distance;
  std::size_t key_object_points = 0;  // labelled with a key-object class
  std::size_t background_points = 0;
  std::optional<double> key_object_density;  // points per occupied density cell
  std::optional<double> background_density;
};

// One ghost: which point, how far from the static scene, and the first swept actor triangle
// within the ghost margin (its frame tells when the actor was there).
struct GhostPoint {
  std::size_t index = 0;
  double static_distance = 0.0;
  std::size_t actor_triangle = 0;
};

// Scores world points (in the ground-truth frame). `key_labels`: class ids of key objects.
// `ghosts` (may be null) receives every ghost, in point order.
DenseTruthScores ScoreDenseCloud(const DenseCloud& cloud, const synth::TriangleList& static_scene,
                                 const synth::TriangleList& actors_swept,
                                 const std::set<int>& key_labels, const DenseTruthOptions& options,
                                 std::vector<GhostPoint>* ghosts = nullptr);

// Every actor triangle of `sequence` at every stride-th frame of the first `frames` (0 = all).
// `frame_of_triangle` (may be null) receives the frame of each.
synth::TriangleList SweptActorGeometry(const synth::SynthSequence& sequence, int stride,
                                       int frames = 0,
                                       std::vector<int>* frame_of_triangle = nullptr);
// COCO ids of the sequence's static key objects.
std::set<int> KeyObjectLabels(const synth::SynthSequence& sequence);

// The options a dataset was generated with, from the Synth.* and Camera.* keys of its
// settings.yaml, with procedural textures (geometry does not depend on them). Throws Error
// naming the file when it was not written by `drvslam synth`.
synth::SynthOptions SynthOptionsFromSettings(const SettingsFile& file);

// Shortest distance from p to the triangle (a, b, c).
double PointTriangleDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                             const Eigen::Vector3d& b, const Eigen::Vector3d& c);

// Rigidly aligns `estimate` (camera poses T_wc) onto `truth` by matching stamps within
// max_difference seconds - positions and orientations, through each camera's centre and axis
// tips - and maps the cloud into the ground-truth frame. Throws Error when fewer than 3 poses
// match.
DenseCloud AlignCloudToTruth(const DenseCloud& cloud, const Trajectory& estimate,
                             const Trajectory& truth, double max_difference = 0.02);

// The scores as lines of text, for the CLI.
std::string FormatDenseTruthScores(const DenseTruthScores& scores);

}  // namespace drvslam
