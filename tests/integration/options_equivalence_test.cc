// The option tables load exactly what the hand-written Load*Options functions loaded: the same
// defaults, the same values from every config in configs/, and for every key a spread of valid,
// out-of-range and wrongly typed values, both loaders accept the same files and give equal
// fields (compared key by key), or both reject them.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/core/settings.h"
#include "drvslam/dense/dense_options.h"
#include "drvslam/dynamic/dynamic_options.h"
#include "drvslam/loop/loop_closing_options.h"
#include "drvslam/loop/relocalization_options.h"
#include "drvslam/mapping/local_mapping_options.h"
#include "drvslam/semantic/segmentation_options.h"
#include "drvslam/settings_registry.h"
#include "drvslam/tracking/tracker_options.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

// Values tried for a key of this type with this default.
std::vector<std::string> Trials(const OptionInfo& option) {
  if (option.type == "bool") return {"0", "1", "true", "false", "2", "maybe"};
  if (option.type == "text") return {"\"abc\"", "\"\"", "\"cat\"", "\"person\"", "3"};
  if (option.type == "path") return {"\"voc.txt\"", "\"/abs/voc.txt\"", "\"\"", "\"a/../b.bin\""};
  if (option.type == "list") {
    return {"[ \"a\", \"b\" ]", "\"a, b\"", "[ \"\", \"x\" ]", "\"\"", "4"};
  }
  if (option.type == "choice") {
    std::vector<std::string> values = {"\"bogus\"", "7"};
    std::string rest = option.allowed;
    while (!rest.empty()) {
      const std::size_t bar = rest.find(" | ");
      values.push_back("\"" + rest.substr(0, bar) + "\"");
      rest = bar == std::string::npos ? "" : rest.substr(bar + 3);
    }
    return values;
  }
  const double d = std::stod(option.default_value);
  std::vector<std::string> values = {"\"text\"", "0",     "-1",     "1",     "2",
                                     "7",        "255",   "256",    "1000",  "1001",
                                     "16384",    "16385", "100000", "100001"};
  const auto add = [&values](double value) {
    values.push_back(std::to_string(value));
    values.push_back(std::to_string(static_cast<long long>(value)));
  };
  add(d + 1);
  add(d - 1);
  add(d * 2 + 3);
  add(-d);
  if (option.type == "real") {
    for (const double v : {d * 1.5 + 0.1, d * 0.5, 0.125, 0.124, 0.001, 0.0009, 0.005, 0.004, 0.5,
                           0.99, 1.0001, 1.5, 2.5, 4.0, 4.01, 8.5, 50.5, 100.5, 1e9}) {
      values.push_back(std::to_string(v));
    }
  } else {
    values.push_back("1.5");
    values.push_back(std::to_string(d) + "1");
  }
  return values;
}

// Loads `file` with `old_loader` and `new_loader`: "" when both give equal fields
// (`differences` lists the keys that differ), "rejected" when both reject it with an error naming
// the file, else what disagreed.
template <typename Options>
std::function<std::string(const SettingsFile&)> Compare(
    std::function<Options(const SettingsFile&)> old_loader,
    std::function<Options(const SettingsFile&)> new_loader,
    std::function<std::vector<std::string>(const Options&, const Options&)> differences) {
  return [=](const SettingsFile& file) -> std::string {
    Options old_result;
    Options new_result;
    std::string old_error;
    std::string new_error;
    try {
      old_result = old_loader(file);
    } catch (const Error& e) {
      old_error = e.what();
    }
    try {
      new_result = new_loader(file);
    } catch (const Error& e) {
      new_error = e.what();
    }
    if (old_error.empty() != new_error.empty()) {
      return "old: '" + old_error + "', new: '" + new_error + "'";
    }
    if (!old_error.empty()) {
      if (new_error.rfind(file.Path() + ": ", 0) != 0) return "new error lacks path: " + new_error;
      return "rejected";
    }
    std::string differing;
    for (const std::string& key : differences(old_result, new_result)) differing += key + " ";
    return differing.empty() ? "" : "fields differ: " + differing;
  };
}

template <typename Options>
std::function<std::string(const SettingsFile&)> Compare(
    std::function<Options(const SettingsFile&)> old_loader, const OptionTable<Options>& table) {
  return Compare<Options>(
      old_loader, [&table](const SettingsFile& file) { return table.Load(file); },
      [&table](const Options& a, const Options& b) { return table.Differences(a, b); });
}

// The old LoadSettings read Camera.*, ThDepth, DepthMapFactor and ORBextractor.* and checked
// them together: the three tables together must accept and reject the same files.
std::function<std::string(const SettingsFile&)> CompareSettings() {
  return Compare<Settings>(
      [](const SettingsFile& file) { return LoadSettings(file); },
      [](const SettingsFile& file) {
        Settings settings;
        settings.camera = CameraOptionTable().Load(file);
        settings.depth = DepthOptionTable().Load(file);
        settings.orb = OrbExtractorOptionTable().Load(file);
        return settings;
      },
      [](const Settings& a, const Settings& b) {
        std::vector<std::string> keys = CameraOptionTable().Differences(a.camera, b.camera);
        for (const std::string& key : DepthOptionTable().Differences(a.depth, b.depth)) {
          keys.push_back(key);
        }
        for (const std::string& key : OrbExtractorOptionTable().Differences(a.orb, b.orb)) {
          keys.push_back(key);
        }
        return keys;
      });
}

std::vector<std::function<std::string(const SettingsFile&)>> AllComparisons() {
  return {
      CompareSettings(),
      Compare<TrackerOptions>(LoadTrackerOptions, TrackerOptionTable()),
      Compare<LocalMappingOptions>(LoadLocalMappingOptions, LocalMappingOptionTable()),
      Compare<RelocalizationOptions>(LoadRelocalizationOptions, RelocalizationOptionTable()),
      Compare<LoopClosingOptions>(LoadLoopClosingOptions, LoopClosingOptionTable()),
      Compare<SegmentationOptions>(LoadSegmentationOptions, SegmentationOptionTable()),
      Compare<DynamicOptions>(LoadDynamicOptions, DynamicOptionTable()),
      Compare<DenseMapOptions>(LoadDenseMapOptions, DenseMapOptionTable()),
  };
}

// Counts of files both loaders rejected (with an error naming the file).
int rejected_files = 0;

// Every loader on `path` (each loads it the old way and the new way); the disagreements, one line
// each.
std::string CompareAll(const std::string& path) {
  const SettingsFile file(path);
  std::string failures;
  for (const auto& compare : AllComparisons()) {
    const std::string failure = compare(file);
    if (failure == "rejected") {
      ++rejected_files;
    } else if (!failure.empty()) {
      failures += failure + "\n";
    }
  }
  return failures;
}

class OptionsEquivalenceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() /
              ("drvslam_options_equivalence_" +
               std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
               std::to_string(getpid()));
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }
  std::string Write(const std::string& body) {
    const fs::path path = folder_ / ("s" + std::to_string(count_++) + ".yaml");
    std::ofstream(path) << "%YAML:1.0\n" << body;
    return path.string();
  }
  fs::path folder_;
  int count_ = 0;
};

TEST_F(OptionsEquivalenceTest, DefaultsAndEveryConfigLoadTheSame) {
  EXPECT_EQ(CompareAll(Write("")), "");
  int configs = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(DRVSLAM_SOURCE_DIR) / "configs")) {
    if (entry.path().extension() != ".yaml") continue;
    EXPECT_EQ(CompareAll(entry.path().string()), "") << entry.path();
    ++configs;
  }
  EXPECT_GE(configs, 3);
}

TEST_F(OptionsEquivalenceTest, EveryKeyWithManyValuesLoadsTheSame) {
  int files = 0;
  rejected_files = 0;
  for (const OptionSection& section : SettingsSections()) {
    for (const OptionInfo& option : section.options) {
      for (const std::string& value : Trials(option)) {
        const std::string path = Write(option.key + ": " + value + "\n");
        EXPECT_EQ(CompareAll(path), "") << option.key << ": " << value;
        ++files;
      }
    }
  }
  EXPECT_GT(files, 1000);
  // Both branches are exercised: many files are rejected by both loaders, most accepted.
  EXPECT_GT(rejected_files, 300);
  EXPECT_LT(rejected_files, files);
  std::printf("compared %d single-key files, %d rejected by both loaders\n", files, rejected_files);
}

TEST_F(OptionsEquivalenceTest, KeysThatDependOnEachOtherLoadTheSame) {
  const std::vector<std::string> bodies = {
      "ORBextractor.iniThFAST: 10\nORBextractor.minThFAST: 11\n",
      "ORBextractor.iniThFAST: 10\nORBextractor.minThFAST: 10\n",
      "Relocalization.minPnpInliers: 20\nRelocalization.minInliers: 19\n",
      "Relocalization.minPnpInliers: 20\nRelocalization.minInliers: 20\n",
      "Dynamic.deltaStatic: 0.5\nDynamic.deltaMoving: 0.6\n",
      "Dynamic.deltaStatic: 0.5\nDynamic.deltaMoving: 0.5\n",
      "DenseMap.minDepth: 1.0\nDenseMap.maxDepth: 1.0\n",
      "DenseMap.minDepth: 1.0\nDenseMap.maxDepth: 1.5\n",
      "DenseMap.leafSize: 0.01\nDenseMap.objectLeafSize: 0.02\n",
      "DenseMap.leafSize: 0.01\nDenseMap.objectLeafSize: 0.01\n",
      "Segmentation.dnnBackend: opencv\nSegmentation.dnnTarget: cuda\n",
      "Segmentation.dnnBackend: opencv\nSegmentation.dnnTarget: cuda_fp16\n",
      "Segmentation.dnnBackend: cuda\nSegmentation.dnnTarget: cpu\n",
      "Segmentation.dnnBackend: cuda\nSegmentation.dnnTarget: opencl\n",
      "Segmentation.dnnBackend: cuda\nSegmentation.dnnTarget: cuda_fp16\n",
      "Segmentation.backend: yolo\n",
      "Segmentation.backend: yolo\nSegmentation.model: m.onnx\n",
      "Segmentation.maskClass: \"teddy bear\"\nSegmentation.classNames: [ \"a\", \"b c\" ]\n",
      "Segmentation.movingClasses: [ \"person\" ]\nSegmentation.keyObjects: \"cup, book\"\n",
      "Dynamic.flowWindow: 12\n",
      "Dynamic.flowWindow: 13\nDynamic.motionRule: delta\nDynamic.unlabelledMotion: 0\n",
      "DenseMap.octomapResolution: 0.004\n",
      "DenseMap.octomapResolution: 0.005\n",
      "Camera.fx: 517.306408\nCamera.k1: 0.262383\nCamera.RGB: 0\nCamera.width: 320\n",
  };
  for (const std::string& body : bodies) EXPECT_EQ(CompareAll(Write(body)), "") << body;
}

}  // namespace
}  // namespace drvslam
