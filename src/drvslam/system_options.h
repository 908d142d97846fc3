// SystemOptions: what a System runs beyond the ORB-SLAM2 settings (core/settings.h) and the
// tracker's options (tracking/tracker_options.h): the threads, dynamic-object handling, dense
// mapping, relocalization and loop closing. Each part is loaded from its own settings section
// by the loader named in its header.
#pragma once

#include <optional>
#include <string>

#include "drvslam/dense/dense_options.h"
#include "drvslam/dynamic/dynamic_front_end.h"
#include "drvslam/loop/loop_closing_options.h"
#include "drvslam/loop/relocalization_options.h"
#include "drvslam/mapping/local_mapping_options.h"

namespace drvslam {

struct SystemOptions {
  // Run every stage in order on the caller's thread (deterministic, bit-identical results).
  bool sequential = false;
  LocalMappingOptions mapping;
  // Dynamic-object handling (segmentation, motion consistency, feature removal); nullopt runs
  // plain ORB-SLAM2 tracking. Its `sequential` follows the field above.
  std::optional<DynamicFrontEndConfig> dynamic;
  // The dense mapping thread (DenseMap.*); nullopt or enabled = false: no dense map.
  std::optional<DenseMapOptions> dense;
  // Relocalization when tracking is lost (needs a vocabulary: the file named there or the
  // build's default; without either it is off, with a warning).
  RelocalizationOptions relocalization;
  // The loop closing thread (LoopClosing.*); it needs the vocabulary relocalization loads, so
  // with relocalization off (or no vocabulary) it is off too, with a warning.
  LoopClosingOptions loop;
  // A map file (System::SaveMap) to start from: its keyframes, points and graph (and, with
  // dense mapping on, its dense map) are loaded before the first frame, which is relocalized in
  // it. Needs the vocabulary the map was saved with. Empty: start a new map.
  std::string load_map;
  // With load_map: track against the loaded map only, adding no keyframes or map points, and
  // relocalize whenever lost (local mapping and loop closing then have nothing to do). Without
  // it a loaded map is extended, and loop closing can join new keyframes to loaded ones.
  bool localization = false;
};

}  // namespace drvslam
