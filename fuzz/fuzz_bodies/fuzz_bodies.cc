#include "fuzz_bodies/fuzz_bodies.h"

#include <spdlog/spdlog.h>

namespace drvslam::fuzz {

const std::vector<FuzzBody>& FuzzBodies() {
  static const std::vector<FuzzBody> bodies = {
      {"map_file", RunMapFileBody},      {"onnx_metadata", RunOnnxMetadataBody},
#ifdef DRVSLAM_FUZZ_ROS2
      {"ros2_image", RunRos2ImageBody},
#endif
      {"settings", RunSettingsBody},     {"tum_text", RunTumTextBody},
      {"vocabulary", RunVocabularyBody},
  };
  return bodies;
}

void SilenceLogging() { spdlog::set_level(spdlog::level::off); }

}  // namespace drvslam::fuzz
