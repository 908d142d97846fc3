// The options registry: unknown keys are found with the nearest known key, --strict-settings
// turns them into errors, the dump is a complete settings file holding the defaults,
// docs/configuration.md and configs/full_example.yaml are what the code declares, and
// `drvslam run --config <dump>` gives the trajectory of the default settings byte for byte.
#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
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
#include "synthesized_sequence.h"
#include "test_support/cli_run.h"
#include "test_support/error_message.h"

namespace drvslam {
namespace {

using drvslam::testing::CliRun;
using drvslam::testing::RunCli;

namespace fs = std::filesystem;

std::string Suggestion(const std::vector<UnknownSetting>& unknown, const std::string& key) {
  for (const UnknownSetting& setting : unknown) {
    if (setting.key == key) return setting.suggestion;
  }
  return "(not reported)";
}

TEST(UnknownSettingsTest, TyposInOurSectionsAreFoundWithTheNearestKey) {
  const std::vector<std::string> keys = {
      "Camera.fx",   "Dynamic.largeShare",  "Dynamic.largeshare", "Viewer.KeyFrameSize",
      "Synth.Seed",  "Dynamics.boxMargin",  "DepthMapFactr",      "Tracking.minInlier",
      "LEFT.height", "DenseMap.octomapRes", "Dynamic.zzzzzzzz",   "ThDepth"};
  const std::vector<UnknownSetting> unknown = FindUnknownSettings(keys, SettingsSections());
  ASSERT_EQ(unknown.size(), 6u);
  EXPECT_EQ(Suggestion(unknown, "Dynamic.largeshare"), "Dynamic.largeShare");
  EXPECT_EQ(Suggestion(unknown, "Dynamics.boxMargin"), "Dynamic.boxMargin");
  EXPECT_EQ(Suggestion(unknown, "DepthMapFactr"), "DepthMapFactor");
  EXPECT_EQ(Suggestion(unknown, "Tracking.minInlier"), "Tracking.minInliers");
  EXPECT_EQ(Suggestion(unknown, "DenseMap.octomapRes"), "");  // 7 letters short: too far
  EXPECT_EQ(Suggestion(unknown, "Dynamic.zzzzzzzz"), "");
}

class SettingsFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = test::FreshTempFolder("drvslam_options_registry_test");
    logged_ = std::make_shared<std::ostringstream>();
    previous_ = spdlog::default_logger();
    auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(*logged_);
    sink->set_pattern("%l %v");
    spdlog::set_default_logger(std::make_shared<spdlog::logger>("options_test", sink));
    spdlog::set_level(spdlog::level::info);
  }
  void TearDown() override {
    spdlog::set_default_logger(previous_);
    fs::remove_all(folder_);
  }
  std::string Write(const std::string& name, const std::string& text) {
    const fs::path path = folder_ / name;
    std::ofstream(path) << text;
    return path.string();
  }
  int Warnings() const {
    const std::string text = logged_->str();
    int count = 0;
    for (std::size_t at = text.find("warning "); at != std::string::npos;
         at = text.find("warning ", at + 1)) {
      ++count;
    }
    return count;
  }
  fs::path folder_;
  std::shared_ptr<std::ostringstream> logged_;
  std::shared_ptr<spdlog::logger> previous_;
};

TEST_F(SettingsFileTest, ATypoWarnsOnceNamingTheNearestKey) {
  const std::string path = Write("typo.yaml", "%YAML:1.0\nDynamic.largeshare: 0.4\n");
  CheckSettingsKeys(SettingsFile(path), false);
  EXPECT_EQ(Warnings(), 1) << logged_->str();
  EXPECT_NE(logged_->str().find("unknown setting Dynamic.largeshare (did you mean "
                                "Dynamic.largeShare?)"),
            std::string::npos)
      << logged_->str();
}

TEST_F(SettingsFileTest, StrictModeMakesTheTypoAnErrorNamingFileKeyAndSuggestion) {
  const std::string path =
      Write("typo.yaml", "%YAML:1.0\nDynamic.largeshare: 0.4\nTracking.minInlier: 40\n");
  try {
    CheckSettingsKeys(SettingsFile(path), true);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
    EXPECT_NE(message.find("Dynamic.largeshare (did you mean Dynamic.largeShare?)"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("Tracking.minInlier (did you mean Tracking.minInliers?)"),
              std::string::npos)
        << message;
  }
}

TEST_F(SettingsFileTest, CorrectFilesGiveNoWarning) {
  const std::string dump = Write("dump.yaml", SettingsDump(SettingsSections()));
  std::vector<std::string> paths = {dump};
  for (const auto& entry : fs::directory_iterator(fs::path(DRVSLAM_SOURCE_DIR) / "configs")) {
    if (entry.path().extension() == ".yaml") paths.push_back(entry.path().string());
  }
  ASSERT_GE(paths.size(), 5u);  // the dump, TUM1-3 and full_example
  for (const std::string& path : paths) {
    EXPECT_NO_THROW(CheckSettingsKeys(SettingsFile(path), true)) << path;
    CheckSettingsKeys(SettingsFile(path), false);
  }
  EXPECT_EQ(Warnings(), 0) << logged_->str();
}

// Every table loads `path` to its defaults.
std::vector<std::string> KeysOffDefault(const std::string& path) {
  const SettingsFile file(path);
  std::vector<std::string> keys;
  const auto add = [&keys](const std::vector<std::string>& more) {
    keys.insert(keys.end(), more.begin(), more.end());
  };
  const Settings settings = LoadSettings(file);
  add(CameraOptionTable().Differences(settings.camera, CameraOptions()));
  add(DepthOptionTable().Differences(settings.depth, DepthOptions()));
  add(OrbExtractorOptionTable().Differences(settings.orb, OrbExtractorOptions()));
  add(TrackerOptionTable().Differences(LoadTrackerOptions(file), TrackerOptions()));
  add(LocalMappingOptionTable().Differences(LoadLocalMappingOptions(file), LocalMappingOptions()));
  add(RelocalizationOptionTable().Differences(LoadRelocalizationOptions(file),
                                              RelocalizationOptions()));
  add(LoopClosingOptionTable().Differences(LoadLoopClosingOptions(file), LoopClosingOptions()));
  add(SegmentationOptionTable().Differences(LoadSegmentationOptions(file), SegmentationOptions()));
  add(DynamicOptionTable().Differences(LoadDynamicOptions(file), DynamicOptions()));
  add(DenseMapOptionTable().Differences(LoadDenseMapOptions(file), DenseMapOptions()));
  return keys;
}

TEST_F(SettingsFileTest, TheDumpHoldsEveryKeyOnceAtItsDefaultWithItsDoc) {
  const std::string text = SettingsDump(SettingsSections());
  const std::string path = Write("dump.yaml", text);
  const SettingsFile file(path);
  std::map<std::string, int> in_file;
  for (const std::string& key : file.Keys()) ++in_file[key];
  std::size_t declared = 0;
  for (const OptionSection& section : SettingsSections()) {
    for (const OptionInfo& option : section.options) {
      ++declared;
      EXPECT_EQ(in_file[option.key], 1) << option.key;
      EXPECT_FALSE(option.doc.empty()) << option.key;
      // The doc line sits right above the key.
      EXPECT_NE(text.find("# " + option.doc + " (" + option.type), std::string::npos) << option.key;
    }
  }
  EXPECT_EQ(in_file.size(), declared);
  EXPECT_GT(declared, 130u);
  EXPECT_EQ(KeysOffDefault(path), std::vector<std::string>());
  // A changed value is read: the comparison can fail.
  std::string edited = text;
  const std::string line = "Dynamic.largeShare: 0.3\n";
  ASSERT_NE(edited.find(line), std::string::npos);
  edited.replace(edited.find(line), line.size(), "Dynamic.largeShare: 0.35\n");
  EXPECT_EQ(KeysOffDefault(Write("edited.yaml", edited)),
            std::vector<std::string>{"Dynamic.largeShare"});
}

TEST(GeneratedFilesTest, ConfigurationDocsAndFullExampleAreUpToDate) {
  const fs::path source(DRVSLAM_SOURCE_DIR);
  EXPECT_EQ(test::ReadFile(source / "docs" / "configuration.md"),
            SettingsMarkdown(SettingsSections()))
      << "regenerate: build/bin/drvslam config --markdown docs/configuration.md";
  EXPECT_EQ(test::ReadFile(source / "configs" / "full_example.yaml"),
            SettingsDump(SettingsSections()))
      << "regenerate: build/bin/drvslam config --dump configs/full_example.yaml";
}

TEST(OptionChecksTest, BadValuesNameTheKeyTheValueAndTheRule) {
  DynamicOptions dynamic;
  dynamic.large_share = 1.5;
  EXPECT_EQ(testing::ErrorMessageOf([&] { dynamic.Check(); }),
            "Dynamic.largeShare = 1.5 must be in [0, 1]");
  dynamic = DynamicOptions();
  dynamic.delta_moving = 0.8;
  EXPECT_THROW(dynamic.Check(), Error);
  OrbExtractorOptions orb;
  orb.min_th_fast = 21;
  EXPECT_EQ(testing::ErrorMessageOf([&] { orb.Check(); }),
            "ORBextractor.minThFAST = 21 must not exceed ORBextractor.iniThFAST");
  for (const double floor : {0.0, -0.5, 1.5}) {
    orb = OrbExtractorOptions();
    orb.load_shedding_floor = floor;
    EXPECT_NE(testing::ErrorMessageOf([&] { orb.Check(); }).find("ORBextractor.loadSheddingFloor"),
              std::string::npos)
        << floor;
  }
  TrackerOptions tracker;
  tracker.min_inliers = 5;
  EXPECT_EQ(testing::ErrorMessageOf([&] { tracker.Check(); }),
            "Tracking.minInliers = 5 must be at least 6");
}

// ---- end to end, through the CLI ----

class ConfigCommandTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = test::FreshTempFolder("drvslam_config_command_test");
    failure_ = test::SynthesizeSequence(root_, "--scenario walking_xyz --frames 30 --seed 3");
    // Without the sequence's settings.yaml a run uses the built-in defaults.
    fs::remove(root_ / "seq" / "settings.yaml");
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }
  static fs::path root_;
  static std::string failure_;
};
fs::path ConfigCommandTest::root_;
std::string ConfigCommandTest::failure_;

TEST_F(ConfigCommandTest, TheDumpRunsAsItIsAndGivesTheDefaultTrajectory) {
  ASSERT_TRUE(failure_.empty()) << failure_;
  const fs::path dump = root_ / "dump.yaml";
  const CliRun dumped = RunCli("config --dump " + dump.string());
  ASSERT_EQ(dumped.status, 0) << dumped.output;
  EXPECT_EQ(test::ReadFile(dump), SettingsDump(SettingsSections()));
  const std::string seq = (root_ / "seq").string();
  // No --segmenter: the dump's Segmentation.backend (auto) must pick the sequence's
  // ground-truth masks exactly as a run without any settings file does.
  const CliRun with_dump =
      RunCli("run --sequential --strict-settings --dataset " + seq + " --config " + dump.string() +
             " --out " + (root_ / "out_dump").string());
  ASSERT_EQ(with_dump.status, 0) << with_dump.output;
  EXPECT_EQ(with_dump.output.find("unknown setting"), std::string::npos) << with_dump.output;
  const CliRun with_defaults =
      RunCli("run --sequential --dataset " + seq + " --out " + (root_ / "out_defaults").string());
  ASSERT_EQ(with_defaults.status, 0) << with_defaults.output;
  EXPECT_NE(with_dump.output.find("gt (ground-truth masks: ORACLE)"), std::string::npos)
      << with_dump.output;
  EXPECT_NE(with_defaults.output.find("gt (ground-truth masks: ORACLE)"), std::string::npos)
      << with_defaults.output;
  const std::string trajectory_dump = test::ReadFile(root_ / "out_dump" / "CameraTrajectory.txt");
  const std::string trajectory_defaults =
      test::ReadFile(root_ / "out_defaults" / "CameraTrajectory.txt");
  // 30 frames, a header line or more.
  EXPECT_GE(std::count(trajectory_dump.begin(), trajectory_dump.end(), '\n'), 30);
  EXPECT_EQ(trajectory_dump, trajectory_defaults);
}

TEST_F(ConfigCommandTest, StrictSettingsRejectsATypoAndPlainRunsWarn) {
  ASSERT_TRUE(failure_.empty()) << failure_;
  const fs::path typo = root_ / "typo.yaml";
  std::ofstream(typo) << "%YAML:1.0\nDynamic.largeshare: 0.4\n";
  const std::string seq = (root_ / "seq").string();
  const CliRun strict =
      RunCli("run --sequential --strict-settings --max-frames 3 --dataset " + seq + " --config " +
             typo.string() + " --out " + (root_ / "out_strict").string());
  EXPECT_EQ(strict.status, 2) << strict.output;
  EXPECT_NE(strict.output.find("error: " + typo.string() +
                               ": unknown setting Dynamic.largeshare (did you mean "
                               "Dynamic.largeShare?)"),
            std::string::npos)
      << strict.output;
  const CliRun plain = RunCli("run --sequential --max-frames 3 --dataset " + seq + " --config " +
                              typo.string() + " --out " + (root_ / "out_plain").string());
  EXPECT_EQ(plain.status, 0) << plain.output;
  EXPECT_NE(plain.output.find("did you mean Dynamic.largeShare?"), std::string::npos)
      << plain.output;
}

}  // namespace
}  // namespace drvslam
