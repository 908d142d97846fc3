// Runs the built `drvslam synth` (DRVSLAM_CLI) the way a user would.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "test_folder.h"
#include "test_support/cli_run.h"

namespace drvslam::synth {
namespace {

using drvslam::testing::CliRun;
using drvslam::testing::RunCli;

using testing::ReadFileBytes;
using testing::TestFolder;

int CountFiles(const std::string& folder) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    count += entry.is_regular_file();
  return count;
}

TEST(SynthCliTest, WritesATumLayoutSequence) {
  TestFolder folder("cli");
  const std::string out = folder / "walking";
  const CliRun result =
      RunCli("synth --scenario walking_xyz --frames 5 --width 320 --height 240 --out " + out);
  ASSERT_EQ(result.status, 0) << result.output;
  EXPECT_NE(result.output.find("frames:      5 at 320x240, 2 actors"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("fps"), std::string::npos);
  EXPECT_NE(result.output.find("cover"), std::string::npos);
  for (const char* sub : {"rgb", "depth", "masks"})
    EXPECT_EQ(CountFiles(out + "/" + sub), 5) << sub;
  for (const char* file : {"rgb.txt", "depth.txt", "associations.txt", "groundtruth.txt",
                           "instances.txt", "settings.yaml"}) {
    EXPECT_TRUE(std::filesystem::is_regular_file(out + "/" + file)) << file;
  }
  const std::string ground_truth = ReadFileBytes(out + "/groundtruth.txt");
  EXPECT_NE(ground_truth.find("1305031102.175304 "), std::string::npos);
  // Running again into the same folder replaces the earlier sequence.
  const CliRun again =
      RunCli("synth --scenario static_xyz --frames 3 --width 160 --height 120 --out " + out);
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_EQ(CountFiles(out + "/rgb"), 3);
}

TEST(SynthCliTest, BadInputExitsWithStatus2) {
  TestFolder folder("cli_bad");
  std::filesystem::create_directories(folder / "empty");
  const struct {
    std::string arguments;
    std::string expected;
  } cases[] = {
      {"synth --scenario flying_xyz --frames 2 --out " + folder / "a", "error: unknown scenario"},
      {"synth --scenario walking_xyz --frames 0 --out " + folder / "b", "error: --frames 0"},
      {"synth --scenario walking_xyz --frames 2 --trajectory " + folder / "missing.txt" +
           " --out " + folder / "c",
       "error: " + folder / "missing.txt"},
      {"synth --scenario walking_xyz --frames 2 --textures " + folder / "empty" + " --out " +
           folder / "d",
       "no images"},
      {"synth --scenario walking_xyz --frames 2", "error: synth: --out DIR is required"},
      {"synth --scenario static_xyz --actors 2 --frames 2 --out " + folder / "e",
       "error: --actors 2"},
  };
  for (const auto& c : cases) {
    const CliRun result = RunCli(c.arguments);
    EXPECT_EQ(result.status, 2) << c.arguments << "\n" << result.output;
    EXPECT_NE(result.output.find(c.expected), std::string::npos) << c.arguments << "\n"
                                                                 << result.output;
  }
  // A folder holding something else is never overwritten.
  testing::WriteFileText(folder / "precious.txt", "keep me");
  const CliRun refused = RunCli("synth --scenario static_xyz --frames 2 --out " + folder.Path());
  EXPECT_EQ(refused.status, 2);
  EXPECT_EQ(ReadFileBytes(folder / "precious.txt"), "keep me");
}

TEST(SynthCliTest, RealCameraPresetIsRecordedAndFlagsOverrideIt) {
  TestFolder folder("cli_real");
  const std::string out = folder / "handheld";
  const CliRun result = RunCli(
      "synth --scenario static_xyz --frames 4 --width 160 --height 120 --real-camera "
      "--blur-exposure 0 --depth-shift -1,0.5 --camera-speed 2 --out " +
      out);
  ASSERT_EQ(result.status, 0) << result.output;
  const std::string settings = ReadFileBytes(out + "/settings.yaml");
  for (const char* line :
       {"Synth.RealBlurExposure: 0.0\n", "Synth.RealRollingShutterReadout: 0.025\n",
        "Synth.RealDepthShiftX: -1.0\n", "Synth.RealDepthShiftY: 0.5\n",
        "Synth.RealIntrinsicsError: 0.03\n", "Camera.k1: 0.262383\n", "Camera.k3: 1.163314\n",
        "Synth.CameraSpeed: 2.0\n"}) {
    EXPECT_NE(settings.find(line), std::string::npos) << line << settings;
  }
  // dense-eval rebuilds the sequence from settings.yaml, camera speed included, and checks its
  // poses against groundtruth.txt.
  const CliRun evaluated = RunCli("dense-eval --dataset " + out);
  EXPECT_EQ(evaluated.status, 0) << evaluated.output;
}

TEST(SynthCliTest, BadRealCameraValuesExitWithStatus2) {
  TestFolder folder("cli_real_bad");
  const std::string base = "synth --scenario static_xyz --frames 2 --width 160 --height 120 ";
  const struct {
    std::string arguments;
    std::string expected;
  } cases[] = {
      {"--distortion 0.1,x", "error: --distortion '0.1,x'"},
      {"--distortion -3", "cannot be inverted"},
      {"--depth-shift 3", "error: --depth-shift '3' must be two numbers"},
      {"--principal-point-error 1,2,3", "error: --principal-point-error"},
      {"--blur-exposure 1", "error: --blur-exposure 1"},
      {"--rolling-shutter -0.1", "error: --rolling-shutter -0.1"},
      {"--camera-speed 0", "error: --camera-speed"},
  };
  for (const auto& c : cases) {
    const CliRun result = RunCli(base + c.arguments + " --out " + folder / "x");
    EXPECT_EQ(result.status, 2) << c.arguments << "\n" << result.output;
    EXPECT_NE(result.output.find(c.expected), std::string::npos) << c.arguments << "\n"
                                                                 << result.output;
  }
}

TEST(SynthCliTest, HelpAndListDocumentTheOptions) {
  const CliRun help = RunCli("synth --help");
  EXPECT_EQ(help.status, 0);
  for (const char* option :
       {"--scenario", "--frames", "--seed", "--trajectory", "--textures", "--actors", "--out",
        "--billboards", "--clean", "--blur-exposure", "--rolling-shutter", "--depth-shift",
        "--intrinsics-error", "--principal-point-error", "--distortion", "--real-camera",
        "--camera-speed"}) {
    EXPECT_NE(help.output.find(option), std::string::npos) << option;
  }
  const CliRun list = RunCli("synth --list");
  EXPECT_EQ(list.status, 0);
  for (const char* name :
       {"walking_xyz", "walking_static", "walking_rpy", "walking_halfsphere", "sitting_static",
        "sitting_xyz", "pushed_xyz", "static_xyz", "static_halfsphere"}) {
    EXPECT_NE(list.output.find(name), std::string::npos) << name;
  }
}

}  // namespace
}  // namespace drvslam::synth
