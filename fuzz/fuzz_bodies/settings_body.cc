// `--config`: the bytes as a settings file, read the way the runner resolves one (SettingsFile
// over OpenCV's FileStorage, then every module's option loader with its checks, then the
// unknown-key check of the option registry, lenient and --strict-settings).
#include <string>

#include "drvslam/core/settings.h"
#include "drvslam/dense/dense_options.h"
#include "drvslam/dense/grid_options.h"
#include "drvslam/dynamic/dynamic_options.h"
#include "drvslam/loop/loop_closing_options.h"
#include "drvslam/loop/relocalization_options.h"
#include "drvslam/mapping/local_mapping_options.h"
#include "drvslam/semantic/segmentation_options.h"
#include "drvslam/settings_registry.h"
#include "drvslam/tracking/tracker_options.h"
#include "fuzz_bodies/fuzz_bodies.h"
#include "fuzz_bodies/rejection.h"
#include "fuzz_bodies/scratch_file.h"

namespace drvslam::fuzz {

void RunSettingsBody(const std::uint8_t* data, std::size_t size) {
  const std::string path = WriteScratchFile("settings.yaml", data, size);
  AllowRejection([&] {
    const SettingsFile file(path);
    // Each loader on its own, so one section's rejection does not hide the next one's parser.
    AllowRejection([&] { LoadSettings(file); });
    AllowRejection([&] { LoadTrackerOptions(file); });
    AllowRejection([&] { LoadLocalMappingOptions(file); });
    AllowRejection([&] { LoadSegmentationOptions(file); });
    AllowRejection([&] { LoadDynamicOptions(file); });
    AllowRejection([&] { LoadRelocalizationOptions(file); });
    AllowRejection([&] { LoadDenseMapOptions(file); });
    AllowRejection([&] { LoadGridOptions(file); });
    AllowRejection([&] { LoadLoopClosingOptions(file); });
    AllowRejection([&] { CheckSettingsKeys(file, false); });
    AllowRejection([&] { CheckSettingsKeys(file, true); });
  });
}

}  // namespace drvslam::fuzz
