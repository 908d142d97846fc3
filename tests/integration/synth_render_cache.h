// A cache of rendered synthetic sequences shared by test processes. CTest runs every case of a
// suite in its own process, so a suite that renders its sequence in SetUpTestSuite or SetUp
// rendered it once per case; the sanitizer jobs render the same sequences again with the same
// release CLI. With DRVSLAM_TEST_SYNTH_CACHE naming a folder (cmake/DrvslamModule.cmake sets it
// for CTest, scripts/sanitizers.sh points the sanitizer jobs at the release build's), a sequence
// is rendered once into that folder and later calls copy it.
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

// False when an argument names an existing file or folder (a camera path, textures): the
// rendered settings.yaml records such a path, which another process may remove, and a folder's
// contents are not in the key.
bool Cacheable(const std::string& synth_args);

// The cache keys of a render: the CLI build (its path, size and modification time: a rebuilt CLI
// renders again) and, under it, the arguments.
std::string CliKey(const std::string& cli);
std::string ArgumentsKey(const std::string& synth_args);

// Nothing when `cache` is empty or the arguments are not Cacheable: the caller renders as
// without a cache. Otherwise the cached folder of this render, rendered by `render` first when
// absent (into a folder of this process's own, then renamed, so processes rendering the same
// key at once never see half a sequence); an empty path when that render failed (its output is
// in `log`). The first render of a new CLI build removes the older builds' renders.
std::optional<std::filesystem::path> CachedRender(const std::filesystem::path& cache,
                                                  const std::string& cli,
                                                  const std::string& synth_args,
                                                  const std::filesystem::path& log,
                                                  RenderFunction render);

// DRVSLAM_TEST_SYNTH_CACHE, or an empty path when it is unset or empty.
std::filesystem::path RenderCacheFromEnvironment();

}  // namespace drvslam::test
