// Helpers for end-to-end tests: a fresh temporary folder per test process (CTest runs every test
// case in its own process, in parallel, so a shared folder would be deleted under another case),
// a synthetic sequence made there by the real `drvslam synth` command, and a fixture for a suite
// that runs SLAM over one such sequence.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "drvslam/tools/eval/ate.h"
#include "drvslam/tools/runner/sequence_runner.h"

namespace drvslam::test {

// The whole file as a string; empty when it cannot be read.
std::string ReadFile(const std::filesystem::path& path);

// A new, empty folder temp_directory_path()/<name>_<pid>_<random> (testing::UniqueTempFolder):
// never one that another run or user already holds. Every call makes a new one.
std::filesystem::path FreshTempFolder(const std::string& name);

// Runs `drvslam --log-level warn synth <synth_args> --out <root>/seq`. Returns an empty string on
// success, else the command line and its output, for the assertion message. The CLI is the one
// built with the test, or the environment's DRVSLAM_TEST_SYNTH_CLI when set: the TSan job renders
// its inputs with the release CLI, because rendering is not what it tests and takes minutes
// under the sanitizer (scripts/sanitizers.sh).
std::string SynthesizeSequence(const std::filesystem::path& root, const std::string& synth_args);

// FreshTempFolder(folder_name) into *root, then SynthesizeSequence there. Use it as
// ASSERT_TRUE(SynthesizeInFreshFolder(...)): a failure says the command line and its output.
::testing::AssertionResult SynthesizeInFreshFolder(const std::string& folder_name,
                                                   const std::string& synth_args,
                                                   std::filesystem::path* root);

// ATE (default options) of the TUM trajectory file `trajectory_path` against the sequence
// folder's groundtruth.txt.
AteResult AteAgainstGroundTruth(const std::filesystem::path& sequence,
                                const std::string& trajectory_path);

// A suite of SLAM runs over one synthetic sequence in root_/seq, made by the suite's own
// SetUpTestSuite() (with SynthesizeInFreshFolder into &root_) and removed after its last case.
// A fixture derives as `class MySuite : public SequenceSuite<MySuite>`: the template argument
// gives each suite its own root_.
template <typename Suite>
class SequenceSuite : public ::testing::Test {
 protected:
  static void TearDownTestSuite() { std::filesystem::remove_all(root_); }

  // A sequential run over the sequence that writes its outputs into root_/out_name.
  static RunOptions SequentialRunOptions(const std::string& out_name) {
    RunOptions options;
    options.dataset = (root_ / "seq").string();
    options.out_dir = (root_ / out_name).string();
    options.sequential = true;
    return options;
  }

  // ATE RMSE (metres) of a run's camera trajectory against the sequence's ground truth.
  static double AteRmse(const RunSummary& summary) {
    return AteAgainstGroundTruth(root_ / "seq", summary.camera_trajectory_path).errors.rmse;
  }

  static inline std::filesystem::path root_;
};

}  // namespace drvslam::test
