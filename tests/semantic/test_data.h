// Paths of the shared models and opencv-doc photographs the semantic tests use; each returns an
// empty string when the file is absent so the test can skip with a clear message.
#pragma once

#include <filesystem>
#include <string>

#include "test_support/missing_data.h"
#include "test_support/temp_folder.h"

namespace drvslam::testing {

inline std::string ExistingOrEmpty(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec) ? path : std::string();
}

inline std::string SharedModel(const std::string& name) {
  return ExistingOrEmpty(std::string(DRVSLAM_SHARED_DIR) + "/models/" + name);
}

inline std::string OpenCvData(const std::string& name) {
  return ExistingOrEmpty(std::string(DRVSLAM_OPENCV_DATA_DIR) + "/" + name);
}

// An empty folder for one test in this process's own temporary folder (ProcessTempFolder,
// removed when the process ends): apart from other test processes' and other users' folders.
inline std::filesystem::path FreshTempDir(const std::string& name) {
  const std::filesystem::path dir = ProcessTempFolder() / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace drvslam::testing

// Skips the current test when `path` is empty, naming what is missing.
#define DRVSLAM_SKIP_IF_MISSING(path, what)                                       \
  do {                                                                            \
    if ((path).empty())                                                           \
      DRVSLAM_MISSING_TEST_DATA() << what << " not found (see shared/README.md)"; \
  } while (0)
