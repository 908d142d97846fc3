#include "drvslam/match/search_window.h"

namespace drvslam {

std::optional<SearchWindow> PredictSearchWindow(const MapPoint& point, const SE3& T_cw,
                                                const Eigen::Vector3d& center,
                                                const SensorGeometry& geometry,
                                                double radius_factor) {
  const Eigen::Vector3d position = point.Position();
  const Eigen::Vector3d point_c = T_cw * position;
  if (point_c.z() <= 0) return std::nullopt;
  SearchWindow window;
  window.pixel = geometry.camera.Project(point_c);
  if (!geometry.InBounds(window.pixel.x(), window.pixel.y())) return std::nullopt;
  const double distance = (position - center).norm();
  if (distance < 0.8 * point.MinDistance() || distance > 1.2 * point.MaxDistance()) {
    return std::nullopt;
  }
  window.level = point.PredictLevel(distance, geometry.pyramid);
  window.radius = radius_factor * geometry.pyramid.scale[window.level];
  return window;
}

}  // namespace drvslam
