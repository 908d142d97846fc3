#include "fuzz_bodies/scratch_file.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace drvslam::fuzz {
namespace {

namespace fs = std::filesystem;

// Made on first use, removed at exit.
struct Folder {
  fs::path path;
  Folder() {
    path = fs::temp_directory_path() / ("drvslam-fuzz-" + std::to_string(::getpid()));
    fs::create_directories(path);
  }
  ~Folder() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

const Folder& TheFolder() {
  static const Folder folder;
  return folder;
}

}  // namespace

std::string ScratchFolder() { return TheFolder().path.string(); }

std::string WriteScratchFile(const std::string& name, const std::string& bytes) {
  const std::string path = (TheFolder().path / name).string();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  // The harness itself failing is not a finding about the parser: stop loudly.
  if (!out) throw std::runtime_error("fuzz harness: cannot write " + path);
  return path;
}

std::string WriteScratchFile(const std::string& name, const std::uint8_t* data, std::size_t size) {
  return WriteScratchFile(name, std::string(reinterpret_cast<const char*>(data), size));
}

void RemoveScratchFile(const std::string& name) {
  std::error_code ignored;
  fs::remove(TheFolder().path / name, ignored);
}

}  // namespace drvslam::fuzz
