// Settings: the ORB-SLAM2-compatible part of a settings file (camera, depth sensor, ORB
// extractor) as typed options structs. Modules added later read their own sections
// (System.*, Segmentation.*, Dynamic.*, DenseMap.*) from the same SettingsFile.
#pragma once

#include <string>
#include <vector>

#include "drvslam/core/camera.h"
#include "drvslam/core/option_table.h"
#include "drvslam/core/settings_file.h"

namespace drvslam {

struct DepthOptions {
  // Points closer than th_depth baselines count as "close" (reliable depth), as in ORB-SLAM2.
  double th_depth = 40.0;
  // Raw 16-bit depth value per metre (5000 for TUM).
  double depth_map_factor = 5000.0;

  void Check() const;
  // Largest depth (metres) counted as reliable: th_depth * bf / fx.
  double CloseDepth(const CameraOptions& camera) const { return th_depth * camera.bf / camera.fx; }
};

struct OrbExtractorOptions {
  int n_features = 1000;
  double scale_factor = 1.2;
  int n_levels = 8;
  int ini_th_fast = 20;
  int min_th_fast = 7;
  // Threads that extract one image: 2 splits the pyramid levels between the calling thread and
  // one helper thread (the same features, bit for bit).
  int threads = 2;
  // With a live camera (--realtime, with the dynamic stage on: the live camera is its realtime
  // mode), the smallest share of n_features tracking extracts while frames are being skipped
  // (tracking/feature_budget.h); 1 always extracts n_features.
  double load_shedding_floor = 1.0;

  void Check() const;
};

struct Settings {
  CameraOptions camera;
  DepthOptions depth;
  OrbExtractorOptions orb;
};

// The keys of Camera.*, the top-level ThDepth and DepthMapFactor, and ORBextractor.*.
const OptionTable<CameraOptions>& CameraOptionTable();
const OptionTable<DepthOptions>& DepthOptionTable();
const OptionTable<OrbExtractorOptions>& OrbExtractorOptionTable();
// Those three sections, as the registry lists them.
std::vector<OptionSection> DescribeSettings();

// Reads Camera.*, ThDepth, DepthMapFactor and ORBextractor.* (absent keys keep their defaults)
// and checks them. Errors name the file, the key and the value.
Settings LoadSettings(const SettingsFile& file);
// Opens `path`, loads the settings above and logs the keys no one read.
Settings LoadSettings(const std::string& path);
// The same keys as YAML text ("%YAML:1.0" header first), numbers in their shortest exact form,
// so a written file loads back to equal values. cv::FileStorage cannot write dotted keys, hence
// text. `extra_yaml` (more "Key: value" lines, e.g. a scenario's parameters) is appended as is.
std::string FormatSettings(const Settings& settings, const std::string& extra_yaml = "");
// Writes FormatSettings() to `path`; throws Error when the file cannot be written.
void WriteSettings(const Settings& settings, const std::string& path,
                   const std::string& extra_yaml = "");

}  // namespace drvslam
