#include "drvslam/loop/default_vocabulary.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "drvslam/core/error.h"
#include "drvslam/loop/vocabulary_io.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

// The running executable's folder; empty when the platform does not say.
fs::path ExecutableFolder() {
  std::error_code error;
  const fs::path executable = fs::read_symlink("/proc/self/exe", error);
  if (error || executable.empty()) return {};
  return executable.parent_path();
}

}  // namespace

std::vector<std::string> DefaultVocabularyCandidates() {
  std::vector<std::string> candidates;
  const char* environment = std::getenv(kDefaultVocabularyEnvironment);
  if (environment != nullptr && environment[0] != '\0') candidates.emplace_back(environment);
  const fs::path folder = ExecutableFolder();
  if (!folder.empty()) {
    candidates.push_back(
        (folder.parent_path() / "share" / "drvslam" / kDefaultVocabularyFileName).string());
  }
#ifdef DRVSLAM_DEFAULT_VOCABULARY_PATH
  candidates.emplace_back(DRVSLAM_DEFAULT_VOCABULARY_PATH);
#endif
  // Where `cmake --install` puts it (cmake/DrvslamInstall.cmake), for programs linking the
  // installed library from their own folders.
#ifdef DRVSLAM_INSTALLED_VOCABULARY_PATH
  candidates.emplace_back(DRVSLAM_INSTALLED_VOCABULARY_PATH);
#endif
  return candidates;
}

std::string DefaultVocabularyPath() {
  for (const std::string& candidate : DefaultVocabularyCandidates()) {
    std::error_code error;
    if (fs::is_regular_file(candidate, error)) return candidate;
  }
  return {};
}

BowVocabulary LoadDefaultVocabulary() {
  const std::string path = DefaultVocabularyPath();
  if (path.empty()) {
    std::string searched;
    for (const std::string& candidate : DefaultVocabularyCandidates()) {
      searched += (searched.empty() ? "" : ", ") + candidate;
    }
    throw Error("no default vocabulary found (searched: " + searched +
                "); the build trains one when the opencv-doc sample images are installed, or "
                "give a vocabulary file");
  }
  return LoadVocabulary(path);
}

}  // namespace drvslam
