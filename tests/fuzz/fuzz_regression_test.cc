// Every seed of fuzz/corpus/<name>/ and every input that once found a bug
// (fuzz/regressions/<name>/) through its fuzz body: the body must return, so the parser either
// accepts the input or rejects it with drvslam::Error. A crash, another exception or (in the
// sanitizer trees) a sanitizer report fails the test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_bodies/fuzz_bodies.h"

namespace drvslam::fuzz {
namespace {

namespace fs = std::filesystem;

const fs::path kFuzzDir = fs::path(DRVSLAM_SOURCE_DIR) / "fuzz";

std::vector<fs::path> FilesIn(const fs::path& folder) {
  std::vector<fs::path> files;
  if (!fs::is_directory(folder)) return files;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::uint8_t> ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in),
                                   std::istreambuf_iterator<char>());
}

class FuzzRegressionTest : public testing::TestWithParam<FuzzBody> {};

TEST_P(FuzzRegressionTest, EveryCorpusAndRegressionInputIsAcceptedOrRejectedWithAnError) {
  SilenceLogging();
  const FuzzBody& body = GetParam();
  const std::vector<fs::path> seeds = FilesIn(kFuzzDir / "corpus" / body.name);
  // A body without seeds would pass without running anything.
  ASSERT_FALSE(seeds.empty()) << "no seeds in " << (kFuzzDir / "corpus" / body.name);
  std::vector<fs::path> inputs = seeds;
  const std::vector<fs::path> regressions = FilesIn(kFuzzDir / "regressions" / body.name);
  inputs.insert(inputs.end(), regressions.begin(), regressions.end());
  for (const fs::path& input : inputs) {
    SCOPED_TRACE(input.string());
    const std::vector<std::uint8_t> bytes = ReadBytes(input);
    EXPECT_NO_THROW(body.run(bytes.data(), bytes.size()));
  }
}

INSTANTIATE_TEST_SUITE_P(Bodies, FuzzRegressionTest, testing::ValuesIn(FuzzBodies()),
                         [](const testing::TestParamInfo<FuzzBody>& info) {
                           return std::string(info.param.name);
                         });

// The body table holds every fuzzer that has a corpus, so no corpus goes unreplayed.
TEST(FuzzRegressionSetTest, EveryCorpusFolderHasABody) {
  std::vector<std::string> names;
  for (const FuzzBody& body : FuzzBodies()) names.emplace_back(body.name);
  for (const fs::directory_entry& entry : fs::directory_iterator(kFuzzDir / "corpus")) {
    const std::string name = entry.path().filename().string();
#ifndef DRVSLAM_FUZZ_ROS2
    if (name == "ros2_image") continue;  // built only with Cyclone DDS
#endif
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  }
}

}  // namespace
}  // namespace drvslam::fuzz
