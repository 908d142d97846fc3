#include "drvslam/dense/grid_stats_json.h"

namespace drvslam {
namespace {

nlohmann::json CandidateJson(const FloorCandidate& c) {
  return {{"depth_below_camera_m", c.depth_below_camera},
          {"inliers", c.plane.inliers},
          {"area_m2", c.area},
          {"width_m", c.width}};
}

}  // namespace

nlohmann::json GridStatsJson(const FloorChoice& floor, const GridExport* grid) {
  nlohmann::json json;
  json["written"] = grid != nullptr;
  json["reason"] = floor.reason.empty() ? nlohmann::json(nullptr) : nlohmann::json(floor.reason);
  json["floor"] = floor.Floor() ? CandidateJson(*floor.Floor()) : nlohmann::json(nullptr);
  nlohmann::json others = nlohmann::json::array();
  for (const FloorCandidate& c : floor.RunnersUp()) {
    nlohmann::json other = CandidateJson(c);
    other["credible"] = c.credible;
    others.push_back(other);
  }
  json["runners_up"] = others;
  if (grid) {
    json["width"] = grid->grid.width;
    json["height"] = grid->grid.height;
    json["resolution"] = grid->grid.resolution;
    json["occupied_cells"] = grid->occupied_cells;
    json["free_cells"] = grid->free_cells;
  }
  return json;
}

}  // namespace drvslam
