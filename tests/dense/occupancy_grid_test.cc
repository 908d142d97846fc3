// The 2-D occupancy grid on a small synthetic scene: a floor, a box standing on it, the free
// space a camera saw through. The scene is tilted (the trajectory's world frame is a pitched
// camera's), so the floor must be found from the cameras' "down", not the world's axes.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "drvslam/core/error.h"
#include "drvslam/dense/floor_plane.h"
#include "drvslam/dense/grid_export.h"
#include "drvslam/dense/occupancy_grid_io.h"
#include "test_support/temp_folder.h"

namespace drvslam {
namespace {

constexpr double kVoxel = 0.05;
// The box: x, y in [kBoxMin, kBoxMax], 0.5 m tall. Free space is seen over x, y in
// [-kSeen, kSeen] except the box and the shadow x > kShadowX (never seen through), up to a wall
// at x = kSeen.
constexpr double kBoxMin = 0.5;
constexpr double kBoxMax = 1.0;
constexpr double kSeen = 1.5;
constexpr double kShadowX = 1.2;
constexpr int kWallColumn = 29;  // voxel centres at x = 1.475

// Scene frame (floor z = 0, z up) to the world frame: pitched 25 degrees, raised and moved.
Eigen::Isometry3d WorldFromScene() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.rotate(Eigen::AngleAxisd(25.0 * M_PI / 180.0, Eigen::Vector3d::UnitX()));
  T.pretranslate(Eigen::Vector3d(0.3, -1.2, 0.7));
  return T;
}

Eigen::Vector3f ToWorld(double x, double y, double z) {
  return (WorldFromScene() * Eigen::Vector3d(x, y, z)).cast<float>();
}

bool InBox(double x, double y) {
  return x >= kBoxMin && x <= kBoxMax && y >= kBoxMin && y <= kBoxMax;
}

// Voxel centres at (i + 0.5) * kVoxel.
double Centre(int i) { return (i + 0.5) * kVoxel; }

struct Scene {
  DenseMapRays rays;
  OccupancySamples samples;
};

Scene MakeScene() {
  Scene scene;
  const int n = static_cast<int>(std::lround(2.0 / kVoxel));
  for (int i = -n; i < n; ++i) {
    for (int j = -n; j < n; ++j) {
      const double x = Centre(i), y = Centre(j);
      // Floor points everywhere in 4 m x 4 m (the floor is occupied but below the band).
      DensePoint floor;
      floor.position = ToWorld(x, y, 0.0);
      scene.rays.cloud.push_back(floor);
      scene.samples.occupied.push_back(ToWorld(x, y, Centre(0) - kVoxel));
      for (int k = 0; k < 30; ++k) {  // up to 1.5 m
        const double z = Centre(k);
        if (InBox(x, y) && z < 0.5) {
          scene.samples.occupied.push_back(ToWorld(x, y, z));
          DensePoint box;
          box.position = ToWorld(x, y, z);
          scene.rays.cloud.push_back(box);
        } else if (i == kWallColumn && std::abs(y) < kSeen) {
          scene.samples.occupied.push_back(ToWorld(x, y, z));  // the wall
        } else if (std::abs(x) < kSeen && std::abs(y) < kSeen && x < kShadowX) {
          scene.samples.free.push_back(ToWorld(x, y, z));
        }
      }
    }
  }
  scene.samples.voxel_size = kVoxel;
  // Two cameras 1.4 m above the floor, image +y (down) along the scene's -z.
  const Eigen::Vector3f down =
      (WorldFromScene().linear() * -Eigen::Vector3d::UnitZ()).cast<float>();
  for (double x : {-0.5, 0.0}) {
    scene.rays.origins.push_back(ToWorld(x, -1.0, 1.4));
    scene.rays.downs.push_back(down);
  }
  return scene;
}

// The cell under scene point (x, y), via the grid's pose in the world.
GridCell CellAt(const OccupancyGrid& grid, double x, double y) {
  const Eigen::Vector4d world = (WorldFromScene() * Eigen::Vector3d(x, y, 0.0)).homogeneous();
  const Eigen::Vector4d g = grid.T_world_grid.inverse() * world;
  int column = 0, row = 0;
  if (!grid.CellOf(g.head<2>(), &column, &row)) return GridCell::kUnknown;
  return grid.At(column, row);
}

TEST(FloorPlane, FindsTheTiltedFloorFromTheCameras) {
  const Scene scene = MakeScene();
  std::vector<Eigen::Vector3f> points;
  for (const DensePoint& p : scene.rays.cloud) points.push_back(p.position);
  const std::optional<FloorPlane> floor =
      FindFloor(points, scene.rays.origins, scene.rays.downs, FloorSearch());
  ASSERT_TRUE(floor.has_value());
  const Eigen::Vector3d up = WorldFromScene().linear() * Eigen::Vector3d::UnitZ();
  EXPECT_GT(floor->up.dot(up), std::cos(0.5 * M_PI / 180.0));
  EXPECT_NEAR(floor->Height(ToWorld(0.3, 0.2, 0.0).cast<double>()), 0.0, 0.005);
  EXPECT_NEAR(floor->Height(ToWorld(0.3, 0.2, 1.4).cast<double>()), 1.4, 0.005);
  // Every floor point, and the box's lowest layer (2.5 cm up, within floorDistance).
  EXPECT_GE(floor->inliers, 80u * 80u);
  EXPECT_LE(floor->inliers, 80u * 80u + 100u);
}

TEST(FloorPlane, NoneWithoutPointsBelowTheCameras) {
  const Scene scene = MakeScene();
  const std::vector<Eigen::Vector3f> above = {ToWorld(0, 0, 2.0), ToWorld(1, 0, 2.0),
                                              ToWorld(0, 1, 2.0)};
  EXPECT_FALSE(FindFloor(above, scene.rays.origins, scene.rays.downs, FloorSearch()));
}

TEST(OccupancyGrid, BoxOccupiedOpenFloorFreeShadowUnknown) {
  const Scene scene = MakeScene();
  const std::optional<GridExport> built =
      BuildOccupancyGrid(scene.rays, scene.samples, GridOptions());
  ASSERT_TRUE(built.has_value());
  const OccupancyGrid& grid = built->grid;
  EXPECT_DOUBLE_EQ(grid.resolution, 0.05);
  // The seen 3 m x 3 m up to the wall (60 x 60 cells) plus about a cell of border.
  EXPECT_GE(grid.width, 60);
  EXPECT_LE(grid.width, 64);
  EXPECT_GE(grid.height, 60);
  EXPECT_LE(grid.height, 64);

  int box = 0, box_occupied = 0, open = 0, open_free = 0, open_occupied = 0, shadow = 0,
      shadow_unknown = 0;
  // Cell centres (the grid frame's cells are aligned to the scene's 5 cm voxels).
  for (int i = -28; i < 28; ++i) {
    for (int j = -28; j < 28; ++j) {
      const double x = Centre(i), y = Centre(j);
      const GridCell cell = CellAt(grid, x, y);
      // 3 cm from the edges: the tilt makes cells straddle them.
      const bool inside_box =
          x > kBoxMin + 0.03 && x < kBoxMax - 0.03 && y > kBoxMin + 0.03 && y < kBoxMax - 0.03;
      const bool near_box =
          x > kBoxMin - 0.08 && x < kBoxMax + 0.08 && y > kBoxMin - 0.08 && y < kBoxMax + 0.08;
      if (inside_box) {
        ++box;
        box_occupied += cell == GridCell::kOccupied;
      } else if (!near_box && x < kShadowX - 0.08) {
        ++open;
        open_free += cell == GridCell::kFree;
        open_occupied += cell == GridCell::kOccupied;
      } else if (x > kShadowX + 0.03 && x < kSeen - 0.08 && !near_box) {
        ++shadow;
        shadow_unknown += cell == GridCell::kUnknown;
      }
    }
  }
  EXPECT_GT(box, 50);
  EXPECT_EQ(box_occupied, box);
  EXPECT_GT(open, 2000);
  EXPECT_EQ(open_free, open);
  EXPECT_EQ(open_occupied, 0);
  EXPECT_GT(shadow, 50);
  EXPECT_EQ(shadow_unknown, shadow);
  // Beyond the seen area: unknown.
  EXPECT_EQ(CellAt(grid, -1.9, 0.0), GridCell::kUnknown);
  EXPECT_EQ(built->occupied_cells, static_cast<std::size_t>(std::count(
                                       grid.cells.begin(), grid.cells.end(), GridCell::kOccupied)));
}

TEST(OccupancyGrid, HeightBandDropsLowAndHighObstacles) {
  Scene scene = MakeScene();
  GridOptions options;
  options.min_obstacle_height = 0.6;  // above the 0.5 m box
  const std::optional<GridExport> built = BuildOccupancyGrid(scene.rays, scene.samples, options);
  ASSERT_TRUE(built.has_value());
  EXPECT_EQ(built->occupied_cells, 60u);  // the wall alone: 3 m of 5 cm cells
  EXPECT_EQ(CellAt(built->grid, 0.775, 0.775), GridCell::kFree);  // seen through above the box
}

TEST(OccupancyGrid, DensePointsKeepAnObstacleWhoseVoxelsRaysCleared) {
  Scene scene = MakeScene();
  // Grazing rays cleared the box's OctoMap voxels: they are free now, its dense points remain.
  std::vector<Eigen::Vector3f> cleared;
  for (const DensePoint& p : scene.rays.cloud) {
    const Eigen::Vector3d q = WorldFromScene().inverse() * p.position.cast<double>();
    if (q.z() > 0.01) cleared.push_back(p.position);
  }
  scene.samples.occupied.erase(
      std::remove_if(scene.samples.occupied.begin(), scene.samples.occupied.end(),
                     [](const Eigen::Vector3f& v) {
                       const Eigen::Vector3d q = WorldFromScene().inverse() * v.cast<double>();
                       return InBox(q.x(), q.y()) && q.z() > 0.0;
                     }),
      scene.samples.occupied.end());
  scene.samples.free.insert(scene.samples.free.end(), cleared.begin(), cleared.end());
  const std::optional<GridExport> built =
      BuildOccupancyGrid(scene.rays, scene.samples, GridOptions());
  ASSERT_TRUE(built.has_value());
  EXPECT_EQ(built->occupied_cells, 160u);  // box 10 x 10 cells and the wall's 60, as before
  EXPECT_EQ(CellAt(built->grid, 0.775, 0.775), GridCell::kOccupied);
}

TEST(OccupancyGridIo, WritesMapServerFilesAndReadsThemBack) {
  const Scene scene = MakeScene();
  const std::filesystem::path folder = drvslam::testing::UniqueTempFolder("drvslam_grid");
  const std::optional<GridExport> written =
      WriteOccupancyGrid(scene.rays, scene.samples, GridOptions(), folder.string());
  ASSERT_TRUE(written.has_value());
  const OccupancyGrid back = ReadMapServerPgm(written->pgm_path, 0.05);
  ASSERT_EQ(back.width, written->grid.width);
  ASSERT_EQ(back.height, written->grid.height);
  EXPECT_TRUE(back.cells == written->grid.cells);

  std::ifstream in(written->yaml_path);
  std::stringstream yaml;
  yaml << in.rdbuf();
  const std::string text = yaml.str();
  for (const char* key : {"image: map.pgm\n", "mode: trinary\n", "resolution: 0.05\n",
                          "negate: 0\n", "occupied_thresh: 0.65\n", "free_thresh: 0.196\n"}) {
    EXPECT_NE(text.find(key), std::string::npos) << key;
  }
  EXPECT_NE(text.find("origin: ["), std::string::npos);
  // drvslam_T_world_grid: 16 numbers, the last row 0 0 0 1.
  const std::size_t start = text.find("drvslam_T_world_grid: [");
  ASSERT_NE(start, std::string::npos);
  std::string numbers = text.substr(start + 23, text.find(']', start) - start - 23);
  for (char& c : numbers) c = c == ',' ? ' ' : c;
  std::istringstream values(numbers);
  std::vector<double> pose;
  for (double v; values >> v;) pose.push_back(v);
  ASSERT_EQ(pose.size(), 16u);
  EXPECT_NEAR(pose[12], 0.0, 1e-12);
  EXPECT_NEAR(pose[15], 1.0, 1e-12);
  for (int i = 0; i < 16; ++i) EXPECT_NEAR(pose[i], written->grid.T_world_grid(i / 4, i % 4), 1e-6);

  // The YAML and its image back as one grid (what drvslam view draws).
  const OccupancyGrid whole = ReadMapServerFiles(written->yaml_path);
  EXPECT_TRUE(whole.cells == written->grid.cells);
  EXPECT_DOUBLE_EQ(whole.resolution, 0.05);
  EXPECT_NEAR(whole.origin.x(), written->grid.origin.x(), 1e-9);
  EXPECT_NEAR(whole.origin.y(), written->grid.origin.y(), 1e-9);
  EXPECT_TRUE(whole.T_world_grid.isApprox(written->grid.T_world_grid, 1e-8));
  std::filesystem::remove_all(folder);
}

TEST(OccupancyGridIo, BadYamlIsAnErrorNamingTheFileAndKey) {
  const std::filesystem::path folder = drvslam::testing::UniqueTempFolder("drvslam_grid");
  const std::string path = (folder / "map.yaml").string();
  const auto message_for = [&](const std::string& yaml) {
    std::ofstream(path) << yaml;
    try {
      ReadMapServerFiles(path);
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  const std::string good_tail =
      "origin: [0, 0, 0.0]\ndrvslam_T_world_grid: [1, 0, 0, 0, 0, 1, 0, "
      "0, 0, 0, 1, 0, 0, 0, 0, 1]\n";
  EXPECT_EQ(message_for("image: map.pgm\n" + good_tail), path + ": no resolution");
  EXPECT_EQ(message_for("image: map.pgm\nresolution: fine\n" + good_tail),
            path + ": resolution is not a number: fine");
  EXPECT_EQ(message_for("image: map.pgm\nresolution: 0.05\norigin: [0, 0, 0.0]\n"
                        "drvslam_T_world_grid: [1, 0, 0]\n"),
            path + ": drvslam_T_world_grid needs 16 numbers");
  EXPECT_NE(
      message_for("image: none.pgm\nresolution: 0.05\n" + good_tail).find("none.pgm: cannot open"),
      std::string::npos);
  std::filesystem::remove_all(folder);
}

TEST(OccupancyGridIo, BadPixelIsAnErrorNamingTheFile) {
  const std::filesystem::path folder = drvslam::testing::UniqueTempFolder("drvslam_grid");
  const std::string path = (folder / "bad.pgm").string();
  {
    std::ofstream out(path, std::ios::binary);
    out << "P5\n2 1\n255\n" << static_cast<char>(0) << static_cast<char>(100);
  }
  try {
    ReadMapServerPgm(path, 0.05);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(path + ": pixel value 100"), std::string::npos)
        << error.what();
  }
  std::filesystem::remove_all(folder);
}

TEST(GridOptions, MaxHeightMustBeAboveMin) {
  GridOptions options;
  options.max_obstacle_height = 0.05;
  EXPECT_THROW(options.Check(), Error);
  options.max_obstacle_height = 0.2;
  EXPECT_NO_THROW(options.Check());
}

}  // namespace
}  // namespace drvslam
