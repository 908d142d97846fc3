#include "synth_render_cache.h"

#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <random>
#include <sstream>
#include <system_error>

namespace drvslam::test {

namespace fs = std::filesystem;

namespace {

// 64-bit FNV-1a over every part of a key.
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

// A folder name no other process, on this machine or another sharing the folder, picks.
std::string PartialName(const std::string& key) {
  std::random_device device;
  std::ostringstream name;
  name << key << ".partial." << ::getpid() << "." << std::hex << device() << device();
  return name.str();
}

// Removes every entry of `cache` but `keep`: renders of older CLI builds.
void RemoveOtherBuilds(const fs::path& cache, const fs::path& keep) {
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(cache, error)) {
    if (entry.path() != keep) fs::remove_all(entry.path(), error);
  }
}

}  // namespace

bool Cacheable(const std::string& synth_args) {
  std::istringstream words(synth_args);
  std::string word;
  std::error_code error;
  while (words >> word) {
    if (fs::exists(word, error)) return false;
  }
  return true;
}

std::string CliKey(const std::string& cli) {
  KeyHash hash;
  hash.Add(cli);
  std::error_code error;
  if (fs::is_regular_file(cli, error)) {
    hash.Add(std::to_string(fs::file_size(cli, error)));
    hash.Add(std::to_string(fs::last_write_time(cli, error).time_since_epoch().count()));
  }
  return hash.Hex();
}

std::string ArgumentsKey(const std::string& synth_args) {
  KeyHash hash;
  std::istringstream words(synth_args);
  std::string word;
  while (words >> word) hash.Add(word);
  return hash.Hex();
}

std::optional<fs::path> CachedRender(const fs::path& cache, const std::string& cli,
                                     const std::string& synth_args, const fs::path& log,
                                     RenderFunction render) {
  if (cache.empty() || !Cacheable(synth_args)) return std::nullopt;
  const fs::path build = cache / CliKey(cli);
  const std::string key = ArgumentsKey(synth_args);
  const fs::path entry = build / key;
  std::error_code error;
  if (fs::is_directory(entry, error)) return entry;
  if (!fs::is_directory(build, error)) {
    fs::create_directories(build, error);
    RemoveOtherBuilds(cache, build);
  }
  const fs::path partial = build / PartialName(key);
  if (!render(cli, synth_args, partial, log).empty()) {
    fs::remove_all(partial, error);
    return fs::path();
  }
  // A process that rendered the same key at the same time may have renamed its copy first: then
  // the rename fails, this copy is dropped and theirs, identical, is used.
  fs::rename(partial, entry, error);
  if (error) fs::remove_all(partial, error);
  return fs::is_directory(entry, error) ? entry : fs::path();
}

fs::path RenderCacheFromEnvironment() {
  const char* const folder = std::getenv("DRVSLAM_TEST_SYNTH_CACHE");
  return folder && *folder ? fs::path(folder) : fs::path();
}

}  // namespace drvslam::test
