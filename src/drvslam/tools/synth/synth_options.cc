#include "drvslam/tools/synth/synth_options.h"

#include <cmath>
#include <string>

#include "drvslam/core/coco_classes.h"
#include "drvslam/core/error.h"
#include "drvslam/tools/synth/scenario.h"

namespace drvslam::synth {
namespace {

std::string CocoName(std::string name) {
  for (char& ch : name) {
    if (ch == '_') ch = ' ';
  }
  return name;
}

}  // namespace

std::string SynthOptions::ActorClassName() const {
  return actor_class.empty() ? FindScenario(scenario).ActorClass() : CocoName(actor_class);
}

void SynthOptions::Check() const {
  const Scenario& chosen = FindScenario(scenario);
  if (frames == 0 || frames < -1 || frames > kMaxFrames) {
    throw Error("--frames " + std::to_string(frames) + " must be in 1.." +
                std::to_string(kMaxFrames));
  }
  if (seed > kMaxSeed) {
    throw Error("--seed " + std::to_string(seed) + " must be in 0.." + std::to_string(kMaxSeed));
  }
  if (actors < -1 || actors > kMaxActors) {
    throw Error("--actors " + std::to_string(actors) + " must be in 0.." +
                std::to_string(kMaxActors));
  }
  if (chosen.motion == MotionKind::kStatic && actors > 0) {
    throw Error("--actors " + std::to_string(actors) + ": scenario " + scenario +
                " has no movers (use a walking_*, sitting_* or pushed_* scenario)");
  }
  if (billboard_count < -1 || billboard_count > kMaxActors) {
    throw Error("--billboard-count " + std::to_string(billboard_count) + " must be in 0.." +
                std::to_string(kMaxActors));
  }
  if (!billboards.empty() && chosen.motion == MotionKind::kPushed) {
    throw Error("--billboards: the carts of scenario " + scenario + " are not drawn as cut-outs");
  }
  if (billboard_count > 0 && billboards.empty()) {
    throw Error("--billboard-count needs --billboards DIR");
  }
  if (procedural_textures && !textures.empty()) {
    throw Error("--textures and --procedural-textures exclude each other");
  }
  // The scenario's own class is accepted by name too: settings.yaml states it (Synth.ActorClass)
  // and dense_truth.cc rebuilds a sequence from it.
  if (!actor_class.empty() && CocoClassId(CocoName(actor_class)) < 0 &&
      CocoName(actor_class) != chosen.ActorClass()) {
    throw Error("--actor-class '" + actor_class + "' is not a COCO class name");
  }
  if (width < 32 || width > 4096 || height < 32 || height > 4096) {
    throw Error("--width/--height " + std::to_string(width) + "x" + std::to_string(height) +
                " must be in 32..4096");
  }
  if (!(std::isfinite(fps) && fps > 0.0 && fps <= 1000.0)) {
    throw Error("--fps " + std::to_string(fps) + " must be in (0, 1000]");
  }
  if (!(std::isfinite(camera_speed) && camera_speed > 0.0 && camera_speed <= 20.0)) {
    throw Error("--camera-speed " + std::to_string(camera_speed) + " must be in (0, 20]");
  }
  if (!(std::isfinite(start_stamp) && start_stamp >= 0.0)) {
    throw Error("start stamp must be a non-negative number");
  }
  sensor.Check();
  real_camera.Check();
}

CameraOptions SynthOptions::Camera() const {
  CameraOptions camera;  // TUM fr3 defaults
  const double sx = width / 640.0;
  const double sy = height / 480.0;
  camera.fx *= sx;
  camera.cx *= sx;
  camera.fy *= sy;
  camera.cy *= sy;
  camera.bf *= sx;
  camera.width = width;
  camera.height = height;
  camera.fps = fps;
  camera.k1 = real_camera.k1;
  camera.k2 = real_camera.k2;
  camera.p1 = real_camera.p1;
  camera.p2 = real_camera.p2;
  camera.k3 = real_camera.k3;
  return camera;
}

CameraOptions SynthOptions::StatedCamera() const {
  return synth::StatedCamera(Camera(), real_camera);
}

}  // namespace drvslam::synth
