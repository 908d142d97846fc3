// Whether a saved map can be loaded into a run: same image size and ORB pyramid (else an
// error), the same vocabulary (else an error: the saved bags of words would mean other words),
// intrinsics that differ by at most kIntrinsicsTolerance (else an error; any smaller difference
// is a warning: tracking then works through a slightly wrong calibration), and the settings
// digest (a difference is a warning: e.g. another feature count still tracks).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "drvslam/core/settings.h"
#include "drvslam/loop/bow_vocabulary.h"
#include "drvslam/mapfile/map_file.h"

namespace drvslam {

// Largest relative difference of fx, fy, bf, and of cx, cy relative to the image size, and
// the largest absolute difference of a distortion coefficient, that still loads (with a
// warning).
inline constexpr double kIntrinsicsTolerance = 0.02;

// The vocabulary's size and a hash of its tree (node parents, descriptors, word weights).
VocabularyIdentity IdentifyVocabulary(const BowVocabulary& vocabulary);

// A hash of the settings (FormatSettings text): camera, depth and ORB extractor keys.
uint64_t SettingsDigest(const Settings& settings);

// Throws drvslam::Error naming `path` when the map cannot be used with these settings and
// vocabulary (null: none loaded); returns the warnings for differences it tolerates.
std::vector<std::string> CheckMapCompatibility(const MapFileContents& contents,
                                               const Settings& settings,
                                               const BowVocabulary* vocabulary,
                                               const std::string& path);

}  // namespace drvslam
