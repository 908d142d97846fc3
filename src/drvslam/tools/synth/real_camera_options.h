// RealCameraOptions: the ways a real hand-held RGB-D camera departs from the perfect pinhole
// images the generator renders by default - motion blur, rolling shutter, depth misregistered
// against colour, calibration off by a few percent, lens distortion. Each is off by default and
// can be switched on alone; with all of them off the output is byte for byte what it was
// without them.
#pragma once

#include <string>

#include "drvslam/core/camera.h"

namespace drvslam::synth {

struct RealCameraOptions {
  // Motion blur: each image integrates the scene over blur_exposure seconds centred on its
  // rows' exposure time, the camera and the actors moving, approximated by the mean of
  // blur_samples renders at evenly spaced times (midpoint rule). 0 = off. Depth, masks and the
  // instance ids are those of the render at the centre of the exposure.
  double blur_exposure = 0.0;
  int blur_samples = 5;
  // Rolling shutter: rows are exposed one after another from the top over
  // rolling_shutter_readout seconds. Row r (0 at the top) is exposed around
  // t + ((r + 0.5) / height - 0.5) * readout, so the frame's timestamp, and its ground-truth
  // pose, belong to the middle of the image. rolling_shutter_steps bands of rows share one
  // time (the band's middle). 0 = off.
  double rolling_shutter_readout = 0.0;
  int rolling_shutter_steps = 60;
  // With rolling shutter: depth is captured all at once at the frame's timestamp (a RealSense's
  // global-shutter depth sensor) instead of row by row with colour (a Kinect v1), so depth of
  // anything that moves in the image misregisters against the colour rows. Masks stay with
  // colour.
  bool depth_global_shutter = false;
  // Depth misregistration: the depth image is moved by (dx, dy) pixels against colour: depth at
  // (x, y) is the true depth at (x - dx, y - dy). Sub-pixel shifts interpolate depth where the
  // surface is continuous; depth edges move by the shift rounded to whole pixels. Masks stay
  // with colour.
  double depth_shift_x = 0.0;
  double depth_shift_y = 0.0;
  // Calibration error: settings.yaml states fx, fy (and bf) this fraction larger than the
  // intrinsics the images were rendered with (0.03: 3 % larger), and cx, cy moved by
  // principal_point_error_* pixels. The Synth.True* keys keep the truth.
  double intrinsics_error = 0.0;
  double principal_point_error_x = 0.0;
  double principal_point_error_y = 0.0;
  // Lens distortion, OpenCV's radial-tangential model (the ORB-SLAM2 Camera.k1 k2 p1 p2 k3):
  // images are rendered through it, and settings.yaml states it.
  double k1 = 0.0, k2 = 0.0, p1 = 0.0, p2 = 0.0, k3 = 0.0;

  bool Blur() const { return blur_exposure > 0.0; }
  bool RollingShutter() const { return rolling_shutter_readout > 0.0; }
  bool DepthShift() const { return depth_shift_x != 0.0 || depth_shift_y != 0.0; }
  bool CalibrationError() const {
    return intrinsics_error != 0.0 || principal_point_error_x != 0.0 ||
           principal_point_error_y != 0.0;
  }
  bool Distortion() const { return k1 != 0.0 || k2 != 0.0 || p1 != 0.0 || p2 != 0.0 || k3 != 0.0; }
  // Any effect that changes the rendered images (everything but the calibration error).
  bool ChangesImages() const { return Blur() || RollingShutter() || DepthShift() || Distortion(); }
  bool Any() const { return ChangesImages() || CalibrationError(); }

  // Sets the distortion coefficients from "k1,k2,p1,p2,k3" or a preset name ("fr1", "fr2":
  // the TUM RGB-D calibrations). Throws Error naming --distortion.
  void SetDistortion(const std::string& text);

  // Throws Error naming the option (as its `drvslam synth` flag) and the bad value.
  void Check() const;
};

// --real-camera: a quickly moved hand-held camera with a rolling-shutter colour sensor and a
// global-shutter depth sensor (as a RealSense): 15 ms exposure, 25 ms readout, depth 1.5 px right
// and 1 px down of colour, fx and fy stated 3 % too large, TUM fr1's lens distortion.
RealCameraOptions HandheldCamera();

// The camera the settings file states: `truth` with the calibration error applied.
CameraOptions StatedCamera(const CameraOptions& truth, const RealCameraOptions& options);

}  // namespace drvslam::synth
