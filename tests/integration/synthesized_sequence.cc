#include "synthesized_sequence.h"

#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>
#include <system_error>

#include "drvslam/io/trajectory_io.h"
#include "synth_render_cache.h"
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

namespace {

// Renders into `out`; an empty string on success, else the command line and its output.
std::string Render(const std::string& cli, const std::string& synth_args, const fs::path& out,
                   const fs::path& log) {
  const std::string command = cli + " --log-level warn synth " + synth_args + " --out " +
                              out.string() + " > " + log.string() + " 2>&1";
  if (std::system(command.c_str()) == 0) return "";
  return command + "\n" + ReadFile(log);
}

}  // namespace

std::string SynthesizeSequence(const fs::path& root, const std::string& synth_args) {
  const fs::path log = root / "synth.log";
  const char* const synth_cli = std::getenv("DRVSLAM_TEST_SYNTH_CLI");
  const std::string cli = synth_cli && *synth_cli ? synth_cli : DRVSLAM_CLI;
  const std::optional<fs::path> cached =
      CachedRender(RenderCacheFromEnvironment(), cli, synth_args, log, &Render);
  if (!cached) return Render(cli, synth_args, root / "seq", log);
  if (cached->empty()) return "rendering into the cache failed:\n" + ReadFile(log);
  std::error_code error;
  fs::remove_all(root / "seq", error);  // as `synth --out` replaces the folder
  fs::copy(*cached, root / "seq", fs::copy_options::recursive, error);
  if (error) {
    return "copying " + cached->string() + " to " + (root / "seq").string() + ": " +
           error.message();
  }
  return "";
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
