// ScratchFolderTest: a fixture that gives every test case its own empty folder, dir_, and removes
// it when the case ends. CTest runs the cases of one binary in parallel processes: the folder is
// made by UniqueTempFolder (the process id and a random part besides the suite's and the case's
// names), so it is never one that another process or user holds.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "test_support/temp_folder.h"

namespace drvslam::testing {

class ScratchFolderTest : public ::testing::Test {
 protected:
  // `subfolders` are made inside the folder, e.g. {"rgb", "depth"} for a TUM sequence.
  explicit ScratchFolderTest(std::vector<std::string> subfolders = {})
      : subfolders_(std::move(subfolders)) {}

  // A fixture that needs more in the folder calls this first from its own SetUp().
  void SetUp() override {
    const ::testing::TestInfo& info = *::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string("drvslam_") + info.test_suite_name() + "_" + info.name();
    std::replace(name.begin(), name.end(), '/', '_');  // parameterized names hold slashes
    dir_ = UniqueTempFolder(name);
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
