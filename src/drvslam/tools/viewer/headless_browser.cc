#include "drvslam/tools/viewer/headless_browser.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <thread>
#include <vector>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

bool IsExecutableFile(const fs::path& path) {
  std::error_code error;
  return fs::is_regular_file(path, error) && ::access(path.c_str(), X_OK) == 0;
}

// The exit status of a wait, as a shell reports it (128 + signal when killed).
int ShellStatus(int code, int status) { return code == CLD_EXITED ? status : 128 + status; }

}  // namespace

std::string FindChromium() {
  if (const char* chosen = std::getenv("DRVSLAM_CHROMIUM"); chosen && *chosen) {
    if (!IsExecutableFile(chosen)) {
      throw Error(std::string("DRVSLAM_CHROMIUM = ") + chosen +
                  " is not an executable file (the headless Chromium for the live viewer)");
    }
    return chosen;
  }
  const char* path = std::getenv("PATH");
  std::istringstream folders(path ? path : "");
  const char* const kNames[] = {"chromium", "chromium-browser"};
  std::vector<std::string> searched;
  for (std::string folder; std::getline(folders, folder, ':');) {
    if (!folder.empty()) searched.push_back(folder);
  }
  for (const char* name : kNames) {
    for (const std::string& folder : searched) {
      const fs::path candidate = fs::path(folder) / name;
      if (IsExecutableFile(candidate)) return candidate.string();
    }
  }
  throw Error(
      "chromium is missing: the live viewer needs a headless Chromium to connect to it, and "
      "neither `chromium` nor `chromium-browser` is on PATH (Debian: apt-get install chromium, "
      "as scripts/install-deps.sh does; or set DRVSLAM_CHROMIUM to the browser's executable)");
}

HeadlessBrowser::HeadlessBrowser(const std::string& chromium, const std::string& url,
                                 const std::string& log_path) {
  std::string profile = (fs::temp_directory_path() / "drvslam-chromium-XXXXXX").string();
  if (::mkdtemp(profile.data()) == nullptr) {
    throw Error(profile + ": cannot create the browser's profile folder: " + std::strerror(errno));
  }
  profile_dir_ = profile;
  const std::string output = log_path.empty() ? "/dev/null" : log_path;
  const int log_fd = ::open(output.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  const int null_fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  if (log_fd < 0 || null_fd < 0) {
    const std::string reason = std::strerror(errno);
    if (log_fd >= 0) ::close(log_fd);
    if (null_fd >= 0) ::close(null_fd);
    std::error_code ignored;
    fs::remove_all(profile_dir_, ignored);
    throw Error(output + ": cannot open the browser's log: " + reason);
  }
  // WebGL without a GPU through SwiftShader, as the browser tests run the page; no sandbox (it
  // needs privileges containers lack); nothing that reaches the network on its own.
  const std::vector<std::string> arguments = {chromium,
                                              "--headless=new",
                                              "--no-sandbox",
                                              "--disable-dev-shm-usage",
                                              "--use-gl=angle",
                                              "--use-angle=swiftshader",
                                              "--enable-unsafe-swiftshader",
                                              "--no-first-run",
                                              "--no-default-browser-check",
                                              "--disable-extensions",
                                              "--disable-background-networking",
                                              "--disable-component-update",
                                              "--disable-sync",
                                              "--mute-audio",
                                              "--window-size=1280,800",
                                              "--user-data-dir=" + profile_dir_,
                                              url};
  // Built before fork: the child may only make async-signal-safe calls until exec.
  std::vector<char*> argv;
  for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
  argv.push_back(nullptr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::setpgid(0, 0);  // its own group, so that Close ends its helper processes too
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);  // the parent died before prctl took effect
    ::dup2(null_fd, STDIN_FILENO);
    ::dup2(log_fd, STDOUT_FILENO);
    ::dup2(log_fd, STDERR_FILENO);
    // The server's sockets and every other descriptor stay with the parent.
    ::close_range(3, ~0U, 0);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  const int fork_errno = errno;
  ::close(log_fd);
  ::close(null_fd);
  if (pid < 0) {
    std::error_code ignored;
    fs::remove_all(profile_dir_, ignored);
    throw Error("cannot start " + chromium + ": " + std::strerror(fork_errno));
  }
  // Also set here: Close may signal the group before the child has run setpgid.
  ::setpgid(pid, pid);
  pid_ = pid;
}

HeadlessBrowser::~HeadlessBrowser() { Close(); }

std::optional<int> HeadlessBrowser::ExitedWith() {
  if (pid_ < 0) return std::nullopt;
  if (reaped_) return exit_status_;
  siginfo_t info{};
  // WNOWAIT: the process stays a zombie, so its id (and its group's) cannot be reused before
  // Close signals the group.
  if (::waitid(P_PID, pid_, &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid_) {
    return ShellStatus(info.si_code, info.si_status);
  }
  return std::nullopt;
}

void HeadlessBrowser::Close() {
  if (pid_ < 0 || reaped_) return;
  ::kill(-pid_, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(3);
  while (!ExitedWith() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  // The leader is unreaped (running or a zombie), so the group is still ours: this ends
  // whatever of it is left, renderer and GPU processes included.
  ::kill(-pid_, SIGKILL);
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  exit_status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  reaped_ = true;
  std::error_code ignored;
  fs::remove_all(profile_dir_, ignored);
}

}  // namespace drvslam
