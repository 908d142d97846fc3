// ShutterRenderer: one frame as a real camera's colour sensor records it - rows exposed at
// row-dependent times (rolling shutter), each over an exposure time while the camera and the
// actors move (motion blur), through a distorting lens. It renders the scene at sub-frame times
// and assembles the image from them:
//  - the rows are split into bands that share one time (rolling_shutter_steps of them, one band
//    without rolling shutter); a band is exposed around the time of its middle row;
//  - each band's colour is the mean of blur_samples renders spread evenly over the exposure
//    (one render without blur); depth, instance ids and incidence come from the render at the
//    band's exposure centre, so masks match the middle of the blurred colour;
//  - with a global-shutter depth sensor, depth and incidence instead come from one render at the
//    timestamp;
//  - with distortion, the renders are undistorted ("canvas") images that cover every sensor
//    ray, and each sensor pixel reads its ray's canvas position: colour bilinearly, depth,
//    instance ids and incidence from the nearest canvas pixel (no blending across edges).
// Bands are drawn in parallel; every pixel is computed the same way on any number of threads.
#pragma once

#include <functional>
#include <vector>

#include "drvslam/core/camera.h"
#include "drvslam/core/se3.h"
#include "drvslam/tools/synth/lens_distortion.h"
#include "drvslam/tools/synth/rasterizer.h"
#include "drvslam/tools/synth/real_camera_options.h"
#include "drvslam/tools/synth/scene.h"
#include "drvslam/tools/synth/texture.h"

namespace drvslam::synth {

class ShutterRenderer {
 public:
  // The scene `offset` seconds after the frame's timestamp: the camera (T_cw) and the moving
  // geometry. Called from several threads at once.
  using SceneAt = std::function<void(double offset, SE3* T_cw, TriangleList* movers)>;

  // `sensor`: the true intrinsics, size and distortion (its k1..k3). Throws Error naming the
  // option at fault.
  ShutterRenderer(const CameraOptions& sensor, const RealCameraOptions& options,
                  const RasterOptions& raster = {});

  // True when a frame is a single render at the timestamp: no blur, no rolling shutter, no
  // distortion.
  bool SingleRender() const;
  // Exposure centre of image row `row` (0 at the top, may be fractional), in seconds after the
  // frame's timestamp, as the bands quantize it: 0 for every row without rolling shutter.
  double RowOffset(int row) const;
  // Offsets of the blur samples from a band's exposure centre.
  const std::vector<double>& SampleOffsets() const { return sample_offsets_; }
  int Bands() const { return bands_; }
  const CameraOptions& Canvas() const { return distortion_.Canvas(); }

  void Render(const TriangleList& statics, const std::vector<Texture>& textures,
              const SceneAt& scene_at, RenderBuffers* out) const;

 private:
  // Draws sensor rows [row_begin, row_end) of `out` (allocated at the sensor size).
  void RenderBand(int row_begin, int row_end, double offset, const TriangleList& statics,
                  const std::vector<Texture>& textures, const SceneAt& scene_at, bool parallel,
                  RenderBuffers* out) const;

  // Replaces depth and incidence of `out` with those of one render at the timestamp.
  void RenderGlobalDepth(const TriangleList& statics, const std::vector<Texture>& textures,
                         const SceneAt& scene_at, RenderBuffers* out) const;

  CameraOptions sensor_;
  RealCameraOptions options_;
  DistortionMap distortion_;
  Rasterizer rasterizer_;  // draws the canvas
  int bands_ = 1;
  std::vector<double> sample_offsets_;
  int centre_sample_ = 0;  // index of the sample at offset 0; -1 when there is none
};

}  // namespace drvslam::synth
