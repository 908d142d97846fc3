// TestFolder: a fresh temporary folder for one test, removed again when the test ends.
#pragma once

#include <string>

namespace drvslam::synth::testing {

class TestFolder {
 public:
  explicit TestFolder(const std::string& name);
  ~TestFolder();
  TestFolder(const TestFolder&) = delete;
  TestFolder& operator=(const TestFolder&) = delete;

  const std::string& Path() const { return path_; }
  // Path of an entry inside the folder.
  std::string operator/(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

// The whole contents of a file (empty when it cannot be read).
std::string ReadFileBytes(const std::string& path);
// Writes `text` to `path`.
void WriteFileText(const std::string& path, const std::string& text);

}  // namespace drvslam::synth::testing
