#include "drvslam/core/settings.h"

#include <fstream>

#include "drvslam/core/error.h"

namespace drvslam {
void DepthOptions::Check() const { DepthOptionTable().Check(*this); }

void OrbExtractorOptions::Check() const { OrbExtractorOptionTable().Check(*this); }

const OptionTable<CameraOptions>& CameraOptionTable() {
  static const OptionTable<CameraOptions> table = [] {
    using C = CameraOptions;
    OptionTable<C> t("Camera",
                     "pinhole intrinsics and lens distortion of the colour camera (ORB-SLAM2 keys; "
                     "the defaults are TUM fr3's, as synthetic sequences use)");
    t.Real("fx", &C::fx, Bounds::Above(0), "Focal length along x, pixels.")
        .Real("fy", &C::fy, Bounds::Above(0), "Focal length along y, pixels.")
        .Real("cx", &C::cx, Bounds::Any(), "Principal point x, pixels.")
        .Real("cy", &C::cy, Bounds::Any(), "Principal point y, pixels.")
        .Real("k1", &C::k1, Bounds::Any(), "Radial distortion k1 (OpenCV model; 0: none).")
        .Real("k2", &C::k2, Bounds::Any(), "Radial distortion k2.")
        .Real("p1", &C::p1, Bounds::Any(), "Tangential distortion p1.")
        .Real("p2", &C::p2, Bounds::Any(), "Tangential distortion p2.")
        .Real("k3", &C::k3, Bounds::Any(), "Radial distortion k3.")
        .Int("width", &C::width, Bounds::In(1, 16384),
             "Image width, pixels; frames of another size are an error.")
        .Int("height", &C::height, Bounds::In(1, 16384), "Image height, pixels.")
        .Real("fps", &C::fps, Bounds::Above(0),
              "Frame rate; a keyframe is due at the latest after this many frames by default.")
        .Real("bf", &C::bf, Bounds::Above(0),
              "Virtual stereo baseline times fx (pixels x metres) for RGB-D's right coordinate.")
        .Bool("RGB", &C::rgb, "1: images are stored RGB; 0: BGR.");
    return t;
  }();
  return table;
}

const OptionTable<DepthOptions>& DepthOptionTable() {
  static const OptionTable<DepthOptions> table = [] {
    OptionTable<DepthOptions> t("", "the depth sensor (ORB-SLAM2 keys)");
    t.Real("ThDepth", &DepthOptions::th_depth, Bounds::Above(0),
           "Points closer than ThDepth * bf / fx metres have reliable (close) depth.")
        .Real("DepthMapFactor", &DepthOptions::depth_map_factor, Bounds::Above(0),
              "Raw 16-bit depth value per metre (5000 for TUM).");
    return t;
  }();
  return table;
}

const OptionTable<OrbExtractorOptions>& OrbExtractorOptionTable() {
  static const OptionTable<OrbExtractorOptions> table = [] {
    using O = OrbExtractorOptions;
    OptionTable<O> t("ORBextractor", "ORB features per frame (ORB-SLAM2 keys)");
    t.Int("nFeatures", &O::n_features, Bounds::In(1, 100000),
          "Features extracted per frame (before the dynamic stage raises it).")
        .Real("scaleFactor", &O::scale_factor, Bounds::AboveUpTo(1, 4),
              "Scale between pyramid levels.")
        .Int("nLevels", &O::n_levels, Bounds::In(1, 32), "Pyramid levels.")
        .Int("iniThFAST", &O::ini_th_fast, Bounds::In(1, 255), "FAST threshold tried first.")
        .Int("minThFAST", &O::min_th_fast, Bounds::AtLeast(1),
             "FAST threshold of cells where the first finds no corner.")
        .Int("threads", &O::threads, Bounds::In(1, 2),
             "Threads extracting one image: 2 gives half the pyramid levels to a helper thread "
             "(same features; --sequential always uses 1).")
        .Real("loadSheddingFloor", &O::load_shedding_floor, Bounds::AboveUpTo(0, 1),
              "With a live camera (--realtime, dynamic stage on): while frames are skipped, "
              "extract fewer features, down to this share of nFeatures, so that tracking keeps "
              "up (1: never fewer).")
        .Rule(
            "minThFAST", [](const O& o) { return o.min_th_fast <= o.ini_th_fast; },
            "must not exceed ORBextractor.iniThFAST");
    return t;
  }();
  return table;
}

std::vector<OptionSection> DescribeSettings() {
  return {CameraOptionTable().Describe(), DepthOptionTable().Describe(),
          OrbExtractorOptionTable().Describe()};
}

Settings LoadSettings(const SettingsFile& file) {
  Settings settings;
  settings.camera = CameraOptionTable().Load(file);
  settings.depth = DepthOptionTable().Load(file);
  settings.orb = OrbExtractorOptionTable().Load(file);
  return settings;
}

Settings LoadSettings(const std::string& path) {
  SettingsFile file(path);
  Settings settings = LoadSettings(file);
  file.LogUnreadKeys();
  return settings;
}

std::string FormatSettings(const Settings& s, const std::string& extra_yaml) {
  return "%YAML:1.0\n" + CameraOptionTable().Yaml(s.camera) + DepthOptionTable().Yaml(s.depth) +
         OrbExtractorOptionTable().Yaml(s.orb) + extra_yaml;
}

void WriteSettings(const Settings& settings, const std::string& path,
                   const std::string& extra_yaml) {
  std::ofstream out(path);
  if (!out) throw Error(path + ": cannot open for writing");
  out << FormatSettings(settings, extra_yaml);
  out.flush();
  if (!out) throw Error(path + ": write failed");
}

}  // namespace drvslam
