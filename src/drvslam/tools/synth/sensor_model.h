// SensorModel: what a Kinect-style RGB-D camera does to the exact rendered images. Each effect
// can be switched off on its own; with all of them off, depth is the exact rendered z (only the
// 16-bit file's 1/5000 m steps remain) and colour is the exact shaded texture.
// Random effects draw from counter-based hashes of (seed, frame, pixel), so they are the same
// on any number of threads and a frame can be re-rendered alone.
#pragma once

#include <cstdint>
#include <string>

#include "drvslam/core/camera.h"
#include "drvslam/core/se3.h"
#include "drvslam/tools/synth/rasterizer.h"

namespace drvslam::synth {

struct SensorOptions {
  // Axial depth noise, sigma = depth_noise_coeff * z^2 (a Kinect's grows with distance
  // squared; 0.0012 m^-1 gives 1.2 mm at 1 m, 4.8 mm at 2 m).
  bool depth_noise = true;
  double depth_noise_coeff = 0.0012;
  // Rounds depth to 1/depth_factor m, as the 16-bit file does anyway.
  bool depth_quantization = true;
  double depth_factor = 5000.0;
  // Missing depth at depth discontinuities: pixels next to a jump larger than
  // edge_jump_ratio * z are dropped with probability edge_hole_probability.
  bool edge_holes = true;
  double edge_jump_ratio = 0.03;
  double edge_hole_probability = 0.75;
  // Missing depth where the viewing ray meets the surface at more than grazing_angle_deg from
  // its normal.
  bool grazing_holes = true;
  double grazing_angle_deg = 80.0;
  // No depth nearer than min_range or beyond max_range (metres).
  bool range_limits = true;
  double min_range = 0.4;
  double max_range = 5.0;
  // Per-pixel colour noise, sigma in grey levels.
  bool color_noise = true;
  double color_noise_sigma = 2.0;
  // Auto-exposure drift: a smooth brightness gain of 1 +- exposure_amplitude.
  bool exposure = true;
  double exposure_amplitude = 0.05;
  // Blur along the image motion during the exposure (camera motion only), off by default.
  bool motion_blur = false;
  double exposure_time = 0.012;  // seconds
  int blur_samples = 6;

  // Every effect off: exact images.
  static SensorOptions Clean();
  // Throws Error naming the bad option ("sensor.<name>") and its value.
  void Check() const;
};

class SensorModel {
 public:
  SensorModel(const SensorOptions& options, const CameraOptions& camera, uint32_t seed);

  const SensorOptions& Options() const { return options_; }
  // Brightness gain at time t (seconds since the first frame); 1 with exposure off.
  double ExposureGain(double t) const;

  // Applies the effects to a clean render of frame `frame` taken at time t. T_start_now maps
  // points from the camera at t into the camera at the start of the exposure (used for motion
  // blur only). Replaces frame->bgr and frame->depth; leaves instance ids untouched.
  void Apply(int frame, double t, const SE3& T_start_now, RenderBuffers* frame_buffers) const;

 private:
  SensorOptions options_;
  CameraOptions camera_;
  uint32_t seed_;
  double exposure_phase_[2];
};

}  // namespace drvslam::synth
