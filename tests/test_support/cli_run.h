// RunCli: the built `drvslam` (DRVSLAM_CLI, set by drvslam_test) run through the shell the way a
// user runs it, for tests whose contract is the exit status and what the command prints.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace drvslam::testing {

struct CliRun {
  int status = -1;     // the exit status; -1 when the command did not exit normally
  std::string output;  // stdout and stderr, interleaved as printed
};

// `arguments` follow the program name unquoted: quote what the shell must not split.
inline CliRun RunCli(const std::string& arguments) {
  const std::string command = std::string(DRVSLAM_CLI) + " " + arguments + " 2>&1";
  CliRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  char buffer[4096];
  std::size_t read = 0;
  while ((read = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0) run.output.append(buffer, read);
  const int status = pclose(pipe);
  run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

}  // namespace drvslam::testing
