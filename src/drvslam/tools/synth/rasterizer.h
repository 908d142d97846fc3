// Rasterizer: exact colour, depth and instance images of textured triangles seen by a pinhole
// camera. A z-buffer pass finds the nearest surface at every pixel centre, then a shading pass
// textures only the visible pixels (perspective-correct, trilinear). Depth is the z coordinate in
// the camera frame, as a Kinect or TUM depth image stores it, not the length of the ray.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/core/camera.h"
#include "drvslam/core/se3.h"
#include "drvslam/tools/synth/scene.h"
#include "drvslam/tools/synth/texture.h"

namespace drvslam::synth {

struct RenderBuffers {
  cv::Mat bgr;        // CV_8UC3
  cv::Mat depth;      // CV_32FC1, metres; 0 where no surface was hit
  cv::Mat instance;   // CV_16UC1, instance id of the nearest surface; 0 = background
  cv::Mat incidence;  // CV_32FC1, cosine between surface normal and viewing ray (1 = head-on)
};

struct RasterOptions {
  // Geometry closer than this (metres, camera z) is clipped away.
  double near_plane = 0.05;
  // Direction towards the light, in the world frame (z up), and the unlit share of brightness.
  // Shading depends on the surface normal only, so a static surface looks the same from any
  // viewpoint, as a matte surface would.
  Eigen::Vector3d light_direction{0.35, -0.55, 1.0};
  double ambient = 0.62;

  // Throws Error naming the bad option.
  void Check() const;
};

class Rasterizer {
 public:
  // Uses the camera's intrinsics and image size; distortion is ignored (synthetic images have
  // none).
  explicit Rasterizer(const CameraOptions& camera, const RasterOptions& options = {});

  // Draws every triangle of `lists` seen from T_cw. Triangle::texture indexes `textures`.
  // Bands of rows are drawn in parallel, each pixel by one band, and a depth tie keeps the
  // triangle that came first, so the images do not depend on the number of threads. Throws
  // Error when a triangle names a texture that does not exist.
  void Render(const std::vector<const TriangleList*>& lists, const std::vector<Texture>& textures,
              const SE3& T_cw, RenderBuffers* out) const;
  // Draws only image rows [row_begin, row_end): `out` gets row_end - row_begin rows, its row 0
  // being image row row_begin, with exactly the pixels Render gives there. With `parallel`
  // false everything runs on the calling thread (for callers that draw many row ranges in
  // parallel, e.g. a rolling shutter's bands).
  void RenderRows(const std::vector<const TriangleList*>& lists,
                  const std::vector<Texture>& textures, const SE3& T_cw, int row_begin, int row_end,
                  RenderBuffers* out, bool parallel = true) const;

  const CameraOptions& Camera() const { return camera_; }

 private:
  CameraOptions camera_;
  RasterOptions options_;
  Eigen::Vector3d light_;  // unit
};

}  // namespace drvslam::synth
