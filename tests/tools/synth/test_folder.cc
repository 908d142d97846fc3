#include "test_folder.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "test_support/temp_folder.h"

namespace drvslam::synth::testing {

TestFolder::TestFolder(const std::string& name) {
  path_ = drvslam::testing::UniqueTempFolder("drvslam_synth_" + name).string();
}

TestFolder::~TestFolder() {
  std::error_code error;
  std::filesystem::remove_all(path_, error);
}

std::string ReadFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

void WriteFileText(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

}  // namespace drvslam::synth::testing
