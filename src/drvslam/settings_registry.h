// Every settings section drvslam reads, gathered from the modules' option tables: what the
// unknown-key check, `drvslam config --dump` and docs/configuration.md are made from.
#pragma once

#include <vector>

#include "drvslam/core/options_registry.h"
#include "drvslam/core/settings_file.h"

namespace drvslam {

// In the order a settings file lists them: the ORB-SLAM2 keys (Camera.*, ThDepth,
// DepthMapFactor, ORBextractor.*), then drvslam's own sections.
const std::vector<OptionSection>& SettingsSections();

// Warns about each unknown key of `file` in one of those sections, naming the nearest known
// key; with `strict` (--strict-settings) throws one Error naming them all.
void CheckSettingsKeys(const SettingsFile& file, bool strict);

}  // namespace drvslam
