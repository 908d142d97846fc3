#include "drvslam/tools/synth/synth_sequence.h"

#include <spdlog/spdlog.h>

#include <charconv>
#include <cmath>
#include <type_traits>

#include "drvslam/core/coco_classes.h"
#include "drvslam/core/error.h"
#include "drvslam/core/options_registry.h"
#include "drvslam/tools/synth/billboard.h"
#include "drvslam/tools/synth/depth_shift.h"
#include "drvslam/tools/synth/photo_library.h"
#include "drvslam/tools/synth/random.h"
#include "drvslam/tools/synth/texture_bank.h"

namespace drvslam::synth {
namespace {

// Replayed paths get a room that keeps the camera this far from every wall.
constexpr double kReplayWallMargin = 1.0;

const SynthOptions& Checked(const SynthOptions& options) {
  options.Check();
  return options;
}

template <typename T>
std::string Number(T value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  std::string text(buffer, result.ptr);
  if constexpr (std::is_floating_point_v<T>) {
    if (text.find_first_of(".en") == std::string::npos) text += ".0";
  }
  return text;
}

}  // namespace

SynthSequence::SynthSequence(const SynthOptions& options)
    : options_(Checked(options)),
      scenario_(&FindScenario(options.scenario)),
      camera_(options.Camera()),
      shutter_(options.Camera(), options.real_camera),
      sensor_(options.sensor, options.Camera(), SubSeed(options.seed, RandomStream::kSensor)) {
  const ViewAnchor anchor;
  int frames = options_.frames < 0 ? kDefaultFrames : options_.frames;
  double start = options_.start_stamp;
  if (!options_.trajectory.empty()) {
    const Trajectory recorded = ReadTumTrajectory(options_.trajectory);
    if (recorded.size() < 2) {
      throw Error(options_.trajectory + ": a replayed trajectory needs at least 2 poses");
    }
    path_ = CameraPath::Replay(recorded, anchor);
    start = path_.RecordedStart();
    const int available = static_cast<int>(std::floor(
                              path_.Duration() / options_.camera_speed * options_.fps + 1e-9)) +
                          1;
    if (options_.frames < 0) {
      frames = available;
    } else if (options_.frames > available) {
      spdlog::warn("{}: the recording covers {} frames at {} Hz; writing {}", options_.trajectory,
                   available, options_.fps, available);
      frames = available;
    }
  } else {
    path_ = CameraPath::Procedural(scenario_->path, anchor, options_.seed);
  }

  // Photographs last: the trajectory is the likelier mistake, and it reads faster.
  PhotoLibrary photos;
  if (!options_.procedural_textures) {
    photos = options_.textures.empty() ? PhotoLibrary::OpenCvSamples(options_.opencv_samples)
                                       : PhotoLibrary::FromFolder(options_.textures);
  }
  texture_source_ = photos.Source();
  std::vector<cv::Mat> billboards;
  if (!options_.billboards.empty()) billboards = LoadBillboards(options_.billboards);

  for (int f = 0; f < frames; ++f) {
    times_.push_back(f / options_.fps);
    stamps_.push_back(start + times_.back());
    poses_.push_back(path_.PoseAt(options_.camera_speed * times_.back()));
  }
  std::vector<Eigen::Vector3d> centres;
  for (const SE3& pose : poses_) centres.push_back(pose.Translation());
  if (path_.Kind() == PathKind::kReplay) layout_.Enclose(centres, kReplayWallMargin);

  TextureBank bank(camera_.fx / CameraOptions().fx);
  scene_ = BuildStaticScene(layout_, options_.seed, &bank);

  ActorOptions actor_options;
  actor_options.count = scenario_->motion == MotionKind::kStatic
                            ? 0
                            : (options_.actors >= 0 ? options_.actors : scenario_->default_actors);
  actor_options.behaviour = scenario_->motion == MotionKind::kSitting ? ActorBehaviour::kSitting
                                                                      : ActorBehaviour::kWalking;
  actor_options.shape =
      scenario_->motion == MotionKind::kPushed ? ActorShape::kCart : ActorShape::kPerson;
  actor_options.class_name = options_.ActorClassName();
  actor_options.coco_id = CocoClassId(actor_options.class_name);
  actor_options.billboards = billboards;
  actor_options.billboard_count =
      billboards.empty()
          ? 0
          : (options_.billboard_count < 0 ? actor_options.count : options_.billboard_count);
  actor_options.seed = options_.seed;
  actors_ = ActorSet(actor_options, layout_, times_, centres, &bank);

  spdlog::debug("synth: painting {} textures ({:.1f} Mtexels) from {}", bank.Size(),
                bank.TexelCount() / 1e6, texture_source_);
  textures_ = bank.Realize(photos);
}

Trajectory SynthSequence::GroundTruth() const {
  Trajectory trajectory;
  for (int f = 0; f < FrameCount(); ++f) trajectory.push_back({stamps_[f], poses_[f]});
  return trajectory;
}

std::vector<SynthInstance> SynthSequence::Instances() const {
  std::vector<SynthInstance> instances = actors_.Instances();
  instances.insert(instances.end(), scene_.instances.begin(), scene_.instances.end());
  return instances;
}

std::vector<bool> SynthSequence::MovingFlags(int frame) const {
  std::vector<bool> flags;
  for (int k = 0; k < actors_.Count(); ++k) flags.push_back(actors_.Moving(k, frame));
  flags.resize(flags.size() + scene_.instances.size(), false);
  return flags;
}

InstancesFile SynthSequence::MakeInstancesFile() const {
  InstancesFile file;
  file.instances = Instances();
  file.frame_stamps = stamps_;
  for (int f = 0; f < FrameCount(); ++f) file.moving.push_back(MovingFlags(f));
  return file;
}

RenderBuffers SynthSequence::Render(int frame, bool apply_sensor) const {
  if (frame < 0 || frame >= FrameCount()) {
    throw Error("synth: frame " + std::to_string(frame) + " is outside 0.." +
                std::to_string(FrameCount() - 1));
  }
  RenderBuffers buffers;
  shutter_.Render(
      scene_.triangles, textures_,
      [this, frame](double offset, SE3* T_cw, TriangleList* movers) {
        *T_cw = PoseAt(frame, offset).Inverse();
        AppendMoversAt(frame, offset, movers);
      },
      &buffers);
  const RealCameraOptions& real = options_.real_camera;
  if (real.DepthShift()) ShiftDepth(real.depth_shift_x, real.depth_shift_y, &buffers);
  if (apply_sensor) {
    const double t = times_[frame];
    const SE3 T_start_now = PoseAt(frame, -options_.sensor.exposure_time).Inverse() * poses_[frame];
    sensor_.Apply(frame, t, T_start_now, &buffers);
  }
  return buffers;
}

SE3 SynthSequence::PoseAt(int frame, double offset) const {
  return offset == 0.0 ? poses_[frame]
                       : path_.PoseAt(options_.camera_speed * (times_[frame] + offset));
}

void SynthSequence::AppendMoversAt(int frame, double offset, TriangleList* movers) const {
  if (offset == 0.0) {
    actors_.AppendTriangles(frame, movers);
  } else {
    actors_.AppendTrianglesAt(frame + offset * options_.fps, movers);
  }
}

double SynthSequence::MoverCoverage(const cv::Mat& instance) const {
  const int last_actor = actors_.Count();
  if (last_actor == 0 || instance.empty()) return 0.0;
  long long covered = 0;
  for (int y = 0; y < instance.rows; ++y) {
    const uint16_t* row = instance.ptr<uint16_t>(y);
    for (int x = 0; x < instance.cols; ++x) covered += row[x] >= 1 && row[x] <= last_actor;
  }
  return static_cast<double>(covered) / (static_cast<double>(instance.rows) * instance.cols);
}

Settings SynthSequence::MakeSettings() const {
  Settings settings;
  settings.camera = options_.real_camera.CalibrationError() ? options_.StatedCamera() : camera_;
  settings.depth.depth_map_factor = options_.sensor.depth_factor;
  return settings;
}

std::string SynthSequence::SettingsExtraYaml() const {
  const SensorOptions& s = options_.sensor;
  std::string yaml = "# Synthetic sequence written by drvslam synth\n";
  const auto add = [&yaml](const char* key, const std::string& value) {
    yaml += std::string("Synth.") + key + ": " + value + "\n";
  };
  const auto flag = [](bool on) { return std::string(on ? "1" : "0"); };
  add("Scenario", option_format::YamlText(scenario_->name));
  add("StaticCounterpart", option_format::YamlText(StaticCounterpart(*scenario_)));
  add("Seed", Number(static_cast<long long>(options_.seed)));
  add("Frames", Number(FrameCount()));
  add("Actors", Number(actors_.Count()));
  add("ActorClass", option_format::YamlText(actors_.Count() > 0 ? options_.ActorClassName() : ""));
  // A class no COCO model names (the carts) is a mover only when listed: ground-truth masks then
  // remove it as they remove people.
  const std::string actor_class = options_.ActorClassName();
  if (actors_.Count() > 0 && CocoClassId(actor_class) < 0) {
    std::vector<std::string> moving = DefaultMovingCocoClasses();
    moving.push_back(actor_class);
    yaml += "Segmentation.movingClasses: " + option_format::YamlList(moving) + "\n";
  }
  add("Billboards", option_format::YamlText(options_.billboards));
  add("Path", option_format::YamlText(PathKindName(path_.Kind())));
  add("Trajectory", option_format::YamlText(options_.trajectory));
  add("Textures", option_format::YamlText(texture_source_));
  add("RoomMinX", Number(layout_.min.x()));
  add("RoomMinY", Number(layout_.min.y()));
  add("RoomMinZ", Number(layout_.min.z()));
  add("RoomMaxX", Number(layout_.max.x()));
  add("RoomMaxY", Number(layout_.max.y()));
  add("RoomMaxZ", Number(layout_.max.z()));
  add("MovingThreshold", Number(kMovingThreshold));
  add("DepthNoise", flag(s.depth_noise));
  add("DepthNoiseCoeff", Number(s.depth_noise_coeff));
  add("DepthQuantization", flag(s.depth_quantization));
  add("EdgeHoles", flag(s.edge_holes));
  add("EdgeJumpRatio", Number(s.edge_jump_ratio));
  add("EdgeHoleProbability", Number(s.edge_hole_probability));
  add("GrazingHoles", flag(s.grazing_holes));
  add("GrazingAngleDeg", Number(s.grazing_angle_deg));
  add("RangeLimits", flag(s.range_limits));
  add("MinRange", Number(s.min_range));
  add("MaxRange", Number(s.max_range));
  add("ColorNoise", flag(s.color_noise));
  add("ColorNoiseSigma", Number(s.color_noise_sigma));
  add("Exposure", flag(s.exposure));
  add("ExposureAmplitude", Number(s.exposure_amplitude));
  add("MotionBlur", flag(s.motion_blur));
  add("ExposureTime", Number(s.exposure_time));
  add("BlurSamples", Number(s.blur_samples));
  // Written only when changed, as the real-camera keys below.
  if (options_.camera_speed != 1.0) add("CameraSpeed", Number(options_.camera_speed));
  const RealCameraOptions& r = options_.real_camera;
  if (!r.Any()) return yaml;  // sequences without them stay byte-identical to earlier ones
  yaml +=
      "# Real-camera effects. Timestamps and ground truth belong to the middle of the image\n"
      "# (rolling shutter: row r is exposed at t + ((r + 0.5) / height - 0.5) * readout).\n"
      "# Camera.* above states the calibration with its error; the truth is Synth.True*.\n";
  add("RealBlurExposure", Number(r.blur_exposure));
  add("RealBlurSamples", Number(r.blur_samples));
  add("RealRollingShutterReadout", Number(r.rolling_shutter_readout));
  add("RealRollingShutterSteps", Number(r.rolling_shutter_steps));
  add("RealDepthGlobalShutter", flag(r.depth_global_shutter));
  add("RealTimestampRow", option_format::YamlText("middle"));
  add("RealDepthShiftX", Number(r.depth_shift_x));
  add("RealDepthShiftY", Number(r.depth_shift_y));
  add("RealIntrinsicsError", Number(r.intrinsics_error));
  add("RealPrincipalPointErrorX", Number(r.principal_point_error_x));
  add("RealPrincipalPointErrorY", Number(r.principal_point_error_y));
  add("TrueFx", Number(camera_.fx));
  add("TrueFy", Number(camera_.fy));
  add("TrueCx", Number(camera_.cx));
  add("TrueCy", Number(camera_.cy));
  add("TrueK1", Number(camera_.k1));
  add("TrueK2", Number(camera_.k2));
  add("TrueP1", Number(camera_.p1));
  add("TrueP2", Number(camera_.p2));
  add("TrueK3", Number(camera_.k3));
  return yaml;
}

}  // namespace drvslam::synth
