// UniqueTempFolder: a new, empty folder of this process's own under the temporary directory
// ($TMPDIR or /tmp), for a test's files. The name is <prefix>_<pid>_<6 random characters>, made
// by mkdtemp: it can never be a folder (or file) that another run, another test process or
// another user already holds, so nothing has to be removed first and nothing of theirs is. Each
// call makes a new folder; the caller keeps the path and removes the folder when done.
#pragma once

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace drvslam::testing {

inline std::filesystem::path UniqueTempFolder(const std::string& prefix) {
  const std::filesystem::path pattern = std::filesystem::temp_directory_path() /
                                        (prefix + "_" + std::to_string(::getpid()) + "_XXXXXX");
  std::string text = pattern.string();
  std::vector<char> buffer(text.begin(), text.end());
  buffer.push_back('\0');
  if (::mkdtemp(buffer.data()) == nullptr) {
    throw std::runtime_error("mkdtemp " + text + ": " + std::strerror(errno));
  }
  return std::filesystem::path(buffer.data());
}

// A folder of this process's own (UniqueTempFolder("drvslam_test")), made on first use and
// removed with everything in it when the process exits: for tests that write loose files by
// name, which in the shared temporary directory itself another run or user could hold.
inline const std::filesystem::path& ProcessTempFolder() {
  struct Folder {
    std::filesystem::path path = UniqueTempFolder("drvslam_test");
    ~Folder() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Folder folder;
  return folder.path;
}

}  // namespace drvslam::testing
