#include "drvslam/tools/synth/real_camera_options.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "drvslam/core/error.h"

namespace drvslam::synth {
namespace {

bool InRange(double value, double lo, double hi) {
  return std::isfinite(value) && value >= lo && value <= hi;
}

void Require(bool ok, const char* flag, double value, const char* rule) {
  if (ok) return;
  std::ostringstream message;
  message << flag << " " << value << " " << rule;
  throw Error(message.str());
}

// TUM RGB-D calibrations (configs/TUM1.yaml, TUM2.yaml).
constexpr double kFr1Distortion[5] = {0.262383, -0.953104, -0.005358, 0.002628, 1.163314};
constexpr double kFr2Distortion[5] = {0.231222, -0.784899, -0.003257, -0.000105, 0.917205};

}  // namespace

void RealCameraOptions::SetDistortion(const std::string& text) {
  std::vector<double> values;
  if (text == "fr1" || text == "fr2") {
    const double* preset = text == "fr1" ? kFr1Distortion : kFr2Distortion;
    values.assign(preset, preset + 5);
  } else {
    std::size_t start = 0;
    while (start <= text.size()) {
      const std::size_t comma = std::min(text.find(',', start), text.size());
      const std::string item = text.substr(start, comma - start);
      char* end = nullptr;
      errno = 0;
      const double value = std::strtod(item.c_str(), &end);
      if (item.empty() || end != item.c_str() + item.size() || errno != 0 ||
          !std::isfinite(value)) {
        throw Error("--distortion '" + text +
                    "' must be fr1, fr2 or 1 to 5 numbers k1,k2,p1,p2,k3");
      }
      values.push_back(value);
      start = comma + 1;
    }
    if (values.size() > 5) {
      throw Error("--distortion '" + text + "' has more than 5 coefficients (k1,k2,p1,p2,k3)");
    }
  }
  values.resize(5, 0.0);
  k1 = values[0];
  k2 = values[1];
  p1 = values[2];
  p2 = values[3];
  k3 = values[4];
}

void RealCameraOptions::Check() const {
  Require(InRange(blur_exposure, 0.0, 0.2), "--blur-exposure", blur_exposure,
          "must be in [0, 0.2] seconds");
  Require(blur_samples >= 2 && blur_samples <= 64, "--blur-samples", blur_samples,
          "must be in 2..64");
  Require(InRange(rolling_shutter_readout, 0.0, 0.2), "--rolling-shutter", rolling_shutter_readout,
          "must be in [0, 0.2] seconds");
  Require(rolling_shutter_steps >= 2 && rolling_shutter_steps <= 4096, "--rolling-shutter-steps",
          rolling_shutter_steps, "must be in 2..4096");
  Require(InRange(depth_shift_x, -50.0, 50.0), "--depth-shift x", depth_shift_x,
          "must be in [-50, 50] pixels");
  Require(InRange(depth_shift_y, -50.0, 50.0), "--depth-shift y", depth_shift_y,
          "must be in [-50, 50] pixels");
  Require(InRange(intrinsics_error, -0.5, 0.5), "--intrinsics-error", intrinsics_error,
          "must be in [-0.5, 0.5]");
  Require(InRange(principal_point_error_x, -200.0, 200.0), "--principal-point-error x",
          principal_point_error_x, "must be in [-200, 200] pixels");
  Require(InRange(principal_point_error_y, -200.0, 200.0), "--principal-point-error y",
          principal_point_error_y, "must be in [-200, 200] pixels");
  for (const double k : {k1, k2, p1, p2, k3}) {
    Require(InRange(k, -10.0, 10.0), "--distortion coefficient", k, "must be in [-10, 10]");
  }
}

RealCameraOptions HandheldCamera() {
  RealCameraOptions options;
  options.blur_exposure = 0.015;
  options.rolling_shutter_readout = 0.025;
  options.depth_global_shutter = true;
  options.depth_shift_x = 1.5;
  options.depth_shift_y = 1.0;
  options.intrinsics_error = 0.03;
  options.SetDistortion("fr1");
  return options;
}

CameraOptions StatedCamera(const CameraOptions& truth, const RealCameraOptions& options) {
  CameraOptions stated = truth;
  const double scale = 1.0 + options.intrinsics_error;
  stated.fx *= scale;
  stated.fy *= scale;
  stated.bf *= scale;  // the same baseline at the stated focal length
  stated.cx += options.principal_point_error_x;
  stated.cy += options.principal_point_error_y;
  stated.k1 = options.k1;
  stated.k2 = options.k2;
  stated.p1 = options.p1;
  stated.p2 = options.p2;
  stated.k3 = options.k3;
  return stated;
}

}  // namespace drvslam::synth
