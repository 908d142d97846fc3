// SynthSequence: one synthetic dynamic RGB-D sequence, fully built in memory - room, textures,
// camera path, simulated actors - ready to render any frame with its exact ground truth (pose,
// depth, instance mask, moving flags). The generator writes it to disk; tests and benchmarks
// render from it directly.
#pragma once

#include <string>
#include <vector>

#include "drvslam/core/camera.h"
#include "drvslam/core/se3.h"
#include "drvslam/core/settings.h"
#include "drvslam/io/trajectory_io.h"
#include "drvslam/tools/synth/actors.h"
#include "drvslam/tools/synth/camera_path.h"
#include "drvslam/tools/synth/instances_file.h"
#include "drvslam/tools/synth/rasterizer.h"
#include "drvslam/tools/synth/room_layout.h"
#include "drvslam/tools/synth/scenario.h"
#include "drvslam/tools/synth/scene_builder.h"
#include "drvslam/tools/synth/sensor_model.h"
#include "drvslam/tools/synth/shutter_renderer.h"
#include "drvslam/tools/synth/synth_options.h"
#include "drvslam/tools/synth/texture.h"

namespace drvslam::synth {

class SynthSequence {
 public:
  // Checks the options, reads the photos, billboards and trajectory they name, builds the room,
  // simulates the actors and paints every texture. Throws Error naming the option or file at
  // fault.
  explicit SynthSequence(const SynthOptions& options);

  const SynthOptions& Options() const { return options_; }
  const Scenario& GetScenario() const { return *scenario_; }
  const CameraOptions& Camera() const { return camera_; }
  const RoomLayout& Layout() const { return layout_; }
  const CameraPath& Path() const { return path_; }
  const StaticScene& Scene() const { return scene_; }
  const ActorSet& Actors() const { return actors_; }
  const std::vector<Texture>& Textures() const { return textures_; }
  // Where the textures came from: a photo folder, or "procedural".
  const std::string& TextureSource() const { return texture_source_; }

  int FrameCount() const { return static_cast<int>(stamps_.size()); }
  double Stamp(int frame) const { return stamps_[frame]; }    // absolute (s)
  double Time(int frame) const { return times_[frame]; }      // since the first frame (s)
  const SE3& Pose(int frame) const { return poses_[frame]; }  // T_wc
  Trajectory GroundTruth() const;

  // Actors first (ids 1..), then the static key objects (ids from kFirstObjectInstanceId).
  std::vector<SynthInstance> Instances() const;
  // Moving flag of each instance, in Instances() order.
  std::vector<bool> MovingFlags(int frame) const;
  InstancesFile MakeInstancesFile() const;

  // Renders a frame: exact geometry as the real-camera options expose it (rolling shutter,
  // motion blur, lens distortion, depth misregistration), then (unless apply_sensor is false)
  // the sensor's noise and holes. Thread-safe.
  RenderBuffers Render(int frame, bool apply_sensor = true) const;
  // The camera pose (T_wc) and the actors `offset` seconds after frame `frame`'s timestamp.
  SE3 PoseAt(int frame, double offset) const;
  void AppendMoversAt(int frame, double offset, TriangleList* movers) const;
  const ShutterRenderer& Shutter() const { return shutter_; }
  // Share of the image covered by actors in an instance image.
  double MoverCoverage(const cv::Mat& instance) const;

  // Camera (as stated, with the calibration error), depth and ORB settings for `drvslam run`,
  // and the scenario as "Synth.*" keys (with the real-camera effects when any is on).
  Settings MakeSettings() const;
  std::string SettingsExtraYaml() const;

 private:
  SynthOptions options_;
  const Scenario* scenario_ = nullptr;
  CameraOptions camera_;
  RoomLayout layout_;
  CameraPath path_;
  std::vector<double> stamps_;
  std::vector<double> times_;
  std::vector<SE3> poses_;
  StaticScene scene_;
  ActorSet actors_;
  std::vector<Texture> textures_;
  std::string texture_source_;
  ShutterRenderer shutter_;
  SensorModel sensor_;
};

}  // namespace drvslam::synth
