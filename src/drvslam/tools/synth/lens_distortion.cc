#include "drvslam/tools/synth/lens_distortion.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "drvslam/core/error.h"

namespace drvslam::synth {
namespace {

constexpr int kNewtonIterations = 40;
constexpr double kNewtonTolerance = 1e-12;  // normalized units: far below a pixel
// A canvas larger than this many times the sensor in either direction means the model is not
// a lens any more (it would show nearly a half-space).
constexpr int kMaxCanvasFactor = 4;

}  // namespace

LensDistortion LensDistortion::Of(const CameraOptions& camera) {
  return {camera.k1, camera.k2, camera.p1, camera.p2, camera.k3};
}

Eigen::Vector2d LensDistortion::Distort(const Eigen::Vector2d& undistorted) const {
  const double x = undistorted.x(), y = undistorted.y();
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
  return {x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
          y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y};
}

bool LensDistortion::Undistort(const Eigen::Vector2d& distorted,
                               Eigen::Vector2d* undistorted) const {
  Eigen::Vector2d u = distorted;
  for (int iteration = 0; iteration < kNewtonIterations; ++iteration) {
    const double x = u.x(), y = u.y();
    const double r2 = x * x + y * y;
    const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
    // d(radial)/d(r2), times 2x or 2y below.
    const double slope = k1 + r2 * (2.0 * k2 + 3.0 * r2 * k3);
    Eigen::Matrix2d jacobian;
    jacobian(0, 0) = radial + 2.0 * x * x * slope + 2.0 * p1 * y + 6.0 * p2 * x;
    jacobian(0, 1) = 2.0 * x * y * slope + 2.0 * p1 * x + 2.0 * p2 * y;
    jacobian(1, 0) = 2.0 * x * y * slope + 2.0 * p1 * x + 2.0 * p2 * y;
    jacobian(1, 1) = radial + 2.0 * y * y * slope + 6.0 * p1 * y + 2.0 * p2 * x;
    const Eigen::Vector2d residual = Distort(u) - distorted;
    const double determinant = jacobian.determinant();
    if (!(determinant > 0.0)) return false;
    if (residual.norm() < kNewtonTolerance) {
      *undistorted = u;
      return true;
    }
    u -= jacobian.inverse() * residual;
    if (!u.allFinite()) return false;
  }
  return false;
}

DistortionMap::DistortionMap(const CameraOptions& sensor)
    : sensor_width_(sensor.width), canvas_(sensor) {
  canvas_.k1 = canvas_.k2 = canvas_.p1 = canvas_.p2 = canvas_.k3 = 0.0;
  if (!sensor.HasDistortion()) return;
  identity_ = false;
  const LensDistortion lens = LensDistortion::Of(sensor);
  const int width = sensor.width, height = sensor.height;
  map_x_.resize(static_cast<std::size_t>(width) * height);
  map_y_.resize(map_x_.size());
  double min_x = std::numeric_limits<double>::infinity(), max_x = -min_x;
  double min_y = min_x, max_y = -min_x;
  std::vector<double> canvas_x(map_x_.size()), canvas_y(map_x_.size());
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const Eigen::Vector2d distorted((x - sensor.cx) / sensor.fx, (y - sensor.cy) / sensor.fy);
      Eigen::Vector2d undistorted;
      if (!lens.Undistort(distorted, &undistorted)) {
        throw Error("--distortion " + std::to_string(sensor.k1) + "," + std::to_string(sensor.k2) +
                    "," + std::to_string(sensor.p1) + "," + std::to_string(sensor.p2) + "," +
                    std::to_string(sensor.k3) + " cannot be inverted at pixel (" +
                    std::to_string(x) + ", " + std::to_string(y) +
                    "): the model folds over inside the image");
      }
      const std::size_t i = Index(x, y);
      canvas_x[i] = sensor.fx * undistorted.x() + sensor.cx;
      canvas_y[i] = sensor.fy * undistorted.y() + sensor.cy;
      min_x = std::min(min_x, canvas_x[i]);
      max_x = std::max(max_x, canvas_x[i]);
      min_y = std::min(min_y, canvas_y[i]);
      max_y = std::max(max_y, canvas_y[i]);
    }
  }
  // One pixel of margin on each side, so bilinear interpolation always has its four texels.
  const double offset_x = 1.0 - std::floor(min_x);
  const double offset_y = 1.0 - std::floor(min_y);
  const double canvas_width = std::floor(max_x) + offset_x + 2.0;
  const double canvas_height = std::floor(max_y) + offset_y + 2.0;
  if (canvas_width > kMaxCanvasFactor * width || canvas_height > kMaxCanvasFactor * height) {
    throw Error("--distortion " + std::to_string(sensor.k1) + ",...: the undistorted view of a " +
                std::to_string(width) + "x" + std::to_string(height) + " image would need " +
                std::to_string(static_cast<long long>(canvas_width)) + "x" +
                std::to_string(static_cast<long long>(canvas_height)) + " pixels");
  }
  canvas_.width = static_cast<int>(canvas_width);
  canvas_.height = static_cast<int>(canvas_height);
  canvas_.cx = sensor.cx + offset_x;
  canvas_.cy = sensor.cy + offset_y;
  row_min_.assign(height, std::numeric_limits<int>::max());
  row_max_.assign(height, std::numeric_limits<int>::min());
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t i = Index(x, y);
      map_x_[i] = static_cast<float>(canvas_x[i] + offset_x);
      map_y_[i] = static_cast<float>(canvas_y[i] + offset_y);
      const int row = static_cast<int>(std::floor(map_y_[i]));
      row_min_[y] = std::min(row_min_[y], row);
      row_max_[y] = std::max(row_max_[y], row + 1);
    }
  }
}

std::pair<int, int> DistortionMap::CanvasRows(int row_begin, int row_end) const {
  if (identity_) return {row_begin, row_end};
  int first = std::numeric_limits<int>::max(), last = std::numeric_limits<int>::min();
  for (int y = row_begin; y < row_end; ++y) {
    first = std::min(first, row_min_[y]);
    last = std::max(last, row_max_[y]);
  }
  return {std::max(0, first), std::min(canvas_.height, last + 1)};
}

}  // namespace drvslam::synth
