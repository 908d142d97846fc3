#include "synthesized_sequence.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "drvslam/io/trajectory_io.h"
#include "test_support/temp_folder.h"

namespace drvslam::test {

namespace fs = std::filesystem;

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

fs::path FreshTempFolder(const std::string& name) { return testing::UniqueTempFolder(name); }

std::string SynthesizeSequence(const fs::path& root, const std::string& synth_args) {
  const fs::path log = root / "synth.log";
  const char* const synth_cli = std::getenv("DRVSLAM_TEST_SYNTH_CLI");
  const std::string cli = synth_cli && *synth_cli ? synth_cli : DRVSLAM_CLI;
  const std::string command = cli + " --log-level warn synth " + synth_args + " --out " +
                              (root / "seq").string() + " > " + log.string() + " 2>&1";
  if (std::system(command.c_str()) == 0) return "";
  return command + "\n" + ReadFile(log);
}

::testing::AssertionResult SynthesizeInFreshFolder(const std::string& folder_name,
                                                   const std::string& synth_args, fs::path* root) {
  *root = FreshTempFolder(folder_name);
  const std::string failure = SynthesizeSequence(*root, synth_args);
  if (failure.empty()) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << failure;
}

AteResult AteAgainstGroundTruth(const fs::path& sequence, const std::string& trajectory_path) {
  const Trajectory truth = ReadTumTrajectory((sequence / "groundtruth.txt").string());
  return ComputeAte(truth, ReadTumTrajectory(trajectory_path), AteOptions{});
}

}  // namespace drvslam::test
