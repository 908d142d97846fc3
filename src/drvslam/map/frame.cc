#include "drvslam/map/frame.h"

#include "drvslam/map/map_point.h"

namespace drvslam {

Frame::Frame(long id, double timestamp, std::shared_ptr<const FrameFeatures> features)
    : id_(id), timestamp_(timestamp), features_(std::move(features)) {
  map_points.resize(features_->Size());
  outlier.assign(features_->Size(), false);
}

std::optional<Frame::Projection> Frame::ProjectIfVisible(const MapPoint& point,
                                                         double min_view_cos) const {
  const Eigen::Vector3d position = point.Position();
  const Eigen::Vector3d point_c = *T_cw_ * position;
  if (point_c.z() <= 0) return std::nullopt;
  const SensorGeometry& geometry = Geometry();
  const Eigen::Vector2d pixel = geometry.camera.Project(point_c);
  if (!geometry.InBounds(pixel.x(), pixel.y())) return std::nullopt;
  const Eigen::Vector3d ray = position - center_;
  const double distance = ray.norm();
  const double max_distance = point.MaxDistance() * 1.2;
  const double min_distance = point.MinDistance() * 0.8;
  if (distance < min_distance || distance > max_distance) return std::nullopt;
  const Eigen::Vector3d normal = point.Normal();
  const double view_cos = normal.norm() > 0 ? ray.dot(normal) / (distance * normal.norm()) : 1.0;
  if (view_cos < min_view_cos) return std::nullopt;
  Projection projection;
  projection.u = pixel.x();
  projection.v = pixel.y();
  projection.right_u = pixel.x() - geometry.Bf() / point_c.z();
  projection.predicted_level = point.PredictLevel(distance, geometry.pyramid);
  projection.view_cos = view_cos;
  return projection;
}

}  // namespace drvslam
