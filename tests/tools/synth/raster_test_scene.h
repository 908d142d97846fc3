// A test scene for the rasterizer and the renderers built on it: a 640x480 camera at the origin
// looking along +z, lighting that leaves texture colours as they are, and rectangles facing the
// camera.
#pragma once

#include <Eigen/Core>
#include <initializer_list>
#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/core/camera.h"
#include "drvslam/tools/synth/rasterizer.h"
#include "drvslam/tools/synth/texture.h"

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

// One flat 8x8 texture per BGR colour: texture i is colours[i] all over.
inline std::vector<Texture> SolidTextures(std::initializer_list<cv::Scalar> colours) {
  std::vector<Texture> textures;
  for (const cv::Scalar& colour : colours) textures.emplace_back(cv::Mat(8, 8, CV_8UC3, colour));
  return textures;
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
