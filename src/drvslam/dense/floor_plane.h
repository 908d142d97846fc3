// ChooseFloor: the floor of a dense map, for the 2-D occupancy grid. Horizontal planes below the
// cameras are found one after another (floor_candidates.h); the floor is the lowest of them that
// is credible - enough points and a real area - not the one with the most points, which in a
// furnished room seen by a hand-held camera is often a table top. With a known camera height
// (a camera fixed on a robot) the plane at that depth below the cameras is the floor instead.
// The cameras' orientation rather than the world frame's axes decides what is down (the
// trajectory's world frame is the first camera's, pitched however it was held), refined by the
// strongest plane found: floors and table tops are level.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace drvslam {

struct FloorPlane {
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();  // unit normal, pointing to the cameras
  double offset = 0.0;                            // up . p + offset = height of p above it
  std::size_t inliers = 0;

  double Height(const Eigen::Vector3d& p) const { return up.dot(p) + offset; }
};

// One horizontal plane found below the cameras.
struct FloorCandidate {
  FloorPlane plane;
  double depth_below_camera = 0.0;  // metres from the mean camera centre down to the plane
  double area = 0.0;                // m^2 of FloorSearch::area_cell squares its inliers touch
  double width = 0.0;               // metres: its area over its length (a mean width)
  bool credible = false;            // may be the floor without a camera height
};

struct FloorSearch {
  double inlier_distance = 0.03;        // metres
  double max_tilt_deg = 45.0;           // normal against the cameras' mean up
  double min_depth_below_camera = 0.3;  // metres below the mean camera centre
  int iterations = 400;                 // RANSAC hypotheses per candidate
  std::size_t min_inliers = 50;         // fewer points are no candidate at all
  // Depth noise spreads a surface's points beyond inlier_distance; points this many
  // inlier_distances from a found plane belong to it and cannot make a second candidate.
  double removal_bands = 3.0;
  // Room surfaces worth telling apart (floor, seats, beds, tables, shelves, pieces of them) are
  // few; planes found after that many are clutter.
  int max_candidates = 10;
  // Candidates lie within this angle of the level: the normal of the strongest plane within
  // max_tilt_deg of the cameras' up. Floors, seats and table tops are level to within a few
  // degrees, and so are their fits; a plane tilted more is a ramp, a backrest or a mixed fit.
  double max_parallel_deg = 10.0;
  // Credible: a floor the cameras saw holds at least this share of the strongest plane's
  // points (sparse planes below the floor come from reflections and depth outliers) ...
  double min_support_share = 0.05;
  // ... covers this much area (a few times a small robot's footprint; noise patches cover less)
  double min_area = 0.5;   // m^2
  double area_cell = 0.1;  // m: area is counted in squares of this edge, whatever the density
  // ... and is this wide on average: a line of edge pixels, a skirting board or a slice
  // through walls is long but no floor.
  double min_width = 0.3;  // m
  // Credible candidates closer in height than this are one surface split by drift or noise
  // (the grid's obstacle band cannot tell them apart): the stronger one stands for both.
  double same_surface_gap = 0.1;  // m
  // A camera fixed on a robot: its height above the floor (0: not given) and how far the floor
  // may lie from it (the mean camera centre wobbles with the robot, tracking and depth noise).
  double camera_height = 0.0;            // m
  double camera_height_tolerance = 0.1;  // m
};

struct FloorChoice {
  std::vector<FloorCandidate> candidates;  // as found: strongest first
  int chosen = -1;                         // index into candidates; -1: no floor
  std::string reason;                      // why there is no floor (empty when there is one)

  const FloorCandidate* Floor() const { return chosen >= 0 ? &candidates[chosen] : nullptr; }
  // The other candidates, strongest first.
  std::vector<FloorCandidate> RunnersUp() const;
  // Two credible candidates whose support differs by less than a fifth (the choice between
  // them rests on their heights alone), or nothing.
  std::optional<std::pair<FloorCandidate, FloorCandidate>> CloseInSupport() const;
};

// `camera_centres` and `camera_downs` (each camera's image +y axis in the world) hold one entry
// per camera. Deterministic (fixed seed).
FloorChoice ChooseFloor(const std::vector<Eigen::Vector3f>& points,
                        const std::vector<Eigen::Vector3f>& camera_centres,
                        const std::vector<Eigen::Vector3f>& camera_downs,
                        const FloorSearch& search);

// ChooseFloor's plane alone.
std::optional<FloorPlane> FindFloor(const std::vector<Eigen::Vector3f>& points,
                                    const std::vector<Eigen::Vector3f>& camera_centres,
                                    const std::vector<Eigen::Vector3f>& camera_downs,
                                    const FloorSearch& search);

}  // namespace drvslam
