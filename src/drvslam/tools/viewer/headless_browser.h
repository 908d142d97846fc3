// HeadlessBrowser: a headless Chromium (Debian's `chromium`) kept open on one URL as a child
// process, so that a page really loads and receives what a server streams (the benchmark's live
// viewer entries). It renders WebGL in software (SwiftShader), as the browser tests do, so the
// page runs as it would on a desktop. The browser runs in its own process group with a fresh
// profile folder; closing it (or destroying the object) ends the whole group and removes the
// profile, and the child is killed too if this process dies first.
#pragma once

#include <sys/types.h>

#include <optional>
#include <string>

namespace drvslam {

// The Chromium to run: $DRVSLAM_CHROMIUM when set (it must be an executable file), else the
// first of `chromium`, `chromium-browser` on $PATH. Throws Error naming what is missing.
std::string FindChromium();

class HeadlessBrowser {
 public:
  // Starts `chromium` on `url`; its stdout and stderr go to `log_path` (empty: discarded).
  // Throws Error when the profile folder, the log or the process cannot be created.
  HeadlessBrowser(const std::string& chromium, const std::string& url, const std::string& log_path);
  ~HeadlessBrowser();  // Close
  HeadlessBrowser(const HeadlessBrowser&) = delete;
  HeadlessBrowser& operator=(const HeadlessBrowser&) = delete;

  // The exit status when the browser has already ended on its own (it should not), else nullopt.
  std::optional<int> ExitedWith();

  // Ends the browser: SIGTERM to its process group, SIGKILL after 3 s, waits for it, removes
  // the profile folder. Idempotent.
  void Close();

 private:
  pid_t pid_ = -1;
  bool reaped_ = false;
  int exit_status_ = 0;
  std::string profile_dir_;
};

}  // namespace drvslam
