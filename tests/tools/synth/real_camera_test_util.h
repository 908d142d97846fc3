// Helpers the real-camera tests share (real_camera_test.cc, lens_distortion_test.cc): two
// flat textures and a small, clean synthetic sequence.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "drvslam/tools/synth/synth_options.h"
#include "drvslam/tools/synth/texture.h"
#include "raster_test_scene.h"

namespace drvslam::synth::testing {

// Texture 0 dark grey, texture 1 white.
inline std::vector<Texture> TwoTextures() {
  return SolidTextures({cv::Scalar(20, 20, 20), cv::Scalar(230, 230, 230)});
}

inline SynthOptions SmallOptions(const std::string& scenario, int frames) {
  SynthOptions options;
  options.scenario = scenario;
  options.frames = frames;
  options.width = 320;
  options.height = 240;
  options.seed = 5;
  options.procedural_textures = true;
  options.sensor = SensorOptions::Clean();
  return options;
}

}  // namespace drvslam::synth::testing
