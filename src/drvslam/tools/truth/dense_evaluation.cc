#include "drvslam/tools/truth/dense_evaluation.h"

#include <octomap/OcTree.h>

#include <filesystem>
#include <fstream>

#include "drvslam/core/error.h"
#include "drvslam/core/timing.h"
#include "drvslam/dense/point_cloud_io.h"
#include "drvslam/io/tum_dataset.h"
#include "drvslam/tools/truth/ground_truth_mapping.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

// The rebuilt sequence must be the one on disk: its poses match groundtruth.txt.
void CheckRebuilt(const synth::SynthSequence& sequence, const Trajectory& truth,
                  const std::string& dataset) {
  const std::size_t n = std::min<std::size_t>(truth.size(), sequence.FrameCount());
  for (std::size_t i = 0; i < n; i += std::max<std::size_t>(1, n / 10)) {
    const double error =
        (truth[i].T_wc.Translation() - sequence.Pose(static_cast<int>(i)).Translation()).norm();
    if (error > 1e-3) {
      throw Error(dataset + ": groundtruth.txt differs from the sequence rebuilt from " +
                  "settings.yaml (pose " + std::to_string(i) + " off by " + std::to_string(error) +
                  " m)");
    }
  }
}

// A relative Synth.Billboards names a folder from where `drvslam synth` ran: try the working
// folder, then the dataset folder and its parents.
std::string ResolveBillboards(const std::string& configured, const std::string& dataset,
                              const std::string& settings_path) {
  if (configured.empty() || fs::path(configured).is_absolute() || fs::is_directory(configured)) {
    return configured;
  }
  fs::path base = fs::absolute(dataset);
  for (int up = 0; up < 3 && !base.empty(); ++up, base = base.parent_path()) {
    if (fs::is_directory(base / configured)) return (base / configured).string();
  }
  throw Error(settings_path + ": Synth.Billboards = " + configured +
              " is found neither from the working folder nor from the dataset or its parents; " +
              "pass --billboards");
}

// Centres of the occupied cells of a .bt file at its resolution (pruned leaves are expanded).
DenseCloud OccupiedCells(const std::string& path, double* resolution) {
  if (!fs::exists(path)) throw Error(path + ": missing");
  octomap::OcTree tree(0.1);
  if (!tree.readBinary(path)) throw Error(path + ": not a binary OctoMap (.bt) file");
  *resolution = tree.getResolution();
  DenseCloud cells;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    const double size = it.getSize();
    const int n = std::max(1, static_cast<int>(std::lround(size / *resolution)));
    const octomap::point3d c = it.getCoordinate();
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        for (int k = 0; k < n; ++k) {
          DensePoint p;
          p.position = {static_cast<float>(c.x() - size / 2 + (i + 0.5) * *resolution),
                        static_cast<float>(c.y() - size / 2 + (j + 0.5) * *resolution),
                        static_cast<float>(c.z() - size / 2 + (k + 0.5) * *resolution)};
          cells.push_back(p);
        }
      }
    }
  }
  return cells;
}

void WriteGhostRows(const std::string& source, const DenseCloud& cloud,
                    const std::vector<GhostPoint>& ghosts,
                    const std::vector<int>& frame_of_triangle, std::ofstream* out) {
  for (const GhostPoint& g : ghosts) {
    const DensePoint& p = cloud[g.index];
    *out << source << ',' << g.index << ',' << p.position.x() << ',' << p.position.y() << ','
         << p.position.z() << ',' << p.label << ',' << g.static_distance << ','
         << frame_of_triangle[g.actor_triangle] << '\n';
  }
}

}  // namespace

DenseEvaluation EvaluateDenseMap(const DenseEvaluationOptions& options,
                                 const std::function<void(std::size_t, std::size_t)>& progress) {
  if (!options.removal.empty() && options.removal != "on" && options.removal != "off") {
    throw Error("--removal = " + options.removal + " must be on or off");
  }
  if (options.truth.ghost_margin <= 0 || options.truth.max_distance <= 0 ||
      options.truth.density_cell <= 0) {
    throw Error("ghost margin, distance cap and density cell must be positive");
  }
  const std::string settings_path = (fs::path(options.dataset) / "settings.yaml").string();
  if (!fs::exists(settings_path)) throw Error(settings_path + ": missing");
  const SettingsFile settings(settings_path);
  const TumDataset dataset(options.dataset);
  if (!dataset.HasGroundTruth()) throw Error(options.dataset + ": no groundtruth.txt");

  DenseEvaluation evaluation;
  DenseCloud cloud;
  DenseCloud cells;  // occupied OctoMap cells, aligned as the map
  if (!options.octomap.empty())
    cells = OccupiedCells(options.octomap, &evaluation.octomap_resolution);
  int frames = static_cast<int>(dataset.Size());
  if (options.map.empty()) {
    GroundTruthMappingOptions mapping;
    mapping.dense = LoadDenseMapOptions(settings);
    if (!options.removal.empty()) mapping.dense.remove_dynamic = options.removal == "on";
    mapping.keyframe_every = options.keyframe_every;
    mapping.max_frames = options.max_frames;
    GroundTruthMapping built = MapWithGroundTruth(options.dataset, mapping, progress);
    cloud = std::move(built.cloud);
    evaluation.stats = built.stats;
    if (options.max_frames > 0) frames = std::min(frames, static_cast<int>(options.max_frames));
    if (!options.out_dir.empty()) {
      std::error_code error;
      fs::create_directories(options.out_dir, error);
      WritePlyCloud((fs::path(options.out_dir) / "dense_map.ply").string(), cloud);
      WritePcdCloud((fs::path(options.out_dir) / "dense_map.pcd").string(), cloud);
    }
  } else {
    cloud = ReadPlyCloud(options.map);
    if (!options.trajectory.empty()) {
      const Trajectory estimate = ReadTumTrajectory(options.trajectory);
      cloud = AlignCloudToTruth(cloud, estimate, dataset.GroundTruth());
      if (!cells.empty()) cells = AlignCloudToTruth(cells, estimate, dataset.GroundTruth());
      // Actors count up to the run's last frame.
      if (!estimate.empty()) {
        int last = 0;
        for (std::size_t i = 0; i < dataset.Size(); ++i) {
          if (dataset.Timestamp(i) <= estimate.back().timestamp + 1e-3) {
            last = static_cast<int>(i) + 1;
          }
        }
        frames = last;
      }
    }
    if (options.max_frames > 0) frames = std::min(frames, static_cast<int>(options.max_frames));
  }

  const Stopwatch watch;
  synth::SynthOptions synth_options = SynthOptionsFromSettings(settings);
  synth_options.billboards =
      options.billboards.empty()
          ? ResolveBillboards(synth_options.billboards, options.dataset, settings_path)
          : options.billboards;
  const synth::SynthSequence sequence(synth_options);
  CheckRebuilt(sequence, dataset.GroundTruth(), options.dataset);
  std::vector<int> frame_of_triangle;
  const synth::TriangleList swept =
      SweptActorGeometry(sequence, options.truth.actor_frame_stride, frames, &frame_of_triangle);
  evaluation.frames = frames;
  evaluation.actor_triangles = swept.size();
  std::vector<GhostPoint> ghosts, ghost_cells;
  const bool list = !options.ghosts_csv.empty();
  evaluation.scores =
      ScoreDenseCloud(cloud, sequence.Scene().triangles, swept, KeyObjectLabels(sequence),
                      options.truth, list ? &ghosts : nullptr);
  if (!options.octomap.empty()) {
    evaluation.octomap_scores =
        ScoreDenseCloud(cells, sequence.Scene().triangles, swept, KeyObjectLabels(sequence),
                        options.truth, list ? &ghost_cells : nullptr);
  }
  if (list) {
    std::ofstream out(options.ghosts_csv);
    if (!out) throw Error(options.ghosts_csv + ": cannot open for writing");
    out << "source,index,x,y,z,label,static_distance_m,actor_frame\n";
    WriteGhostRows("map", cloud, ghosts, frame_of_triangle, &out);
    WriteGhostRows("octomap", cells, ghost_cells, frame_of_triangle, &out);
    if (!out) throw Error(options.ghosts_csv + ": write failed");
  }
  evaluation.seconds = watch.ElapsedMs() / 1000.0;
  return evaluation;
}

}  // namespace drvslam
