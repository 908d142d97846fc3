// Lens distortion for the generator: OpenCV's radial-tangential model (k1 k2 p1 p2 k3, the
// ORB-SLAM2 Camera.* keys) and the map that turns an undistorted render into the image a
// distorting lens would give. The render ("canvas") has the sensor's focal lengths and is just
// large enough that every sensor pixel finds its ray on it.
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "drvslam/core/camera.h"

namespace drvslam::synth {

struct LensDistortion {
  double k1 = 0.0, k2 = 0.0, p1 = 0.0, p2 = 0.0, k3 = 0.0;

  static LensDistortion Of(const CameraOptions& camera);
  // Normalized undistorted coordinates (X/Z, Y/Z) to normalized distorted ones.
  Eigen::Vector2d Distort(const Eigen::Vector2d& undistorted) const;
  // The inverse, by Newton's method from the distorted point. False when it does not converge
  // or the model folds over there (its Jacobian is not positive): a lens cannot do that.
  bool Undistort(const Eigen::Vector2d& distorted, Eigen::Vector2d* undistorted) const;
};

class DistortionMap {
 public:
  // `sensor`: the true intrinsics, size and distortion. Without distortion the map is the
  // identity and the canvas is the sensor. Throws Error naming --distortion when the model
  // cannot be inverted over the whole image or needs an absurdly large canvas.
  explicit DistortionMap(const CameraOptions& sensor);

  bool Identity() const { return identity_; }
  // The undistorted pinhole camera to render with.
  const CameraOptions& Canvas() const { return canvas_; }
  // Canvas position (pixel coordinates, centres at integers) seen by sensor pixel (x, y).
  float CanvasX(int x, int y) const { return map_x_[Index(x, y)]; }
  float CanvasY(int x, int y) const { return map_y_[Index(x, y)]; }
  // Canvas rows [first, last) that sensor rows [row_begin, row_end) read, with bilinear
  // interpolation's neighbour included.
  std::pair<int, int> CanvasRows(int row_begin, int row_end) const;

 private:
  std::size_t Index(int x, int y) const { return static_cast<std::size_t>(y) * sensor_width_ + x; }

  bool identity_ = true;
  int sensor_width_ = 0;
  CameraOptions canvas_;
  std::vector<float> map_x_, map_y_;
  // Per sensor row: the lowest and highest canvas row read.
  std::vector<int> row_min_, row_max_;
};

}  // namespace drvslam::synth
