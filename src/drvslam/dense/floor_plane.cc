#include "drvslam/dense/floor_plane.h"

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <cmath>

#include "drvslam/dense/floor_candidates.h"

namespace drvslam {
namespace {

Eigen::Vector3d MeanOf(const std::vector<Eigen::Vector3f>& vectors) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3f& v : vectors) sum += v.cast<double>();
  return vectors.empty() ? sum : Eigen::Vector3d(sum / static_cast<double>(vectors.size()));
}

// Points at least min_depth_below_camera below `camera` along `up`: not the ceiling.
std::vector<Eigen::Vector3d> Below(const std::vector<Eigen::Vector3f>& points,
                                   const Eigen::Vector3d& camera, const Eigen::Vector3d& up,
                                   const FloorSearch& search) {
  std::vector<Eigen::Vector3d> below;
  for (const Eigen::Vector3f& p : points) {
    const Eigen::Vector3d q = p.cast<double>();
    if (up.dot(camera - q) >= search.min_depth_below_camera) below.push_back(q);
  }
  return below;
}

int Strongest(const std::vector<FloorCandidate>& candidates) {
  int strongest = 0;
  for (int i = 1; i < static_cast<int>(candidates.size()); ++i) {
    if (candidates[i].plane.inliers > candidates[strongest].plane.inliers) strongest = i;
  }
  return strongest;
}

// Sets `credible` (FloorSearch says why each threshold is what it is).
void Judge(const FloorSearch& search, std::vector<FloorCandidate>* candidates) {
  const std::size_t most = (*candidates)[Strongest(*candidates)].plane.inliers;
  for (FloorCandidate& c : *candidates) {
    c.credible = c.plane.inliers >= search.min_inliers &&
                 c.plane.inliers >= search.min_support_share * most && c.area >= search.min_area &&
                 c.width >= search.min_width;
  }
}

// The lowest credible candidate; within same_surface_gap of it, the strongest. -1: none.
int LowestCredible(const FloorSearch& search, const std::vector<FloorCandidate>& candidates) {
  int lowest = -1;
  for (int i = 0; i < static_cast<int>(candidates.size()); ++i) {
    if (!candidates[i].credible) continue;
    if (lowest < 0 || candidates[i].depth_below_camera > candidates[lowest].depth_below_camera) {
      lowest = i;
    }
  }
  if (lowest < 0) return -1;
  int chosen = lowest;
  for (int i = 0; i < static_cast<int>(candidates.size()); ++i) {
    const double gap =
        std::abs(candidates[i].depth_below_camera - candidates[lowest].depth_below_camera);
    if (candidates[i].credible && gap < search.same_surface_gap &&
        candidates[i].plane.inliers > candidates[chosen].plane.inliers) {
      chosen = i;
    }
  }
  return chosen;
}

// The candidate nearest camera_height below the cameras, within its tolerance; -1: none.
int NearestCameraHeight(const FloorSearch& search, const std::vector<FloorCandidate>& candidates) {
  int nearest = -1;
  double nearest_error = search.camera_height_tolerance;
  for (int i = 0; i < static_cast<int>(candidates.size()); ++i) {
    const double error = std::abs(candidates[i].depth_below_camera - search.camera_height);
    if (error <= nearest_error) {
      nearest = i;
      nearest_error = error;
    }
  }
  return nearest;
}

std::string Depths(const std::vector<FloorCandidate>& candidates) {
  std::string list;
  for (const FloorCandidate& c : candidates) {
    list +=
        fmt::format("{}{:.2f} m ({} points, {:.2f} m^2, {:.2f} m wide)", list.empty() ? "" : ", ",
                    c.depth_below_camera, c.plane.inliers, c.area, c.width);
  }
  return list;
}

std::string NoneChosenReason(const FloorSearch& search,
                             const std::vector<FloorCandidate>& candidates) {
  if (search.camera_height > 0.0) {
    return fmt::format(
        "no horizontal plane lies within {:.2f} m of Grid.cameraHeight ({:.2f} m) below the "
        "cameras; found at {}",
        search.camera_height_tolerance, search.camera_height, Depths(candidates));
  }
  return fmt::format(
      "no horizontal plane below the cameras is credible as the floor (it needs {:.0f} % of the "
      "strongest plane's points, {:.2f} m^2 and {:.2f} m of width); found at {}",
      100.0 * search.min_support_share, search.min_area, search.min_width, Depths(candidates));
}

}  // namespace

std::vector<FloorCandidate> FloorChoice::RunnersUp() const {
  std::vector<FloorCandidate> others;
  for (int i = 0; i < static_cast<int>(candidates.size()); ++i) {
    if (i != chosen) others.push_back(candidates[i]);
  }
  std::stable_sort(others.begin(), others.end(),
                   [](const FloorCandidate& a, const FloorCandidate& b) {
                     return a.plane.inliers > b.plane.inliers;
                   });
  return others;
}

std::optional<std::pair<FloorCandidate, FloorCandidate>> FloorChoice::CloseInSupport() const {
  std::vector<FloorCandidate> credible;
  for (const FloorCandidate& c : candidates) {
    if (c.credible) credible.push_back(c);
  }
  std::stable_sort(credible.begin(), credible.end(),
                   [](const FloorCandidate& a, const FloorCandidate& b) {
                     return a.plane.inliers > b.plane.inliers;
                   });
  if (credible.size() < 2 || credible[1].plane.inliers < 0.8 * credible[0].plane.inliers) {
    return std::nullopt;
  }
  return std::make_pair(credible[0], credible[1]);
}

FloorChoice ChooseFloor(const std::vector<Eigen::Vector3f>& points,
                        const std::vector<Eigen::Vector3f>& camera_centres,
                        const std::vector<Eigen::Vector3f>& camera_downs,
                        const FloorSearch& search) {
  FloorChoice choice;
  if (camera_centres.empty() || camera_downs.empty()) {
    choice.reason = "no camera poses";
    return choice;
  }
  const Eigen::Vector3d down_sum = MeanOf(camera_downs);
  if (down_sum.norm() < 1e-6) {
    choice.reason = "the cameras' down directions cancel out: no up to find a floor against";
    return choice;
  }
  const Eigen::Vector3d camera = MeanOf(camera_centres);
  const Eigen::Vector3d cameras_up = -down_sum.normalized();
  // The cameras' mean image up is off the true up by their mean pitch (tens of degrees for a
  // camera looking down at a table): it only finds the strongest near-horizontal plane, which is
  // level (a floor or a table top). The candidates are then searched against that plane's
  // normal, within max_parallel_deg of it: sloped surfaces and walls are no candidates, and the
  // cameras' pitch no longer hides far parts of the room from "below the cameras".
  FloorSearch first = search;
  first.max_candidates = 1;
  const std::vector<FloorCandidate> strongest =
      HorizontalPlanes(Below(points, camera, cameras_up, search), cameras_up, camera, first);
  if (!strongest.empty()) {
    const Eigen::Vector3d level_up = strongest.front().plane.up;
    FloorSearch level = search;
    level.max_tilt_deg = search.max_parallel_deg;
    choice.candidates =
        HorizontalPlanes(Below(points, camera, level_up, search), level_up, camera, level);
  }
  if (choice.candidates.empty()) {
    choice.reason = fmt::format(
        "no horizontal plane of {} dense points lies {:.2f} m or more below the cameras",
        search.min_inliers, search.min_depth_below_camera);
    return choice;
  }
  Judge(search, &choice.candidates);
  choice.chosen = search.camera_height > 0.0 ? NearestCameraHeight(search, choice.candidates)
                                             : LowestCredible(search, choice.candidates);
  if (choice.chosen < 0) choice.reason = NoneChosenReason(search, choice.candidates);
  return choice;
}

std::optional<FloorPlane> FindFloor(const std::vector<Eigen::Vector3f>& points,
                                    const std::vector<Eigen::Vector3f>& camera_centres,
                                    const std::vector<Eigen::Vector3f>& camera_downs,
                                    const FloorSearch& search) {
  const FloorChoice choice = ChooseFloor(points, camera_centres, camera_downs, search);
  if (const FloorCandidate* floor = choice.Floor()) return floor->plane;
  return std::nullopt;
}

}  // namespace drvslam
