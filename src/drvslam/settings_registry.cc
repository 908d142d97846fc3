#include "drvslam/settings_registry.h"

#include "drvslam/core/settings.h"
#include "drvslam/dense/dense_options.h"
#include "drvslam/dense/grid_options.h"
#include "drvslam/dynamic/dynamic_options.h"
#include "drvslam/loop/loop_closing_options.h"
#include "drvslam/loop/relocalization_options.h"
#include "drvslam/mapping/local_mapping_options.h"
#include "drvslam/semantic/segmentation_options.h"
#include "drvslam/tracking/tracker_options.h"

namespace drvslam {

const std::vector<OptionSection>& SettingsSections() {
  static const std::vector<OptionSection> sections = [] {
    std::vector<OptionSection> all = DescribeSettings();
    all.push_back(TrackerOptionTable().Describe());
    all.push_back(LocalMappingOptionTable().Describe());
    all.push_back(RelocalizationOptionTable().Describe());
    all.push_back(LoopClosingOptionTable().Describe());
    all.push_back(SegmentationOptionTable().Describe());
    all.push_back(DynamicOptionTable().Describe());
    all.push_back(DenseMapOptionTable().Describe());
    all.push_back(GridOptionTable().Describe());
    return all;
  }();
  return sections;
}

void CheckSettingsKeys(const SettingsFile& file, bool strict) {
  ReportUnknownSettings(file, SettingsSections(), strict);
}

}  // namespace drvslam
