#include "drvslam/dense/dense_octomap.h"

#include <octomap/OcTree.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/core/timing.h"

namespace drvslam {
namespace {

octomap::point3d ToOcto(const Eigen::Vector3f& p) { return {p.x(), p.y(), p.z()}; }

// Key order for a deterministic side table.
struct KeyLess {
  bool operator()(const octomap::OcTreeKey& a, const octomap::OcTreeKey& b) const {
    if (a[0] != b[0]) return a[0] < b[0];
    if (a[1] != b[1]) return a[1] < b[1];
    return a[2] < b[2];
  }
};

// Every finest-level voxel centre of the leaf at `centre` with edge `size` (pruning merges
// eight equal children into one leaf).
void AddLeafVoxels(const octomap::point3d& centre, double size, double resolution,
                   std::vector<Eigen::Vector3f>* voxels) {
  const int n = std::max(1, static_cast<int>(std::lround(size / resolution)));
  const double first = -0.5 * size + 0.5 * resolution;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      for (int k = 0; k < n; ++k) {
        voxels->emplace_back(static_cast<float>(centre.x() + first + i * resolution),
                             static_cast<float>(centre.y() + first + j * resolution),
                             static_cast<float>(centre.z() + first + k * resolution));
      }
    }
  }
}

// Inserts one scan per anchor keyframe, from its camera centre, and fills `labels` (may be
// null) with the class id of each labelled point's voxel.
void InsertRays(const DenseMapRays& rays, octomap::OcTree* tree,
                std::map<octomap::OcTreeKey, int, KeyLess>* labels) {
  std::vector<octomap::Pointcloud> scans(rays.origins.size());
  for (std::size_t i = 0; i < rays.cloud.size(); ++i) {
    const DensePoint& p = rays.cloud[i];
    scans[static_cast<std::size_t>(rays.origin_of_point[i])].push_back(ToOcto(p.position));
    if (labels == nullptr || p.label < 0) continue;
    octomap::OcTreeKey key;
    if (tree->coordToKeyChecked(ToOcto(p.position), key)) labels->emplace(key, p.label);
  }
  for (std::size_t a = 0; a < scans.size(); ++a) {
    if (scans[a].size() == 0) continue;
    tree->insertPointCloud(scans[a], ToOcto(rays.origins[a]), /*maxrange=*/-1.0,
                           /*lazy_eval=*/true, /*discretize=*/true);
  }
  tree->updateInnerOccupancy();
  tree->prune();
}

// Counts the tree's leaves into `result` and adds their finest-level voxels to `samples` (may
// be null).
void CollectLeaves(const octomap::OcTree& tree, double resolution, DenseOctoMapExport* result,
                   OccupancySamples* samples) {
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    const bool occupied = tree.isNodeOccupied(*it);
    if (occupied) {
      ++result->occupied_leaves;
    } else {
      ++result->free_leaves;
    }
    if (samples != nullptr) {
      AddLeafVoxels(it.getCoordinate(), it.getSize(), resolution,
                    occupied ? &samples->occupied : &samples->free);
    }
  }
  if (samples != nullptr) samples->voxel_size = resolution;
}

}  // namespace

OccupancySamples SampleDenseOctoMap(const DenseMapRays& rays, double resolution) {
  octomap::OcTree tree(resolution);
  InsertRays(rays, &tree, nullptr);
  DenseOctoMapExport counts;
  OccupancySamples samples;
  CollectLeaves(tree, resolution, &counts, &samples);
  return samples;
}

DenseOctoMapExport WriteDenseOctoMap(const DenseMapRays& rays, double resolution,
                                     const std::string& bt_path, const std::string& labels_path,
                                     OccupancySamples* samples) {
  DenseOctoMapExport result;
  result.bt_path = bt_path;
  result.labels_path = labels_path;
  const Stopwatch build;
  octomap::OcTree tree(resolution);
  std::map<octomap::OcTreeKey, int, KeyLess> labels;
  InsertRays(rays, &tree, &labels);
  result.build_ms = build.ElapsedMs();

  const Stopwatch write;
  CollectLeaves(tree, resolution, &result, samples);
  if (!tree.writeBinary(bt_path)) throw Error(bt_path + ": cannot write the OctoMap");
  nlohmann::json table;
  table["resolution"] = resolution;
  table["format"] = "leaves: [x, y, z, class id] at occupied leaf centres (metres, world frame)";
  nlohmann::json leaves = nlohmann::json::array();
  for (const auto& [key, label] : labels) {
    const octomap::OcTreeNode* node = tree.search(key);
    if (node == nullptr || !tree.isNodeOccupied(node)) continue;
    const octomap::point3d centre = tree.keyToCoord(key);
    leaves.push_back({centre.x(), centre.y(), centre.z(), label});
  }
  result.labelled_leaves = leaves.size();
  table["leaves"] = std::move(leaves);
  std::ofstream out(labels_path);
  if (!out) throw Error(labels_path + ": cannot open for writing");
  out << table.dump() << "\n";
  if (!out) throw Error(labels_path + ": write failed");
  out.close();
  result.write_ms = write.ElapsedMs();
  std::error_code error;
  result.bytes = static_cast<std::size_t>(std::filesystem::file_size(bt_path, error));
  return result;
}

}  // namespace drvslam
