#include "drvslam/tools/truth/dense_truth.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>

#include "drvslam/core/error.h"
#include "drvslam/core/option_check.h"
#include "drvslam/dense/voxel_grid.h"
#include "drvslam/tools/eval/alignment.h"
#include "drvslam/tools/eval/closest_index.h"

namespace drvslam {
namespace {

constexpr double kCell = 0.1;  // the point grid's cell edge (metres)

// Map points bucketed by cell, to find those near one triangle.
class PointGrid {
 public:
  explicit PointGrid(const DenseCloud& cloud) {
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      const std::optional<int64_t> key = VoxelKey(cloud[i].position, kCell);
      if (key) cells_[*key].push_back(static_cast<uint32_t>(i));
    }
  }

  // Calls visit(index) for every point in the cells that the triangle's box, grown by radius,
  // overlaps.
  template <typename Visit>
  void ForNear(const synth::Triangle& t, double radius, Visit visit) const {
    Eigen::Vector3d lo = t.p[0], hi = t.p[0];
    for (int k = 1; k < 3; ++k) {
      lo = lo.cwiseMin(t.p[k]);
      hi = hi.cwiseMax(t.p[k]);
    }
    lo.array() -= radius;
    hi.array() += radius;
    const Eigen::Vector3d a = (lo / kCell).array().floor();
    const Eigen::Vector3d b = (hi / kCell).array().floor();
    for (double x = a.x(); x <= b.x(); ++x) {
      for (double y = a.y(); y <= b.y(); ++y) {
        for (double z = a.z(); z <= b.z(); ++z) {
          if (std::abs(x) >= kVoxelIndexLimit || std::abs(y) >= kVoxelIndexLimit ||
              std::abs(z) >= kVoxelIndexLimit) {
            continue;
          }
          const auto it = cells_.find(
              PackVoxel(static_cast<int64_t>(x), static_cast<int64_t>(y), static_cast<int64_t>(z)));
          if (it == cells_.end()) continue;
          for (const uint32_t index : it->second) visit(index);
        }
      }
    }
  }

 private:
  std::unordered_map<int64_t, std::vector<uint32_t>> cells_;
};

std::optional<double> Percentile(std::vector<double> values, double q) {
  if (values.empty()) return std::nullopt;
  const std::size_t k =
      std::min(values.size() - 1, static_cast<std::size_t>(std::ceil(q * values.size())) - 1);
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

std::optional<double> Mean(const std::vector<double>& values) {
  if (values.empty()) return std::nullopt;
  double sum = 0.0;
  for (const double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

std::optional<double> PointsPerCell(const DenseCloud& cloud, double cell) {
  if (cloud.empty()) return std::nullopt;
  std::unordered_map<int64_t, int> cells;
  for (const DensePoint& p : cloud) {
    if (const std::optional<int64_t> key = VoxelKey(p.position, cell)) ++cells[*key];
  }
  if (cells.empty()) return std::nullopt;
  return static_cast<double>(cloud.size()) / cells.size();
}

}  // namespace

double PointTriangleDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                             const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  // Closest point by Voronoi region of the triangle's vertices, edges and face.
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.norm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + ab * (d1 / (d1 - d3)))).norm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + ac * (d2 / (d2 - d6)))).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return (p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).norm();
  }
  const double sum = va + vb + vc;
  if (!(std::abs(sum) > 0)) return ap.norm();  // degenerate triangle
  const double v = vb / sum, w = vc / sum;
  return (p - (a + ab * v + ac * w)).norm();
}

DenseTruthScores ScoreDenseCloud(const DenseCloud& cloud, const synth::TriangleList& static_scene,
                                 const synth::TriangleList& actors_swept,
                                 const std::set<int>& key_labels, const DenseTruthOptions& options,
                                 std::vector<GhostPoint>* ghosts) {
  DenseTruthScores scores;
  scores.points = cloud.size();
  if (cloud.empty()) return scores;
  const PointGrid grid(cloud);
  std::vector<double> distance(cloud.size(), options.max_distance);
  for (const synth::Triangle& t : static_scene) {
    grid.ForNear(t, options.max_distance, [&](uint32_t i) {
      const double d =
          PointTriangleDistance(cloud[i].position.cast<double>(), t.p[0], t.p[1], t.p[2]);
      distance[i] = std::min(distance[i], d);
    });
  }
  std::vector<bool> near_actor(cloud.size(), false);
  std::vector<std::size_t> first_triangle(ghosts != nullptr ? cloud.size() : 0);
  for (std::size_t k = 0; k < actors_swept.size(); ++k) {
    const synth::Triangle& t = actors_swept[k];
    grid.ForNear(t, options.ghost_margin, [&](uint32_t i) {
      if (near_actor[i] || distance[i] <= options.ghost_margin) return;
      near_actor[i] = PointTriangleDistance(cloud[i].position.cast<double>(), t.p[0], t.p[1],
                                            t.p[2]) <= options.ghost_margin;
      if (near_actor[i] && ghosts != nullptr) first_triangle[i] = k;
    });
  }
  if (ghosts != nullptr) {
    ghosts->clear();
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      if (near_actor[i]) ghosts->push_back({i, distance[i], first_triangle[i]});
    }
  }
  std::vector<double> static_distance;
  DenseCloud key_points, background_points;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (near_actor[i]) {
      ++scores.ghosts;
    } else {
      static_distance.push_back(distance[i]);
    }
    (key_labels.count(cloud[i].label) ? key_points : background_points).push_back(cloud[i]);
  }
  scores.ghost_share = static_cast<double>(scores.ghosts) / cloud.size();
  scores.mean_distance = Mean(distance);
  scores.median_distance = Percentile(distance, 0.5);
  scores.p95_distance = Percentile(distance, 0.95);
  scores.static_mean_distance = Mean(static_distance);
  scores.static_p95_distance = Percentile(static_distance, 0.95);
  scores.key_object_points = key_points.size();
  scores.background_points = background_points.size();
  scores.key_object_density = PointsPerCell(key_points, options.density_cell);
  scores.background_density = PointsPerCell(background_points, options.density_cell);
  return scores;
}

synth::TriangleList SweptActorGeometry(const synth::SynthSequence& sequence, int stride, int frames,
                                       std::vector<int>* frame_of_triangle) {
  if (stride < 1) throw Error("actor frame stride must be at least 1");
  const int last = frames > 0 ? std::min(frames, sequence.FrameCount()) : sequence.FrameCount();
  synth::TriangleList swept;
  if (frame_of_triangle != nullptr) frame_of_triangle->clear();
  for (int f = 0; f < last; f += stride) {
    sequence.Actors().AppendTriangles(f, &swept);
    if (frame_of_triangle != nullptr) frame_of_triangle->resize(swept.size(), f);
  }
  return swept;
}

std::set<int> KeyObjectLabels(const synth::SynthSequence& sequence) {
  std::set<int> labels;
  for (const SynthInstance& instance : sequence.Scene().instances) {
    if (instance.coco_id >= 0) labels.insert(instance.coco_id);
  }
  return labels;
}

synth::SynthOptions SynthOptionsFromSettings(const SettingsFile& file) {
  if (!file.Has("Synth.Scenario") || !file.Has("Synth.Seed")) {
    throw Error(file.Path() + ": no Synth.Scenario / Synth.Seed: not a `drvslam synth` sequence");
  }
  synth::SynthOptions o;
  o.scenario = file.GetString("Synth.Scenario", o.scenario);
  const int seed = file.GetInt("Synth.Seed", 1);
  if (seed < 0) throw Error(file.Path() + ": Synth.Seed = " + std::to_string(seed) + " < 0");
  o.seed = static_cast<uint32_t>(seed);
  o.frames = file.GetInt("Synth.Frames", o.frames);
  o.actors = file.GetInt("Synth.Actors", o.actors);
  const std::string actor_class = file.GetString("Synth.ActorClass", "");
  if (!actor_class.empty()) o.actor_class = actor_class;
  o.billboards = file.GetString("Synth.Billboards", "");
  o.trajectory = file.GetString("Synth.Trajectory", "");
  o.width = file.GetInt("Camera.width", o.width);
  o.height = file.GetInt("Camera.height", o.height);
  o.fps = file.GetDouble("Camera.fps", o.fps);
  o.camera_speed = file.GetDouble("Synth.CameraSpeed", o.camera_speed);
  o.procedural_textures = true;
  return CheckedOptions(file.Path(), o);
}

DenseCloud AlignCloudToTruth(const DenseCloud& cloud, const Trajectory& estimate,
                             const Trajectory& truth, double max_difference) {
  std::vector<double> stamps;
  for (const StampedPose& pose : truth) stamps.push_back(pose.timestamp);
  std::vector<Eigen::Vector3d> est, gt;
  for (const StampedPose& pose : estimate) {
    if (stamps.empty()) break;
    const std::size_t k = FindClosestIndex(stamps, pose.timestamp);
    if (std::abs(stamps[k] - pose.timestamp) > max_difference) continue;
    // The camera centre and points 1 m along its axes: a short trajectory's positions alone
    // leave the rotation loose, and metres away from the camera that shows.
    for (int axis = -1; axis < 3; ++axis) {
      const Eigen::Vector3d offset =
          axis < 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d::Unit(axis).eval();
      est.push_back(pose.T_wc * offset);
      gt.push_back(truth[k].T_wc * offset);
    }
  }
  if (est.size() < 3 * 4) {
    throw Error("aligning the dense map: only " + std::to_string(est.size() / 4) +
                " estimated poses match ground-truth stamps (3 needed)");
  }
  const Alignment alignment = AlignPoints(est, gt, false);
  DenseCloud aligned = cloud;
  for (DensePoint& p : aligned) {
    p.position = alignment.Apply(p.position.cast<double>()).cast<float>();
  }
  return aligned;
}

std::string FormatDenseTruthScores(const DenseTruthScores& s) {
  // `format` takes one double (the value times `scale`); n/a when the value is undefined.
  const auto text = [](const char* format, const std::optional<double>& value,
                       double scale = 1.0) -> std::string {
    if (!value) return "n/a";
    char buffer[64];
    std::snprintf(buffer, sizeof(buffer), format, scale * value.value());
    return buffer;
  };
  std::string out;
  out += "points:              " + std::to_string(s.points) + "\n";
  out += "ghosts:              " + std::to_string(s.ghosts) + " (" +
         text("%.4f%%", s.ghost_share, 100.0) + ")\n";
  out += "distance to truth:   mean " + text("%.4f m", s.mean_distance) + ", median " +
         text("%.4f m", s.median_distance) + ", p95 " + text("%.4f m", s.p95_distance) + "\n";
  out += "  without ghosts:    mean " + text("%.4f m", s.static_mean_distance) + ", p95 " +
         text("%.4f m", s.static_p95_distance) + "\n";
  out += "key-object points:   " + std::to_string(s.key_object_points) + " (" +
         text("%.2f", s.key_object_density) + " per occupied cell)\n";
  out += "background points:   " + std::to_string(s.background_points) + " (" +
         text("%.2f", s.background_density) + " per occupied cell)\n";
  return out;
}

}  // namespace drvslam
