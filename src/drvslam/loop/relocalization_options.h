// RelocalizationOptions: how a lost tracker finds itself again ("Relocalization.*" keys beside
// the ORB-SLAM2 ones). Defaults follow ORB-SLAM2's Tracking::Relocalization.
#pragma once

#include <string>

#include "drvslam/core/option_table.h"
#include "drvslam/core/settings_file.h"

namespace drvslam {

struct RelocalizationOptions {
  // false: no relocalization; a lost tracker retries against its last reference keyframe.
  bool enabled = true;
  // Bag-of-words vocabulary file (text or binary; relative to the settings file's folder);
  // empty: the build's default vocabulary.
  std::string vocabulary;
  // Bag-of-words matches a candidate keyframe needs before PnP is tried.
  int min_bow_matches = 15;
  // PnP RANSAC (OpenCV solvePnPRansac with EPnP): iterations, inlier reprojection error in
  // pixels, and the inliers a hypothesis needs before it is refined.
  int ransac_iterations = 300;
  double ransac_reprojection_error = 4.0;
  int min_pnp_inliers = 10;
  // Inliers after pose-only optimization and guided search for the pose to be accepted.
  int min_inliers = 50;

  void Check() const;  // throws Error naming the bad key
};

// Every Relocalization.* key: name, type, bounds and doc, bound to its field (core/option_table.h).
const OptionTable<RelocalizationOptions>& RelocalizationOptionTable();

// Reads Relocalization.enabled, .vocabulary, .minBowMatches, .ransacIterations,
// .ransacReprojectionError, .minPnpInliers and .minInliers.
RelocalizationOptions LoadRelocalizationOptions(const SettingsFile& file);

}  // namespace drvslam
