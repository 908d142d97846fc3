#include "drvslam/dense/voxel_grid.h"

#include <cmath>
#include <unordered_map>

namespace drvslam {
namespace {

constexpr int kBits = 21;
constexpr int64_t kMask = (int64_t{1} << kBits) - 1;

struct Accumulator {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  uint32_t r = 0, g = 0, b = 0;
  uint32_t count = 0;
  int16_t label = -1;
  int32_t track = -1;
};

bool InRange(int64_t index) { return index >= -kVoxelIndexLimit && index < kVoxelIndexLimit; }

}  // namespace

int64_t PackVoxel(int64_t x, int64_t y, int64_t z) {
  return ((x + kVoxelIndexLimit) << (2 * kBits)) | ((y + kVoxelIndexLimit) << kBits) |
         (z + kVoxelIndexLimit);
}

Eigen::Matrix<int64_t, 3, 1> UnpackVoxel(int64_t key) {
  return {((key >> (2 * kBits)) & kMask) - kVoxelIndexLimit,
          ((key >> kBits) & kMask) - kVoxelIndexLimit, (key & kMask) - kVoxelIndexLimit};
}

std::optional<int64_t> VoxelKey(const Eigen::Vector3f& p, double leaf) {
  const double inverse = 1.0 / leaf;
  int64_t index[3];
  for (int axis = 0; axis < 3; ++axis) {
    const double v = std::floor(static_cast<double>(p[axis]) * inverse);
    if (!std::isfinite(v) || v < -static_cast<double>(kVoxelIndexLimit) ||
        v >= static_cast<double>(kVoxelIndexLimit)) {
      return std::nullopt;
    }
    index[axis] = static_cast<int64_t>(v);
  }
  return PackVoxel(index[0], index[1], index[2]);
}

DenseCloud VoxelDownsample(const DenseCloud& points, double leaf) {
  std::unordered_map<int64_t, uint32_t> slot_of_key;
  slot_of_key.reserve(points.size() / 4 + 16);
  std::vector<Accumulator> slots;
  for (const DensePoint& point : points) {
    const std::optional<int64_t> key = VoxelKey(point.position, leaf);
    if (!key) continue;
    const auto [it, inserted] = slot_of_key.try_emplace(*key, static_cast<uint32_t>(slots.size()));
    if (inserted) slots.emplace_back();
    Accumulator& a = slots[it->second];
    a.sum += point.position.cast<double>();
    a.r += point.r;
    a.g += point.g;
    a.b += point.b;
    ++a.count;
    if (a.label < 0) a.label = point.label;
    if (a.track < 0) a.track = point.track;
  }
  DenseCloud out(slots.size());
  for (std::size_t i = 0; i < slots.size(); ++i) {
    const Accumulator& a = slots[i];
    const double n = a.count;
    DensePoint& p = out[i];
    p.position = (a.sum / n).cast<float>();
    p.r = static_cast<uint8_t>(std::lround(a.r / n));
    p.g = static_cast<uint8_t>(std::lround(a.g / n));
    p.b = static_cast<uint8_t>(std::lround(a.b / n));
    p.label = a.label;
    p.track = a.track;
  }
  return out;
}

DenseCloud WeightedVoxelDownsample(const DenseCloud& points, const std::vector<float>& weights,
                                   double leaf, std::vector<float>* voxel_weights) {
  struct Weighted {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Vector3d colour = Eigen::Vector3d::Zero();
    double weight = 0.0;
    int16_t label = -1;
    int32_t track = -1;
  };
  std::unordered_map<int64_t, uint32_t> slot_of_key;
  slot_of_key.reserve(points.size() / 4 + 16);
  std::vector<Weighted> slots;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const DensePoint& point = points[i];
    const std::optional<int64_t> key = VoxelKey(point.position, leaf);
    if (!key) continue;
    const auto [it, inserted] = slot_of_key.try_emplace(*key, static_cast<uint32_t>(slots.size()));
    if (inserted) slots.emplace_back();
    Weighted& a = slots[it->second];
    const double w = weights[i];
    a.sum += w * point.position.cast<double>();
    a.colour += w * Eigen::Vector3d(point.r, point.g, point.b);
    a.weight += w;
    if (a.label < 0) a.label = point.label;
    if (a.track < 0) a.track = point.track;
  }
  DenseCloud out(slots.size());
  voxel_weights->resize(slots.size());
  for (std::size_t i = 0; i < slots.size(); ++i) {
    const Weighted& a = slots[i];
    DensePoint& p = out[i];
    p.position = (a.sum / a.weight).cast<float>();
    const Eigen::Vector3d colour = a.colour / a.weight;
    p.r = static_cast<uint8_t>(std::lround(colour.x()));
    p.g = static_cast<uint8_t>(std::lround(colour.y()));
    p.b = static_cast<uint8_t>(std::lround(colour.z()));
    p.label = a.label;
    p.track = a.track;
    (*voxel_weights)[i] = static_cast<float>(a.weight);
  }
  return out;
}

DenseCloud RemoveIsolatedPoints(const DenseCloud& points, double leaf, int min_neighbours) {
  if (min_neighbours <= 0) return points;
  DenseCloud kept;
  const std::vector<std::size_t> indices = ConnectedPointIndices(points, leaf, min_neighbours);
  kept.reserve(indices.size());
  for (const std::size_t i : indices) kept.push_back(points[i]);
  return kept;
}

std::vector<std::size_t> ConnectedPointIndices(const DenseCloud& points, double leaf,
                                               int min_neighbours) {
  std::vector<std::size_t> kept;
  kept.reserve(points.size());
  if (min_neighbours <= 0) {
    for (std::size_t i = 0; i < points.size(); ++i) kept.push_back(i);
    return kept;
  }
  std::unordered_map<int64_t, int> occupancy;
  occupancy.reserve(points.size() + 16);
  std::vector<std::optional<int64_t>> keys(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    keys[i] = VoxelKey(points[i].position, leaf);
    if (keys[i]) ++occupancy[*keys[i]];
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!keys[i]) continue;
    const Eigen::Matrix<int64_t, 3, 1> v = UnpackVoxel(*keys[i]);
    // Other points in the same voxel count as neighbours too.
    int neighbours = occupancy[*keys[i]] - 1;
    for (int dx = -1; dx <= 1 && neighbours < min_neighbours; ++dx) {
      for (int dy = -1; dy <= 1 && neighbours < min_neighbours; ++dy) {
        for (int dz = -1; dz <= 1 && neighbours < min_neighbours; ++dz) {
          if (dx == 0 && dy == 0 && dz == 0) continue;
          const int64_t x = v.x() + dx, y = v.y() + dy, z = v.z() + dz;
          if (!InRange(x) || !InRange(y) || !InRange(z)) continue;
          neighbours += occupancy.count(PackVoxel(x, y, z)) ? 1 : 0;
        }
      }
    }
    if (neighbours >= min_neighbours) kept.push_back(i);
  }
  return kept;
}

}  // namespace drvslam
