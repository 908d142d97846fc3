// SynthOptions: everything that defines a synthetic sequence (what `drvslam synth` parses).
// The same options always give byte-identical output files.
#pragma once

#include <cstdint>
#include <string>

#include "drvslam/core/camera.h"
#include "drvslam/tools/synth/photo_library.h"
#include "drvslam/tools/synth/real_camera_options.h"
#include "drvslam/tools/synth/sensor_model.h"

namespace drvslam::synth {

inline constexpr int kDefaultFrames = 300;
inline constexpr int kMaxFrames = 100000;
inline constexpr int kMaxActors = 20;
// Seeds fit a signed 32-bit YAML integer (Synth.Seed in settings.yaml).
inline constexpr uint32_t kMaxSeed = 2147483647u;
// First stamp of procedurally moved sequences: an epoch like the TUM recordings'.
inline constexpr double kDefaultStartStamp = 1305031102.175304;

struct SynthOptions {
  std::string scenario = "walking_xyz";
  // -1: kDefaultFrames for procedural paths, the whole recording when replaying one.
  int frames = -1;
  uint32_t seed = 1;
  // A TUM trajectory to replay instead of the scenario's procedural path; frames then follow
  // its time span.
  std::string trajectory;
  // Folder of photographs to texture with; empty: the opencv-doc samples when installed.
  std::string textures;
  bool procedural_textures = false;  // no photographs at all
  // Folder of RGBA PNG cut-outs for billboard actors; empty: box people.
  std::string billboards;
  int billboard_count = -1;  // actors drawn as billboards (-1: all when billboards is set)
  int actors = -1;           // -1: the scenario's default
  // A COCO class name (spaces or underscores) that relabels the actors; empty: the scenario's
  // own (Scenario::ActorClass).
  std::string actor_class;
  int width = 640;  // TUM fr3 intrinsics are scaled to this size
  int height = 480;
  double fps = 30.0;
  // The camera path runs this many times faster (a quickly moved hand-held camera: more motion
  // blur and rolling-shutter shear). A replayed recording then covers fewer frames.
  double camera_speed = 1.0;
  double start_stamp = kDefaultStartStamp;
  SensorOptions sensor;
  // Motion blur, rolling shutter, depth misregistration, calibration error, lens distortion:
  // all off by default.
  RealCameraOptions real_camera;
  std::string opencv_samples = kOpenCvDocDataFolder;

  // Throws Error naming the option (as its command-line flag) and the bad value.
  void Check() const;
  // The actors' class name (spaces, not underscores): actor_class, or the scenario's own.
  std::string ActorClassName() const;
  // The camera the images are rendered with: TUM fr3 intrinsics scaled to width x height, and
  // real_camera's lens distortion (none by default).
  CameraOptions Camera() const;
  // The camera settings.yaml states: Camera() with real_camera's calibration error.
  CameraOptions StatedCamera() const;
};

}  // namespace drvslam::synth
