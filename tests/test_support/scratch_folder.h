// ScratchFolderTest: a fixture that gives every test case its own empty folder, dir_, and removes
// it when the case ends. CTest runs the cases of one binary in parallel processes, so the folder's
// name holds the process id besides the suite's and the case's names.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace drvslam::testing {

class ScratchFolderTest : public ::testing::Test {
 protected:
  // `subfolders` are made inside the folder, e.g. {"rgb", "depth"} for a TUM sequence.
  explicit ScratchFolderTest(std::vector<std::string> subfolders = {})
      : subfolders_(std::move(subfolders)) {}

  // A fixture that needs more in the folder calls this first from its own SetUp().
  void SetUp() override {
    const ::testing::TestInfo& info = *::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string("drvslam_") + info.test_suite_name() + "_" +
                       std::to_string(::getpid()) + "_" + info.name();
    std::replace(name.begin(), name.end(), '/', '_');  // parameterized names hold slashes
    dir_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    for (const std::string& subfolder : subfolders_) {
      std::filesystem::create_directories(dir_ / subfolder);
    }
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path dir_;

 private:
  std::vector<std::string> subfolders_;
};

}  // namespace drvslam::testing
