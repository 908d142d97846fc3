// A test scene for the rasterizer and the renderers built on it: a 640x480 camera at the origin
// looking along +z, lighting that leaves texture colours as they are, and rectangles facing the
// camera.
#pragma once

#include <Eigen/Core>

#include "drvslam/core/camera.h"
#include "drvslam/synth/rasterizer.h"

namespace drvslam::synth::testing {

inline CameraOptions TestCamera() {
  CameraOptions camera;
  camera.fx = 500.0;
  camera.fy = 500.0;
  camera.cx = 320.25;
  camera.cy = 240.25;
  camera.width = 640;
  camera.height = 480;
  return camera;
}

// Lighting that leaves texture colours as they are (shade 1 everywhere).
inline RasterOptions Unlit() {
  RasterOptions options;
  options.ambient = 1.0;
  return options;
}

// A w x h rectangle facing the camera at the camera-frame centre `c` (camera at the origin
// looking along +z, image y down).
inline void AddFacingRect(const Eigen::Vector3d& c, double w, double h, int id, int texture,
                          TriangleList* out) {
  SurfaceTag tag;
  tag.texture = texture;
  tag.instance_id = id;
  const Eigen::Vector3d dx(0.5 * w, 0, 0), dy(0, 0.5 * h, 0);
  AddQuad(c - dx + dy, c + dx + dy, c + dx - dy, c - dx - dy, UvRect(), tag, out);
}

}  // namespace drvslam::synth::testing
