// Helpers for end-to-end tests: a fresh temporary folder per test process (CTest runs every test
// case in its own process, in parallel, so a shared folder would be deleted under another case)
// and a synthetic sequence made there by the real `drvslam synth` command.
#pragma once

#include <filesystem>
#include <string>

#include "drvslam/eval/ate.h"

namespace drvslam::test {

// The whole file as a string; empty when it cannot be read.
std::string ReadFile(const std::filesystem::path& path);

// temp_directory_path()/<name>_<pid>, emptied and created.
std::filesystem::path FreshTempFolder(const std::string& name);

// Runs `drvslam --log-level warn synth <synth_args> --out <root>/seq`. Returns an empty string on
// success, else the command line and its output, for the assertion message.
std::string SynthesizeSequence(const std::filesystem::path& root, const std::string& synth_args);

// ATE (default options) of the TUM trajectory file `trajectory_path` against the sequence
// folder's groundtruth.txt.
AteResult AteAgainstGroundTruth(const std::filesystem::path& sequence,
                                const std::string& trajectory_path);

}  // namespace drvslam::test
