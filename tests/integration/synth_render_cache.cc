#include "synth_render_cache.h"

#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <system_error>

namespace drvslam::test {

namespace fs = std::filesystem;

namespace {

// 64-bit FNV-1a, accumulated over every part of the key.
class KeyHash {
 public:
  void Add(const std::string& text) {
    for (const unsigned char c : text) {
      value_ = (value_ ^ c) * 1099511628211ull;
    }
    value_ = (value_ ^ 0xffu) * 1099511628211ull;  // a separator: "ab","c" differs from "a","bc"
  }
  std::string Hex() const {
    std::ostringstream out;
    out << std::hex << value_;
    return out.str();
  }

 private:
  std::uint64_t value_ = 14695981039346656037ull;
};

std::string FileContents(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

std::string RenderKey(const std::string& cli, const std::string& synth_args) {
  KeyHash hash;
  hash.Add(cli);
  std::error_code error;
  if (fs::is_regular_file(cli, error)) {
    hash.Add(std::to_string(fs::file_size(cli, error)));
    hash.Add(std::to_string(fs::last_write_time(cli, error).time_since_epoch().count()));
  }
  std::istringstream words(synth_args);
  std::string word;
  while (words >> word) {
    hash.Add(fs::is_regular_file(word, error) ? "file:" + FileContents(word) : word);
  }
  return hash.Hex();
}

std::optional<fs::path> CachedRender(const fs::path& cache, const std::string& cli,
                                     const std::string& synth_args, const fs::path& log,
                                     RenderFunction render) {
  if (cache.empty()) return std::nullopt;
  const fs::path entry = cache / RenderKey(cli, synth_args);
  std::error_code error;
  if (fs::is_directory(entry, error)) return entry;
  fs::create_directories(cache, error);
  const fs::path partial =
      cache / (entry.filename().string() + ".partial." + std::to_string(::getpid()));
  fs::remove_all(partial, error);
  if (!render(cli, synth_args, partial, log).empty()) {
    fs::remove_all(partial, error);
    return fs::path();
  }
  // A process that rendered the same key at the same time may have renamed its copy first: then
  // this one is dropped and theirs, identical, is used.
  fs::rename(partial, entry, error);
  if (error) fs::remove_all(partial, error);
  return fs::is_directory(entry, error) ? entry : fs::path();
}

fs::path RenderCacheFromEnvironment() {
  const char* const folder = std::getenv("DRVSLAM_TEST_SYNTH_CACHE");
  return folder && *folder ? fs::path(folder) : fs::path();
}

}  // namespace drvslam::test
