// The occupancy grid in furnished synthetic rooms (furnished_room.h): the floor is the lowest
// credible horizontal plane, not the one with the most points, so a table top, a bed or a desk
// seen better than the floor does not become the grid's plane. Each room's test prints its
// acceptance figures; with DRVSLAM_GRID_PICTURES=DIR it also saves the grid as DIR/ROOM.png.
#include "dense/furnished_room.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "drvslam/dense/grid_export.h"
#include "drvslam/dense/grid_stats_json.h"
#include "drvslam/dense/occupancy_grid_io.h"
#include "test_support/temp_folder.h"

namespace drvslam {
namespace {

using testing::BuildRoom;
using testing::BuiltRoom;
using testing::Furniture;
using testing::PitchedCamera;
using testing::Rect;
using testing::RoomLayout;
using testing::RoomScore;

Eigen::Isometry3d Tilted(double angle_deg, const Eigen::Vector3d& axis) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.rotate(Eigen::AngleAxisd(angle_deg * M_PI / 180.0, axis.normalized()));
  T.pretranslate(Eigen::Vector3d(0.3, -1.2, 0.7));
  return T;
}

// The room: a 1.4 m x 0.6 m table, top at 0.76 m, whose top holds more points than the
// strips of floor around it; people walked along both long sides; a ceiling 2.75 m up (inside
// the obstacle band if the band were counted from the table top). Hand-held cameras at 1.4 m
// look down at the table from four sides.
RoomLayout TableRoom() {
  RoomLayout room;
  room.seen_floor = {{-1.2, -0.8, 1.2, 0.8}};
  room.furniture = {{"table", {-0.7, -0.3, 0.7, 0.3}, 0.76, true}};
  room.lanes = {{-1.1, 0.5, 1.1, 0.75}, {-1.1, -0.75, 1.1, -0.5}};
  room.cameras = {PitchedCamera({0, -1.3, 1.4}, Eigen::Vector3d::UnitY(), 45),
                  PitchedCamera({0, 1.3, 1.4}, -Eigen::Vector3d::UnitY(), 45),
                  PitchedCamera({-1.3, 0, 1.4}, Eigen::Vector3d::UnitX(), 45),
                  PitchedCamera({1.3, 0, 1.4}, -Eigen::Vector3d::UnitX(), 45)};
  room.world_from_scene = Tilted(25.0, Eigen::Vector3d::UnitX());
  return room;
}

// A bed (top 0.5 m, 2 m x 1.5 m) and a low couch (seat 0.42 m), both solid to the floor; the
// bed's top holds more points than the floor. Lanes between them and beside the bed.
RoomLayout BedroomWithCouch() {
  RoomLayout room;
  room.seen_floor = {{-2.0, -1.8, 2.0, 1.9}};
  room.furniture = {{"bed", {-1.6, 0.2, 0.4, 1.7}, 0.5, false},
                    {"couch", {0.9, -1.7, 1.9, -0.9}, 0.42, false}};
  room.lanes = {{-1.9, -0.7, 0.7, -0.35}, {0.6, 0.0, 1.0, 1.8}};
  room.cameras = {PitchedCamera({0, -1.0, 1.5}, {-0.5, 1, 0}, 40),
                  PitchedCamera({1.5, 0.5, 1.5}, -Eigen::Vector3d::UnitX(), 35),
                  PitchedCamera({-1.0, -1.2, 1.5}, Eigen::Vector3d::UnitY(), 30)};
  room.world_from_scene = Tilted(40.0, {1, 1, 0.3});
  return room;
}

// The table room seen by cameras all on one side, pitched 30 degrees down: their mean image
// +y axis is 30 degrees off the true down, and the world frame is the first camera's.
RoomLayout TableRoomPitched30() {
  RoomLayout room = TableRoom();
  room.cameras.clear();
  for (double x : {-0.6, -0.2, 0.2, 0.6}) {
    room.cameras.push_back(PitchedCamera({x, -1.4, 1.4}, Eigen::Vector3d::UnitY(), 30));
  }
  // The first camera's axes in the scene: x right, y down (image +y), z forward.
  const double pitch = 30.0 * M_PI / 180.0;
  Eigen::Isometry3d camera_in_scene = Eigen::Isometry3d::Identity();
  camera_in_scene.linear().col(0) = Eigen::Vector3d::UnitX();
  camera_in_scene.linear().col(1) = room.cameras.front().down;
  camera_in_scene.linear().col(2) = Eigen::Vector3d(0, std::cos(pitch), -std::sin(pitch));
  camera_in_scene.translation() = room.cameras.front().centre;
  room.world_from_scene = camera_in_scene.inverse();
  return room;
}

// A 2 m x 0.8 m desk (top 0.74 m) in front of which the floor was seen only as a strip 0.5 m
// wide: the desk holds seven times the floor's points. People walked along the strip.
RoomLayout DeskWithFloorStrip() {
  RoomLayout room;
  room.seen_floor = {{-1.2, -0.95, 1.2, -0.45}};
  room.furniture = {{"desk", {-1.0, -0.4, 1.0, 0.4}, 0.74, true}};
  room.lanes = {{-1.1, -0.85, 1.1, -0.62}};
  for (double x : {-0.5, 0.0, 0.5}) {
    room.cameras.push_back(PitchedCamera({x, -1.5, 1.3}, Eigen::Vector3d::UnitY(), 35));
  }
  room.world_from_scene = Tilted(15.0, {0.2, 1, 0});
  return room;
}

double MeanCameraHeight(const RoomLayout& room) {
  double sum = 0.0;
  for (const testing::Camera& c : room.cameras) sum += c.centre.z();
  return sum / static_cast<double>(room.cameras.size());
}

// Builds the room's grid, prints and records its acceptance figures, saves its picture, and
// asserts them: the plane within 3 cm of the floor, the furniture's seen footprint at least
// half occupied, nothing occupied where people walked or on open floor.
void ExpectRightGrid(const std::string& name, const RoomLayout& room) {
  const BuiltRoom built = BuildRoom(room);
  FloorChoice choice;
  const std::optional<GridExport> grid =
      BuildOccupancyGrid(built.rays, built.samples, GridOptions(), &choice);
  ASSERT_TRUE(grid.has_value()) << choice.reason;
  const RoomScore score = testing::ScoreGrid(room, grid->grid);
  const FloorCandidate& floor = *choice.Floor();
  std::size_t most = 0;
  for (const FloorCandidate& c : choice.candidates) most = std::max(most, c.plane.inliers);
  std::ostringstream line;
  line << name << ": plane error " << score.floor_error * 100.0 << " cm; floor "
       << floor.depth_below_camera << " m below the cameras (true " << MeanCameraHeight(room)
       << "), " << floor.plane.inliers << " points (most in one plane: " << most
       << "); footprint occupied " << score.footprint_occupied << " of " << score.footprint_cells
       << " (" << 100.0 * score.FootprintShare() << " %); lanes occupied " << score.lane_occupied
       << " of " << score.lane_cells << "; open floor occupied " << score.open_occupied << " of "
       << score.open_cells;
  const std::string picture = testing::SaveGridPicture(grid->grid, name);
  if (!picture.empty()) line << "; picture " << picture;
  std::cout << "[ room     ] " << line.str() << std::endl;
  ::testing::Test::RecordProperty("acceptance", line.str());

  EXPECT_LT(score.floor_error, 0.03);
  EXPECT_NEAR(floor.depth_below_camera, MeanCameraHeight(room), 0.03);
  EXPECT_GT(score.footprint_cells, 50);
  EXPECT_GE(score.FootprintShare(), 0.5);
  EXPECT_GT(score.lane_cells, 50);
  EXPECT_EQ(score.lane_occupied, 0);
  EXPECT_GT(score.open_cells, 20);
  EXPECT_EQ(score.open_occupied, 0);
}

TEST(FurnishedRoom, TableTopWithMorePointsThanTheFloor) {
  ExpectRightGrid("table_room", TableRoom());
}

TEST(FurnishedRoom, LowBedAndCouch) { ExpectRightGrid("bed_and_couch", BedroomWithCouch()); }

TEST(FurnishedRoom, CamerasPitched30DegreesDown) {
  ExpectRightGrid("table_room_pitched_30", TableRoomPitched30());
}

TEST(FurnishedRoom, FloorSeenOnlyAsAStrip) {
  ExpectRightGrid("desk_with_floor_strip", DeskWithFloorStrip());
}

// The rooms are what the issue describes: the strongest plane is the furniture, not the floor.
TEST(FurnishedRoom, TheFurnitureHoldsMorePointsThanTheFloor) {
  for (const RoomLayout& room : {TableRoom(), BedroomWithCouch(), DeskWithFloorStrip()}) {
    const BuiltRoom built = BuildRoom(room);
    const FloorChoice choice = ChooseGridFloor(built.rays, GridOptions());
    ASSERT_NE(choice.Floor(), nullptr) << choice.reason;
    const std::vector<FloorCandidate> others = choice.RunnersUp();
    ASSERT_FALSE(others.empty());
    EXPECT_GT(others.front().plane.inliers, choice.Floor()->plane.inliers);
    EXPECT_LT(others.front().depth_below_camera, choice.Floor()->depth_below_camera - 0.4);
  }
}

// Points of `scene` rectangle `r` at height z, `step` apart, into the room's cloud.
void AddPatch(const RoomLayout& room, const Rect& r, double z, double step, BuiltRoom* built) {
  for (double x = r.x0; x < r.x1; x += step) {
    for (double y = r.y0; y < r.y1; y += step) {
      DensePoint p;
      p.position = (room.world_from_scene * Eigen::Vector3d(x, y, z)).cast<float>();
      built->rays.cloud.push_back(p);
    }
  }
}

TEST(FurnishedRoom, AThinStripOrANoisePatchBelowTheFloorDoesNotWin) {
  const RoomLayout room = TableRoom();
  BuiltRoom built = BuildRoom(room);
  // A line of reflections 0.2 m under the floor (2 m x 3 cm) and a dense noise patch 0.3 m
  // under it (0.3 m x 0.3 m), each with as many points as the floor has.
  AddPatch(room, {-1.0, -0.6, 1.0, -0.57}, -0.2, 0.004, &built);
  AddPatch(room, {-1.0, 0.3, -0.7, 0.6}, -0.3, 0.006, &built);
  const FloorChoice choice = ChooseGridFloor(built.rays, GridOptions());
  ASSERT_NE(choice.Floor(), nullptr) << choice.reason;
  EXPECT_NEAR(choice.Floor()->depth_below_camera, 1.4, 0.03);
  int deeper = 0;
  for (const FloorCandidate& c : choice.RunnersUp()) {
    if (c.depth_below_camera > 1.55) {
      ++deeper;
      EXPECT_FALSE(c.credible) << c.depth_below_camera << " m, " << c.area << " m^2, " << c.width
                               << " m wide";
    }
  }
  EXPECT_EQ(deeper, 2);
}

TEST(FurnishedRoom, NoCredibleFloorNoGridWithTheReason) {
  RoomLayout room;
  room.seen_floor = {{-0.2, -0.2, 0.2, 0.2}};  // 0.16 m^2 of floor and nothing else below
  room.walls = false;
  room.cameras = {PitchedCamera({0, -1.0, 1.4}, Eigen::Vector3d::UnitY(), 45)};
  room.world_from_scene = Tilted(25.0, Eigen::Vector3d::UnitX());
  const BuiltRoom built = BuildRoom(room);
  FloorChoice choice;
  EXPECT_FALSE(BuildOccupancyGrid(built.rays, built.samples, GridOptions(), &choice));
  EXPECT_EQ(choice.Floor(), nullptr);
  EXPECT_NE(choice.reason.find("credible"), std::string::npos) << choice.reason;
  EXPECT_NE(choice.reason.find("1.40 m"), std::string::npos) << choice.reason;
}

// A robot's camera 0.6 m up, beside a sunken area 0.35 m below the floor (a lower level seen
// through an opening) that is larger than the floor it stands on: the lowest credible plane is
// the sunken one; Grid.cameraHeight picks the robot's floor.
RoomLayout RobotBesideASunkenArea() {
  RoomLayout room;
  room.seen_floor = {{-2.0, -1.5, 2.0, 1.8}};
  room.furniture = {{"sunken area", {-2.0, 0.2, 2.0, 1.8}, -0.35, false},
                    {"table", {-1.0, -1.3, 0.2, -0.7}, 0.45, true}};
  for (double x : {-0.5, 0.0, 0.5}) {
    room.cameras.push_back(PitchedCamera({x, -1.4, 0.6}, Eigen::Vector3d::UnitY(), 15));
  }
  room.world_from_scene = Tilted(10.0, Eigen::Vector3d::UnitX());
  return room;
}

TEST(FurnishedRoom, CameraHeightPicksTheRobotsFloor) {
  const BuiltRoom built = BuildRoom(RobotBesideASunkenArea());
  GridOptions options;
  const FloorChoice lowest = ChooseGridFloor(built.rays, options);
  ASSERT_NE(lowest.Floor(), nullptr) << lowest.reason;
  EXPECT_NEAR(lowest.Floor()->depth_below_camera, 0.95, 0.03);  // the rule's failure mode
  options.camera_height = 0.62;
  const FloorChoice robot = ChooseGridFloor(built.rays, options);
  ASSERT_NE(robot.Floor(), nullptr) << robot.reason;
  EXPECT_NEAR(robot.Floor()->depth_below_camera, 0.6, 0.03);
}

TEST(FurnishedRoom, CameraHeightWithNoPlaneNearItGivesNoGrid) {
  const BuiltRoom built = BuildRoom(RobotBesideASunkenArea());
  GridOptions options;
  options.camera_height = 0.8;  // 0.2 m from the floor, 0.15 m from the sunken area
  FloorChoice choice;
  EXPECT_FALSE(BuildOccupancyGrid(built.rays, built.samples, options, &choice));
  EXPECT_NE(choice.reason.find("Grid.cameraHeight (0.80 m)"), std::string::npos) << choice.reason;
}

TEST(FloorChoice, CloseInSupportNamesTwoCredibleCandidatesWithinAFifth) {
  FloorChoice choice;
  for (std::size_t inliers : {1000u, 850u, 5000u}) {
    FloorCandidate c;
    c.plane.inliers = inliers;
    c.credible = inliers < 2000;  // the 5000-point plane is not credible
    choice.candidates.push_back(c);
  }
  const auto close = choice.CloseInSupport();
  ASSERT_TRUE(close.has_value());
  EXPECT_EQ(close->first.plane.inliers, 1000u);
  EXPECT_EQ(close->second.plane.inliers, 850u);
  choice.candidates[1].plane.inliers = 700;
  EXPECT_FALSE(choice.CloseInSupport().has_value());
}

TEST(FurnishedRoom, MapYamlAndStatsCarryTheFloorAndTheRunnersUp) {
  const RoomLayout room = TableRoom();
  const BuiltRoom built = BuildRoom(room);
  const std::filesystem::path folder = drvslam::testing::UniqueTempFolder("drvslam_room");
  FloorChoice choice;
  const std::optional<GridExport> written =
      WriteOccupancyGrid(built.rays, built.samples, GridOptions(), folder.string(), &choice);
  ASSERT_TRUE(written.has_value());
  std::ifstream in(written->yaml_path);
  std::stringstream text;
  text << in.rdbuf();
  std::map<std::string, std::string> keys;
  for (std::string line; std::getline(text, line);) {
    const std::size_t colon = line.find(": ");
    if (line.rfind("drvslam_floor_", 0) == 0) keys[line.substr(0, colon)] = line.substr(colon + 2);
  }
  ASSERT_EQ(keys.size(), 4u);
  EXPECT_NEAR(std::stod(keys["drvslam_floor_depth_below_camera"]), 1.4, 0.03);
  EXPECT_EQ(keys["drvslam_floor_inliers"], std::to_string(choice.Floor()->plane.inliers));
  const std::vector<FloorCandidate> others = choice.RunnersUp();
  ASSERT_FALSE(others.empty());
  EXPECT_EQ(keys["drvslam_floor_runner_up_depths"].rfind("[0.6", 0), 0u)
      << keys["drvslam_floor_runner_up_depths"];  // the table top, 0.64 m below the cameras
  EXPECT_EQ(keys["drvslam_floor_runner_up_inliers"].rfind(
                "[" + std::to_string(others.front().plane.inliers), 0),
            0u);
  // map_server's keys and the grid still read back.
  EXPECT_TRUE(ReadMapServerFiles(written->yaml_path).cells == written->grid.cells);

  const nlohmann::json json = GridStatsJson(choice, &*written);
  EXPECT_TRUE(json["written"].get<bool>());
  EXPECT_TRUE(json["reason"].is_null());
  EXPECT_NEAR(json["floor"]["depth_below_camera_m"].get<double>(), 1.4, 0.03);
  EXPECT_EQ(json["floor"]["inliers"].get<std::size_t>(), choice.Floor()->plane.inliers);
  ASSERT_EQ(json["runners_up"].size(), others.size());
  EXPECT_NEAR(json["runners_up"][0]["depth_below_camera_m"].get<double>(), 0.64, 0.03);
  EXPECT_EQ(json["occupied_cells"].get<std::size_t>(), written->occupied_cells);
  std::filesystem::remove_all(folder);
}

TEST(FurnishedRoom, StatsSayWhyThereIsNoGrid) {
  FloorChoice none;
  none.reason = "no camera poses";
  const nlohmann::json json = GridStatsJson(none, nullptr);
  EXPECT_FALSE(json["written"].get<bool>());
  EXPECT_EQ(json["reason"], "no camera poses");
  EXPECT_TRUE(json["floor"].is_null());
  EXPECT_TRUE(json["runners_up"].empty());
  EXPECT_FALSE(json.contains("occupied_cells"));
}

}  // namespace
}  // namespace drvslam
