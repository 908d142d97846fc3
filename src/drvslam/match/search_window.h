// PredictSearchWindow: where a map point should be looked for in a view whose pose is known, the
// first step of every guided search by projection (ORB-SLAM2's SearchByProjection family).
#pragma once

#include <Eigen/Core>
#include <optional>

#include "drvslam/core/se3.h"
#include "drvslam/map/frame_features.h"
#include "drvslam/map/map_point.h"

namespace drvslam {

struct SearchWindow {
  Eigen::Vector2d pixel;  // the point's projection
  int level = 0;          // the pyramid level its distance predicts
  double radius = 0.0;    // search radius around `pixel`, grown with the level's scale
};

// The window for `point` in a view at T_cw with camera centre `center`: radius_factor times the
// predicted level's scale, in pixels. nullopt when the point is behind the camera, projects
// outside the image, or is farther than 0.8-1.2 times the distance range it was observed at.
std::optional<SearchWindow> PredictSearchWindow(const MapPoint& point, const SE3& T_cw,
                                                const Eigen::Vector3d& center,
                                                const SensorGeometry& geometry,
                                                double radius_factor);

}  // namespace drvslam
