#include "drvslam/core/settings.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string_view>
#include <type_traits>

#include "drvslam/core/error.h"
#include "drvslam/core/option_check.h"

namespace drvslam {
void DepthOptions::Check() const {
  RequireOption(std::isfinite(th_depth) && th_depth > 0, "ThDepth", th_depth,
                "must be a positive number");
  RequireOption(std::isfinite(depth_map_factor) && depth_map_factor > 0, "DepthMapFactor",
                depth_map_factor, "must be a positive number");
}

void OrbExtractorOptions::Check() const {
  RequireOption(n_features > 0 && n_features <= 100000, "ORBextractor.nFeatures", n_features,
                "must be in 1..100000");
  RequireOption(std::isfinite(scale_factor) && scale_factor > 1.0 && scale_factor <= 4.0,
                "ORBextractor.scaleFactor", scale_factor, "must be in (1, 4]");
  RequireOption(n_levels >= 1 && n_levels <= 32, "ORBextractor.nLevels", n_levels,
                "must be in 1..32");
  RequireOption(ini_th_fast >= 1 && ini_th_fast <= 255, "ORBextractor.iniThFAST", ini_th_fast,
                "must be in 1..255");
  RequireOption(min_th_fast >= 1 && min_th_fast <= ini_th_fast, "ORBextractor.minThFAST",
                min_th_fast, "must be in 1..iniThFAST");
}

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
  Settings s;
  CameraOptions& c = s.camera;
  c.fx = file.GetDouble("Camera.fx", c.fx);
  c.fy = file.GetDouble("Camera.fy", c.fy);
  c.cx = file.GetDouble("Camera.cx", c.cx);
  c.cy = file.GetDouble("Camera.cy", c.cy);
  c.k1 = file.GetDouble("Camera.k1", c.k1);
  c.k2 = file.GetDouble("Camera.k2", c.k2);
  c.p1 = file.GetDouble("Camera.p1", c.p1);
  c.p2 = file.GetDouble("Camera.p2", c.p2);
  c.k3 = file.GetDouble("Camera.k3", c.k3);
  c.width = file.GetInt("Camera.width", c.width);
  c.height = file.GetInt("Camera.height", c.height);
  c.fps = file.GetDouble("Camera.fps", c.fps);
  c.bf = file.GetDouble("Camera.bf", c.bf);
  c.rgb = file.GetBool("Camera.RGB", c.rgb);
  s.depth.th_depth = file.GetDouble("ThDepth", s.depth.th_depth);
  s.depth.depth_map_factor = file.GetDouble("DepthMapFactor", s.depth.depth_map_factor);
  OrbExtractorOptions& o = s.orb;
  o.n_features = file.GetInt("ORBextractor.nFeatures", o.n_features);
  o.scale_factor = file.GetDouble("ORBextractor.scaleFactor", o.scale_factor);
  o.n_levels = file.GetInt("ORBextractor.nLevels", o.n_levels);
  o.ini_th_fast = file.GetInt("ORBextractor.iniThFAST", o.ini_th_fast);
  o.min_th_fast = file.GetInt("ORBextractor.minThFAST", o.min_th_fast);
  try {
    s.camera.Check();
    s.depth.Check();
    s.orb.Check();
  } catch (const Error& e) {
    throw Error(file.Path() + ": " + e.what());
  }
  return s;
}

Settings LoadSettings(const std::string& path) {
  SettingsFile file(path);
  Settings settings = LoadSettings(file);
  file.LogUnreadKeys();
  return settings;
}

std::string FormatSettings(const Settings& s, const std::string& extra_yaml) {
  std::string text = "%YAML:1.0\n";
  const auto add = [&text](const char* key, auto value) {
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
    text += key;
    text += ": ";
    text.append(buffer, result.ptr);
    // A real written without a point would read back as an integer; keep the type visible.
    if constexpr (std::is_floating_point_v<decltype(value)>) {
      if (std::string_view(buffer, result.ptr - buffer).find_first_of(".en") ==
          std::string_view::npos) {
        text += ".0";
      }
    }
    text += "\n";
  };
  const CameraOptions& c = s.camera;
  add("Camera.fx", c.fx);
  add("Camera.fy", c.fy);
  add("Camera.cx", c.cx);
  add("Camera.cy", c.cy);
  add("Camera.k1", c.k1);
  add("Camera.k2", c.k2);
  add("Camera.p1", c.p1);
  add("Camera.p2", c.p2);
  add("Camera.k3", c.k3);
  add("Camera.width", c.width);
  add("Camera.height", c.height);
  add("Camera.fps", c.fps);
  add("Camera.bf", c.bf);
  add("Camera.RGB", c.rgb ? 1 : 0);
  add("ThDepth", s.depth.th_depth);
  add("DepthMapFactor", s.depth.depth_map_factor);
  const OrbExtractorOptions& o = s.orb;
  add("ORBextractor.nFeatures", o.n_features);
  add("ORBextractor.scaleFactor", o.scale_factor);
  add("ORBextractor.nLevels", o.n_levels);
  add("ORBextractor.iniThFAST", o.ini_th_fast);
  add("ORBextractor.minThFAST", o.min_th_fast);
  return text + extra_yaml;
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
