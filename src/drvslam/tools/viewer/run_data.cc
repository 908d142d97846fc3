#include "drvslam/tools/viewer/run_data.h"

#include <filesystem>
#include <fstream>

#include "drvslam/core/error.h"
#include "drvslam/dense/occupancy_grid_io.h"
#include "drvslam/dense/point_cloud_io.h"
#include "drvslam/io/trajectory_io.h"
#include "drvslam/tools/viewer/frame_events.h"
#include "drvslam/tools/viewer/viewer_json.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

nlohmann::json ReadJsonFile(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw Error(path.string() + ": cannot open");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& error) {
    throw Error(path.string() + ": not valid JSON (" + error.what() + ")");
  }
}

// The ground truth the options name, else the one beside the run's dataset; empty when none.
std::string GroundTruthPath(const RunDataOptions& options, const nlohmann::json& stats) {
  if (!options.ground_truth.empty()) {
    if (!fs::is_regular_file(options.ground_truth)) {
      throw Error("--ground-truth " + options.ground_truth + ": no such file");
    }
    return options.ground_truth;
  }
  if (!stats.contains("dataset") || !stats["dataset"].is_string()) return "";
  const fs::path candidate = fs::path(stats["dataset"].get<std::string>()) / "groundtruth.txt";
  return fs::is_regular_file(candidate) ? candidate.string() : "";
}

}  // namespace

std::vector<std::string> MissingRunFiles(const std::string& run_dir) {
  std::vector<std::string> missing;
  for (const char* name : kRequiredRunFiles) {
    if (!fs::is_regular_file(fs::path(run_dir) / name)) missing.push_back(name);
  }
  return missing;
}

nlohmann::json LoadRunData(const std::string& run_dir, const RunDataOptions& options) {
  const fs::path dir(run_dir);
  if (!fs::is_directory(dir)) throw Error(run_dir + ": no such run folder");
  const std::vector<std::string> missing = MissingRunFiles(run_dir);
  if (!missing.empty()) {
    std::string list;
    for (const std::string& name : missing) list += (list.empty() ? "" : ", ") + name;
    throw Error(run_dir + ": not the output of drvslam run; missing " + list);
  }
  nlohmann::json data;
  data["mode"] = options.mode;
  data["title"] = fs::absolute(dir).lexically_normal().filename().string();
  const nlohmann::json stats = ReadJsonFile(dir / "stats.json");
  data["stats"] = stats;
  const Trajectory trajectory =
      ReadTumTrajectory((dir / "CameraTrajectory.txt").string(), /*allow_empty=*/true);
  data["trajectory"] = TrajectoryJson(trajectory);
  nlohmann::json notes = nlohmann::json::array();
  const fs::path keyframes = dir / "KeyFrameTrajectory.txt";
  data["keyframes"] = fs::is_regular_file(keyframes)
                          ? TrajectoryJson(ReadTumTrajectory(keyframes.string(), true))
                          : nlohmann::json::array();
  const fs::path sparse = dir / "sparse_map.ply";
  if (fs::is_regular_file(sparse)) {
    const DenseCloud points = ReadPlyCloud(sparse.string());
    data["sparse"] = CloudJson(points, points.size(), /*with_colors=*/false);
  } else {
    notes.push_back("no sparse_map.ply in this run (written by drvslam run since the viewer)");
  }
  const fs::path dense = dir / "dense_map.ply";
  if (fs::is_regular_file(dense)) {
    const DenseCloud cloud = ReadPlyCloud(dense.string());
    data["dense"] = CloudJson(Decimate(cloud, options.dense_budget), cloud.size(), true);
  }
  // The grid is drawn under the trajectory; one that cannot be read is said, not fatal: the rest
  // of the run is still worth seeing.
  const fs::path grid = dir / "map.yaml";
  if (fs::is_regular_file(grid)) {
    try {
      data["grid"] = GridJson(ReadMapServerFiles(grid.string()));
    } catch (const Error& error) {
      notes.push_back(std::string("occupancy grid not drawn: ") + error.what());
    }
  }
  data["loops"] = stats.contains("loop") && stats["loop"].contains("loops")
                      ? stats["loop"]["loops"]
                      : nlohmann::json::array();
  const fs::path frame_log = dir / kFrameLogFile;
  if (fs::is_regular_file(frame_log)) {
    data["events"] = ReadFrameEvents(frame_log.string());
  } else {
    notes.push_back(std::string("no ") + kFrameLogFile +
                    " in this run: the error plot shows no events (drvslam benchmark writes it; "
                    "drvslam run writes it with --frame-log)");
  }
  const std::string truth_path = GroundTruthPath(options, stats);
  if (!truth_path.empty() && !trajectory.empty()) {
    std::string why;
    const std::optional<TruthOverlay> overlay =
        OverlayTruth(ReadTumTrajectory(truth_path), trajectory, &why);
    if (overlay) {
      data["ground_truth"] = overlay->ground_truth;
      data["errors"] = overlay->errors;
      data["ate"] = {{"rmse", overlay->rmse}, {"matched", overlay->matched}, {"file", truth_path}};
    } else {
      notes.push_back("ground truth " + truth_path + " not drawn: " + why);
    }
  }
  data["notes"] = notes;
  return data;
}

}  // namespace drvslam
