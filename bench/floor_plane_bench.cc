// The occupancy grid's floor search (FindFloor) on a run's dense map, or on a synthetic room.
// DRVSLAM_BENCH_RUN=FOLDER names a `drvslam run --out FOLDER` with the dense map on: its
// dense_map.ply and KeyFrameTrajectory.txt (TUM) are read, each keyframe's camera centre and image
// +y axis feed the search as ExportDenseMap feeds it. Without it: a 4 m x 4 m room at 2 cm with a
// ceiling and a table whose top holds more points than the floor.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "drvslam/dense/floor_plane.h"
#include "drvslam/dense/point_cloud_io.h"
#include "drvslam/io/trajectory_io.h"

namespace drvslam {
namespace {

struct FloorInput {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> centres;
  std::vector<Eigen::Vector3f> downs;
};

FloorInput FromRun(const std::string& folder) {
  namespace fs = std::filesystem;
  FloorInput input;
  for (const DensePoint& p : ReadPlyCloud((fs::path(folder) / "dense_map.ply").string())) {
    input.points.push_back(p.position);
  }
  for (const StampedPose& pose :
       ReadTumTrajectory((fs::path(folder) / "KeyFrameTrajectory.txt").string())) {
    input.centres.push_back(pose.T_wc.Translation().cast<float>());
    input.downs.push_back((pose.T_wc.Rotation() * Eigen::Vector3d::UnitY()).cast<float>());
  }
  return input;
}

// Scene z up; cameras (image +y along -z) 1.4 m above the floor.
FloorInput SyntheticRoom() {
  FloorInput input;
  constexpr double kStep = 0.02;
  for (double x = -2.0; x < 2.0; x += kStep) {
    for (double y = -2.0; y < 2.0; y += kStep) {
      // Floor seen in strips 0.3 m wide along the table's long sides, the ceiling everywhere.
      if (std::abs(y) >= 0.3 && std::abs(y) < 0.6) input.points.emplace_back(x, y, 0.0f);
      input.points.emplace_back(x, y, 2.8f);
    }
  }
  // The table top at 0.75 m (1.4 m x 0.6 m), sampled four times as densely as the floor: 8400
  // points against the floor's 6000.
  for (double x = -0.7; x < 0.7; x += kStep / 2) {
    for (double y = -0.3; y < 0.3; y += kStep / 2) input.points.emplace_back(x, y, 0.75f);
  }
  for (double x = -1.0; x <= 1.0; x += 0.25) {
    input.centres.emplace_back(x, -1.2f, 1.4f);
    input.downs.emplace_back(0.0f, 0.0f, -1.0f);
  }
  return input;
}

const FloorInput& Input() {
  static const FloorInput input = [] {
    const char* run = std::getenv("DRVSLAM_BENCH_RUN");
    return run != nullptr ? FromRun(run) : SyntheticRoom();
  }();
  return input;
}

void BM_FindFloor(benchmark::State& state) {
  const FloorInput& input = Input();
  std::size_t inliers = 0;
  double depth = 0.0;  // of the floor below the mean camera centre
  for (auto _ : state) {
    const std::optional<FloorPlane> floor =
        FindFloor(input.points, input.centres, input.downs, FloorSearch());
    inliers = floor ? floor->inliers : 0;
    benchmark::DoNotOptimize(inliers);
    if (floor) {
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (const Eigen::Vector3f& c : input.centres) mean += c.cast<double>();
      depth = floor->Height(mean / static_cast<double>(input.centres.size()));
    }
  }
  state.counters["points"] = static_cast<double>(input.points.size());
  state.counters["cameras"] = static_cast<double>(input.centres.size());
  state.counters["floor_inliers"] = static_cast<double>(inliers);
  state.counters["floor_depth_m"] = depth;
}
BENCHMARK(BM_FindFloor)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace drvslam

BENCHMARK_MAIN();
