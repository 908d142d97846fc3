#include "dense/furnished_room.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <set>
#include <tuple>

#include "drvslam/dense/occupancy_grid_io.h"

namespace drvslam::testing {
namespace {

constexpr double kRoomVoxel = 0.05;

using VoxelKey = std::tuple<int, int, int>;

VoxelKey KeyOf(const Eigen::Vector3d& p) {
  return {static_cast<int>(std::floor(p.x() / kRoomVoxel)),
          static_cast<int>(std::floor(p.y() / kRoomVoxel)),
          static_cast<int>(std::floor(p.z() / kRoomVoxel))};
}

bool AnyContains(const std::vector<Rect>& rects, double x, double y, double margin = 0.0) {
  return std::any_of(rects.begin(), rects.end(),
                     [&](const Rect& r) { return r.Contains(x, y, margin); });
}

const Furniture* Under(const RoomLayout& layout, double x, double y) {
  for (const Furniture& f : layout.furniture) {
    if (f.footprint.Contains(x, y)) return &f;
  }
  return nullptr;
}

// Lattice steps from `from` up to `to` (exclusive), `step` apart, starting half a step in.
std::vector<double> Steps(double from, double to, double step) {
  std::vector<double> values;
  for (double v = from + 0.5 * step; v < to; v += step) values.push_back(v);
  return values;
}

// Scene-frame points of every surface the cameras saw, before noise.
std::vector<Eigen::Vector3d> SurfacePoints(const RoomLayout& layout) {
  std::vector<Eigen::Vector3d> points;
  const Rect& room = layout.room;
  for (double x : Steps(room.x0, room.x1, layout.floor_spacing)) {
    for (double y : Steps(room.y0, room.y1, layout.floor_spacing)) {
      if (AnyContains(layout.seen_floor, x, y) && !Under(layout, x, y))
        points.emplace_back(x, y, 0);
    }
  }
  for (const Furniture& f : layout.furniture) {
    const Rect& r = f.footprint;
    for (double x : Steps(r.x0, r.x1, layout.top_spacing)) {
      for (double y : Steps(r.y0, r.y1, layout.top_spacing)) points.emplace_back(x, y, f.top);
    }
    for (double z : Steps(0.0, f.top, 0.02)) {
      if (f.legs) {  // four 4 cm legs at the corners
        for (double x : {r.x0 + 0.02, r.x1 - 0.02}) {
          for (double y : {r.y0 + 0.02, r.y1 - 0.02}) {
            for (const Eigen::Vector2d& d :
                 {Eigen::Vector2d(-0.02, -0.02), Eigen::Vector2d(0.02, -0.02),
                  Eigen::Vector2d(-0.02, 0.02), Eigen::Vector2d(0.02, 0.02)}) {
              points.emplace_back(x + d.x(), y + d.y(), z);
            }
          }
        }
        continue;
      }
      for (double x : Steps(r.x0, r.x1, layout.floor_spacing)) {  // solid sides
        points.emplace_back(x, r.y0, z);
        points.emplace_back(x, r.y1, z);
      }
      for (double y : Steps(r.y0, r.y1, layout.floor_spacing)) {
        points.emplace_back(r.x0, y, z);
        points.emplace_back(r.x1, y, z);
      }
    }
  }
  for (double z : Steps(0.0, layout.walls ? layout.ceiling : 0.0, kRoomVoxel)) {  // walls
    for (double x : Steps(room.x0, room.x1, kRoomVoxel)) {
      points.emplace_back(x, room.y0, z);
      points.emplace_back(x, room.y1, z);
    }
    for (double y : Steps(room.y0, room.y1, kRoomVoxel)) {
      points.emplace_back(room.x0, y, z);
      points.emplace_back(room.x1, y, z);
    }
  }
  for (double x : Steps(room.x0, room.x1, kRoomVoxel)) {
    for (double y : Steps(room.y0, room.y1, kRoomVoxel)) points.emplace_back(x, y, layout.ceiling);
  }
  return points;
}

}  // namespace

Camera PitchedCamera(const Eigen::Vector3d& centre, const Eigen::Vector3d& heading,
                     double pitch_deg) {
  const double pitch = pitch_deg * M_PI / 180.0;
  const Eigen::Vector3d forward =
      std::cos(pitch) * heading.normalized() - std::sin(pitch) * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d right = heading.normalized().cross(Eigen::Vector3d::UnitZ());
  return {centre, forward.cross(right).normalized()};
}

BuiltRoom BuildRoom(const RoomLayout& layout) {
  BuiltRoom built;
  std::mt19937 random(7u);
  std::normal_distribution<double> noise(0.0, 0.004);
  std::set<VoxelKey> occupied;
  for (const Eigen::Vector3d& clean : SurfacePoints(layout)) {
    const Eigen::Vector3d p = clean + Eigen::Vector3d(noise(random), noise(random), noise(random));
    DensePoint point;
    point.position = (layout.world_from_scene * p).cast<float>();
    built.rays.cloud.push_back(point);
    occupied.insert(KeyOf(p));
  }
  const auto centre_of = [&](int i, int j, int k) {
    return Eigen::Vector3d((i + 0.5) * kRoomVoxel, (j + 0.5) * kRoomVoxel, (k + 0.5) * kRoomVoxel);
  };
  for (const VoxelKey& key : occupied) {
    const Eigen::Vector3d c = centre_of(std::get<0>(key), std::get<1>(key), std::get<2>(key));
    built.samples.occupied.push_back((layout.world_from_scene * c).cast<float>());
  }
  // Free: seen space above the seen floor and above furniture tops (below them: shadow).
  const Rect& room = layout.room;
  for (int i = static_cast<int>(std::floor(room.x0 / kRoomVoxel)); (i + 0.5) * kRoomVoxel < room.x1;
       ++i) {
    for (int j = static_cast<int>(std::floor(room.y0 / kRoomVoxel));
         (j + 0.5) * kRoomVoxel < room.y1; ++j) {
      const Eigen::Vector3d column = centre_of(i, j, 0);
      if (!AnyContains(layout.seen_floor, column.x(), column.y())) continue;
      const Furniture* under = Under(layout, column.x(), column.y());
      for (int k = 0; (k + 1.5) * kRoomVoxel < layout.ceiling; ++k) {
        const Eigen::Vector3d c = centre_of(i, j, k);
        if (under && c.z() < under->top + kRoomVoxel) continue;
        if (occupied.count({i, j, k}) == 0) {
          built.samples.free.push_back((layout.world_from_scene * c).cast<float>());
        }
      }
    }
  }
  built.samples.voxel_size = kRoomVoxel;
  for (const Camera& camera : layout.cameras) {
    built.rays.origins.push_back((layout.world_from_scene * camera.centre).cast<float>());
    built.rays.downs.push_back((layout.world_from_scene.linear() * camera.down).cast<float>());
  }
  return built;
}

RoomScore ScoreGrid(const RoomLayout& layout, const OccupancyGrid& grid) {
  RoomScore score;
  const Eigen::Isometry3d world_from_grid(grid.T_world_grid);
  const Eigen::Isometry3d scene_from_grid = layout.world_from_scene.inverse() * world_from_grid;
  const Eigen::Isometry3d grid_from_scene = scene_from_grid.inverse();
  for (const Rect& r : layout.seen_floor) {
    for (const Eigen::Vector3d& corner :
         {Eigen::Vector3d(r.x0, r.y0, 0), Eigen::Vector3d(r.x1, r.y0, 0),
          Eigen::Vector3d(r.x0, r.y1, 0), Eigen::Vector3d(r.x1, r.y1, 0)}) {
      score.floor_error = std::max(score.floor_error, std::abs((grid_from_scene * corner).z()));
    }
  }
  for (int row = 0; row < grid.height; ++row) {
    for (int column = 0; column < grid.width; ++column) {
      const Eigen::Vector3d centre((column + 0.5) * grid.resolution + grid.origin.x(),
                                   (row + 0.5) * grid.resolution + grid.origin.y(), 0.0);
      const Eigen::Vector3d p = scene_from_grid * centre;
      const bool occupied = grid.At(column, row) == GridCell::kOccupied;
      // Margins: the cells are not aligned to the furniture's edges.
      bool inside = false, near = false;
      for (const Furniture& f : layout.furniture) {
        inside = inside || f.footprint.Contains(p.x(), p.y(), 0.03);
        near = near || f.footprint.Contains(p.x(), p.y(), -0.08);
      }
      if (inside) {
        ++score.footprint_cells;
        score.footprint_occupied += occupied;
      } else if (near) {
        continue;
      } else if (AnyContains(layout.lanes, p.x(), p.y())) {
        ++score.lane_cells;
        score.lane_occupied += occupied;
      } else if (AnyContains(layout.seen_floor, p.x(), p.y(), 0.08)) {
        ++score.open_cells;
        score.open_occupied += occupied;
      }
    }
  }
  return score;
}

std::string SaveGridPicture(const OccupancyGrid& grid, const std::string& name) {
  const char* folder = std::getenv("DRVSLAM_GRID_PICTURES");
  if (folder == nullptr || grid.cells.empty()) return "";
  cv::Mat image(grid.height, grid.width, CV_8UC1);
  for (int row = 0; row < grid.height; ++row) {  // image rows run down, the grid's y up
    for (int column = 0; column < grid.width; ++column) {
      const GridCell cell = grid.At(column, row);
      image.at<std::uint8_t>(grid.height - 1 - row, column) =
          cell == GridCell::kOccupied ? kPgmOccupied
                                      : (cell == GridCell::kFree ? kPgmFree : kPgmUnknown);
    }
  }
  cv::Mat large;
  cv::resize(image, large, cv::Size(), 4.0, 4.0, cv::INTER_NEAREST);
  std::filesystem::create_directories(folder);
  const std::string path = (std::filesystem::path(folder) / (name + ".png")).string();
  return cv::imwrite(path, large) ? path : "";
}

}  // namespace drvslam::testing
