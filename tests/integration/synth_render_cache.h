// A cache of rendered synthetic sequences shared by test processes. CTest runs every case of a
// suite in its own process, so a suite that renders its sequence in SetUpTestSuite or SetUp
// rendered it once per case; the sanitizer jobs render the same sequences again with the same
// release CLI. With DRVSLAM_TEST_SYNTH_CACHE naming a folder (tests/CMakeLists.txt sets it for
// CTest, scripts/sanitizers.sh points the sanitizer jobs at the release build's), a sequence is
// rendered once into that folder and later calls copy it.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace drvslam::test {

// Renders `synth_args` with the CLI `cli` into `out`, its output in `log`; returns an empty string
// on success, else what went wrong.
using RenderFunction = std::string (*)(const std::string& cli, const std::string& synth_args,
                                       const std::filesystem::path& out,
                                       const std::filesystem::path& log);

// The cache key of a render: the CLI (its path, size and modification time, so a rebuilt CLI
// renders again) and the arguments, each argument that names a file standing for the file's
// contents (a test writes its camera path into a folder of its own, named differently in every
// process).
std::string RenderKey(const std::string& cli, const std::string& synth_args);

// Nothing when `cache` is empty: the caller renders as without a cache. Otherwise the cached
// folder of this render, rendered by `render` first when absent (into a folder of this process's
// own, then renamed, so processes rendering the same key at once never see half a sequence); an
// empty path when that render failed (its output is in `log`).
std::optional<std::filesystem::path> CachedRender(const std::filesystem::path& cache,
                                                  const std::string& cli,
                                                  const std::string& synth_args,
                                                  const std::filesystem::path& log,
                                                  RenderFunction render);

// DRVSLAM_TEST_SYNTH_CACHE, or an empty path when it is unset or empty.
std::filesystem::path RenderCacheFromEnvironment();

}  // namespace drvslam::test
