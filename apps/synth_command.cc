// `drvslam synth`: writes a synthetic dynamic RGB-D sequence with exact ground truth (TUM layout
// plus masks/, instances.txt and settings.yaml) and prints a short summary.
#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "command_registry.h"
#include "drvslam/core/error.h"
#include "drvslam/tools/synth/scenario.h"
#include "drvslam/tools/synth/synth_generator.h"
#include "progress_bar.h"

namespace drvslam::cli {
namespace {

struct SynthArguments {
  synth::SynthOptions options;
  std::string out;
  bool list = false;
  bool clean = false;
  bool no_depth_noise = false;
  bool no_holes = false;
  bool no_color_noise = false;
  bool no_exposure = false;
  bool motion_blur = false;
  // Real-camera effects: --real-camera sets them all, then the flags given override.
  bool real_camera = false;
  synth::RealCameraOptions real;
  std::string depth_shift, principal_point_error, distortion;
  std::vector<std::pair<CLI::Option*, std::function<void(synth::RealCameraOptions&)>>> overrides;
};

// A number as help text shows it: 0.015, not 0.015000.
std::string Short(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

// "X,Y" to two numbers; throws Error naming the flag.
std::pair<double, double> ParsePair(const std::string& flag, const std::string& text) {
  const std::size_t comma = text.find(',');
  double values[2] = {0.0, 0.0};
  bool ok = comma != std::string::npos && text.find(',', comma + 1) == std::string::npos;
  const std::string items[2] = {text.substr(0, comma), ok ? text.substr(comma + 1) : ""};
  for (int k = 0; k < 2 && ok; ++k) {
    char* end = nullptr;
    errno = 0;
    values[k] = std::strtod(items[k].c_str(), &end);
    ok = !items[k].empty() && end == items[k].c_str() + items[k].size() && errno == 0 &&
         std::isfinite(values[k]);
  }
  if (!ok) throw Error(flag + " '" + text + "' must be two numbers X,Y (pixels)");
  return {values[0], values[1]};
}

void ListScenarios() {
  for (const synth::Scenario& scenario : synth::Scenarios()) {
    std::printf("%-20s %s\n", scenario.name.c_str(), scenario.description.c_str());
  }
}

void PrintSummary(const synth::SynthSummary& s) {
  std::printf("scenario:    %s (static counterpart: %s), camera path %s\n", s.scenario.c_str(),
              s.static_counterpart.c_str(), s.path.c_str());
  std::printf("frames:      %d at %dx%d, %d actor%s\n", s.frames, s.width, s.height, s.actors,
              s.actors == 1 ? "" : "s");
  std::printf("textures:    %s\n", s.texture_source.c_str());
  std::printf(
      "speed:       %.1f fps rendering (with sensor effects), %.1f fps with PNG writing; "
      "setup %.2f s\n",
      s.render_fps, s.total_fps, s.setup_seconds);
  std::printf(
      "movers:      cover %.1f%% of the image at most, %.1f%% on average; moving in "
      "%.1f%% of actor-frames\n",
      100.0 * s.max_coverage, 100.0 * s.mean_coverage, 100.0 * s.moving_share);
  std::printf(
      "wrote:       %s/{rgb,depth,masks}/, rgb.txt, depth.txt, associations.txt, "
      "groundtruth.txt, instances.txt, settings.yaml\n",
      s.folder.c_str());
}

void RunSynth(SynthArguments& args) {
  if (args.list) {
    ListScenarios();
    return;
  }
  if (args.out.empty()) throw Error("synth: --out DIR is required (or --list)");
  synth::SensorOptions& sensor = args.options.sensor;
  if (args.clean) sensor = synth::SensorOptions::Clean();
  if (args.no_depth_noise) sensor.depth_noise = false;
  if (args.no_holes) sensor.edge_holes = sensor.grazing_holes = sensor.range_limits = false;
  if (args.no_color_noise) sensor.color_noise = false;
  if (args.no_exposure) sensor.exposure = false;
  if (args.motion_blur) sensor.motion_blur = true;
  synth::RealCameraOptions& real = args.options.real_camera;
  if (args.real_camera) real = synth::HandheldCamera();
  for (const auto& [option, apply] : args.overrides) {
    if (option->count() > 0) apply(real);
  }
  ProgressBar bar("synth");
  const synth::SynthSummary summary =
      synth::GenerateSequence(args.options, args.out, [&bar](int done, int total) {
        bar.Update(static_cast<std::size_t>(done), static_cast<std::size_t>(total));
      });
  PrintSummary(summary);
}

const bool kSynthCommandRegistered = RegisterCommand("synth", [](CLI::App& root) {
  auto args = std::make_shared<SynthArguments>();
  synth::SynthOptions& o = args->options;
  CLI::App* cmd = root.add_subcommand(
      "synth",
      "Synthetic dynamic RGB-D sequence with exact ground truth (poses, depth, instance masks, "
      "moving flags): a furnished room, people walking or sitting or carts pushed, a TUM-like "
      "camera path");
  cmd->add_option("--scenario", o.scenario, "one of: " + synth::ScenarioNames())
      ->capture_default_str();
  cmd->add_option("--out", args->out,
                  "output folder (new, empty, or an earlier synth output, which is replaced)");
  cmd->add_option("--frames", o.frames,
                  "number of frames (default: 300; with --trajectory the whole recording)");
  cmd->add_option("--seed", o.seed,
                  "random seed (room, textures, actors, camera shake, sensor noise); the same "
                  "seed gives byte-identical files")
      ->capture_default_str();
  cmd->add_option("--trajectory", o.trajectory,
                  "replay this TUM groundtruth.txt as the camera path (re-anchored in the room; "
                  "frames follow its time span)");
  cmd->add_option("--textures", o.textures,
                  "folder of photographs to texture the room with (default: the opencv-doc "
                  "samples when installed, else procedural textures)");
  cmd->add_flag("--procedural-textures", o.procedural_textures,
                "paint every texture procedurally (no photographs)");
  cmd->add_option("--actors", o.actors,
                  "number of actors (default: 2 for walking_*, sitting_* and pushed_*, 0 for "
                  "static_*)");
  cmd->add_option("--actor-class", o.actor_class,
                  "COCO class the actors are labelled with (default: person, or cart for "
                  "pushed_*, a class no COCO model names)");
  cmd->add_option("--billboards", o.billboards,
                  "folder of RGBA PNG cut-outs (e.g. people cut out of photographs; alpha 0 is "
                  "transparent): actors are drawn as these pictures, turned to the camera");
  cmd->add_option("--billboard-count", o.billboard_count,
                  "how many actors are billboards (default: all, with --billboards)");
  cmd->add_option("--width", o.width, "image width; TUM fr3 intrinsics are scaled to it")
      ->capture_default_str();
  cmd->add_option("--height", o.height, "image height")->capture_default_str();
  cmd->add_option("--camera-speed", o.camera_speed,
                  "the camera path runs this many times faster, as a quickly moved hand-held "
                  "camera (more blur and shear with --real-camera; e.g. 3)")
      ->capture_default_str();
  cmd->add_flag("--clean", args->clean,
                "no sensor effects at all: exact colour, exact depth (to the file's 1/5000 m)");
  cmd->add_flag("--no-depth-noise", args->no_depth_noise, "no Kinect-like depth noise");
  cmd->add_flag("--no-holes", args->no_holes,
                "no missing depth (at depth edges, grazing angles, out of range)");
  cmd->add_flag("--no-color-noise", args->no_color_noise, "no colour noise");
  cmd->add_flag("--no-exposure", args->no_exposure, "no auto-exposure brightness drift");
  cmd->add_flag("--motion-blur", args->motion_blur,
                "blur along the camera motion (off by default): a cheap approximation from "
                "one render and its depth, camera motion only; --blur-exposure renders it");
  cmd->add_option("--depth-noise", o.sensor.depth_noise_coeff,
                  "depth noise sigma per squared metre (sigma = value * z^2)")
      ->capture_default_str();
  cmd->add_option("--max-range", o.sensor.max_range, "no depth beyond this distance (m)")
      ->capture_default_str();
  // Real-camera effects.
  synth::RealCameraOptions& real = args->real;
  const synth::RealCameraOptions handheld = synth::HandheldCamera();
  // The overrides live inside *args: they point at it rather than own it (owning would be a
  // cycle, and the arguments would never be freed).
  SynthArguments* const self = args.get();
  const auto real_option = [&](const std::string& name, auto* value, const std::string& help,
                               auto apply) {
    CLI::Option* option = cmd->add_option(name, *value, help)->capture_default_str();
    args->overrides.emplace_back(option, apply);
  };
  real_option("--blur-exposure", &real.blur_exposure,
              "motion blur: exposure time in seconds, centred on each row's time, camera and "
              "actors moving (0 = off; --real-camera: " +
                  Short(handheld.blur_exposure) + ")",
              [self](synth::RealCameraOptions& r) { r.blur_exposure = self->real.blur_exposure; });
  real_option("--blur-samples", &real.blur_samples,
              "renders averaged per blurred frame (odd: the middle one gives depth and masks)",
              [self](synth::RealCameraOptions& r) { r.blur_samples = self->real.blur_samples; });
  real_option("--rolling-shutter", &real.rolling_shutter_readout,
              "rolling shutter: readout time in seconds from the top row to the bottom one; the "
              "timestamp and ground truth belong to the image's middle (0 = off; --real-camera: " +
                  Short(handheld.rolling_shutter_readout) + ")",
              [self](synth::RealCameraOptions& r) {
                r.rolling_shutter_readout = self->real.rolling_shutter_readout;
              });
  real_option("--rolling-shutter-steps", &real.rolling_shutter_steps,
              "bands of rows that share one exposure time", [self](synth::RealCameraOptions& r) {
                r.rolling_shutter_steps = self->real.rolling_shutter_steps;
              });
  args->overrides.emplace_back(
      cmd->add_option("--depth-global-shutter", real.depth_global_shutter,
                      "1: with --rolling-shutter, depth is captured at once at the timestamp (a "
                      "RealSense's global-shutter depth sensor), so moving depth misregisters "
                      "against the colour rows; 0: depth follows the colour rows (a Kinect v1; "
                      "--real-camera: 1)")
          ->capture_default_str(),
      [self](synth::RealCameraOptions& r) {
        r.depth_global_shutter = self->real.depth_global_shutter;
      });
  real_option("--depth-shift", &args->depth_shift,
              "DX,DY: depth misregistered against colour by this many pixels (sub-pixel "
              "allowed; depth at (x, y) is the true depth at (x - DX, y - DY); masks stay with "
              "colour; --real-camera: 1.5,1)",
              [self](synth::RealCameraOptions& r) {
                std::tie(r.depth_shift_x, r.depth_shift_y) =
                    ParsePair("--depth-shift", self->depth_shift);
              });
  real_option(
      "--intrinsics-error", &real.intrinsics_error,
      "settings.yaml states fx, fy (and bf) this fraction larger than the truth "
      "(0.03 = 3 %; --real-camera: 0.03); Synth.TrueFx.. keep the truth",
      [self](synth::RealCameraOptions& r) { r.intrinsics_error = self->real.intrinsics_error; });
  real_option("--principal-point-error", &args->principal_point_error,
              "DX,DY: settings.yaml states cx, cy moved by this many pixels",
              [self](synth::RealCameraOptions& r) {
                std::tie(r.principal_point_error_x, r.principal_point_error_y) =
                    ParsePair("--principal-point-error", self->principal_point_error);
              });
  real_option("--distortion", &args->distortion,
              "lens distortion k1,k2,p1,p2,k3 (OpenCV radial-tangential; missing ones are 0) or "
              "fr1 / fr2 (the TUM calibrations): images are rendered through it and "
              "settings.yaml states it as Camera.k1..k3 (--real-camera: fr1)",
              [self](synth::RealCameraOptions& r) { r.SetDistortion(self->distortion); });
  cmd->add_flag("--real-camera", args->real_camera,
                "a quickly moved hand-held real camera: --blur-exposure 0.015 --rolling-shutter "
                "0.025 --depth-global-shutter 1 --depth-shift 1.5,1 --intrinsics-error 0.03 "
                "--distortion fr1; the flags "
                "above, when given, override these");
  cmd->add_flag("--list", args->list, "list the scenarios and exit");
  cmd->callback([args] { RunSynth(*args); });
});

}  // namespace
}  // namespace drvslam::cli
