// The cache of rendered synthetic sequences (synth_render_cache.h), with stand-in renderers that
// count their calls: no CLI runs here.
#include "synth_render_cache.h"

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <string>

#include "test_support/temp_folder.h"

namespace drvslam::test {
namespace {

namespace fs = std::filesystem;

int renders = 0;

void WriteText(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  std::string text;
  std::getline(in, text);
  return text;
}

// Writes the arguments into out/args.txt, as a render writes its frames.
std::string CountingRender(const std::string&, const std::string& synth_args, const fs::path& out,
                           const fs::path&) {
  ++renders;
  fs::create_directories(out);
  WriteText(out / "args.txt", synth_args);
  return "";
}

std::string FailingRender(const std::string&, const std::string&, const fs::path& out,
                          const fs::path&) {
  ++renders;
  fs::create_directories(out);
  WriteText(out / "half.txt", "half a sequence");
  return "synth failed";
}

// Leaves no partial folder behind: only finished renders are entries.
int EntriesWithoutPartials(const fs::path& folder) {
  int entries = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    EXPECT_EQ(entry.path().filename().string().find(".partial"), std::string::npos) << entry.path();
    ++entries;
  }
  return entries;
}

class SynthRenderCacheTest : public ::testing::Test {
 protected:
  void SetUp() override { renders = 0; }
  void TearDown() override { fs::remove_all(folder_); }
  const fs::path folder_ = drvslam::testing::UniqueTempFolder("drvslam_render_cache");
  const fs::path cache_ = folder_ / "cache";
  const fs::path log_ = folder_ / "log";
};

TEST_F(SynthRenderCacheTest, ArgumentsNamingFilesOrFoldersAreNotCached) {
  WriteText(folder_ / "path.txt", "0 0 0 0 0 0 0 1\n");
  EXPECT_TRUE(Cacheable("--scenario static_xyz --frames 30 --seed 3"));
  EXPECT_FALSE(Cacheable("--seed 2 --trajectory " + (folder_ / "path.txt").string()));
  EXPECT_FALSE(Cacheable("--textures " + folder_.string()));
  EXPECT_FALSE(CachedRender(cache_, "drvslam", "--trajectory " + (folder_ / "path.txt").string(),
                            log_, &CountingRender)
                   .has_value());
  EXPECT_EQ(renders, 0);
}

TEST_F(SynthRenderCacheTest, KeysTellArgumentsAndCliBuildsApart) {
  EXPECT_NE(ArgumentsKey("--seed 2"), ArgumentsKey("--seed 3"));
  // Word boundaries count: "--frames 12 3" is not "--frames 1 23".
  EXPECT_NE(ArgumentsKey("--frames 12 3"), ArgumentsKey("--frames 1 23"));
  EXPECT_EQ(ArgumentsKey("--seed  2"), ArgumentsKey("--seed 2"));
  const fs::path cli = folder_ / "drvslam";
  WriteText(cli, "build 1");
  const std::string before = CliKey(cli.string());
  fs::last_write_time(cli, fs::last_write_time(cli) + std::chrono::seconds(5));
  EXPECT_NE(CliKey(cli.string()), before);
}

TEST_F(SynthRenderCacheTest, RendersOnceThenHandsBackTheSameFolder) {
  const std::optional<fs::path> first =
      CachedRender(cache_, "drvslam", "--seed 2", log_, &CountingRender);
  ASSERT_TRUE(first.has_value());
  ASSERT_FALSE(first->empty());
  const std::optional<fs::path> second =
      CachedRender(cache_, "drvslam", "--seed 2", log_, &CountingRender);
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(*second, *first);
  EXPECT_EQ(renders, 1);
  EXPECT_EQ(ReadText(*first / "args.txt"), "--seed 2");
  CachedRender(cache_, "drvslam", "--seed 3", log_, &CountingRender);
  EXPECT_EQ(renders, 2);
  EXPECT_EQ(EntriesWithoutPartials(first->parent_path()), 2);
}

TEST_F(SynthRenderCacheTest, AProcessThatLosesTheRaceUsesTheWinnersRender) {
  // Another process renamed its render into place while this one rendered.
  const fs::path winner = cache_ / CliKey("drvslam") / ArgumentsKey("--seed 2");
  const auto render_while_another_wins = [](const std::string& cli, const std::string& args,
                                            const fs::path& out, const fs::path& log) {
    const fs::path entry = out.parent_path() / ArgumentsKey(args);
    fs::create_directories(entry);
    WriteText(entry / "args.txt", "the winner's");
    return CountingRender(cli, args, out, log);
  };
  const std::optional<fs::path> got =
      CachedRender(cache_, "drvslam", "--seed 2", log_, render_while_another_wins);
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(*got, winner);
  EXPECT_EQ(ReadText(winner / "args.txt"), "the winner's");
  EXPECT_EQ(EntriesWithoutPartials(winner.parent_path()), 1);
}

TEST_F(SynthRenderCacheTest, AFailedRenderIsNotKept) {
  const std::optional<fs::path> failed =
      CachedRender(cache_, "drvslam", "--seed 2", log_, &FailingRender);
  ASSERT_TRUE(failed.has_value());
  EXPECT_TRUE(failed->empty());
  EXPECT_EQ(EntriesWithoutPartials(cache_ / CliKey("drvslam")), 0);
  CachedRender(cache_, "drvslam", "--seed 2", log_, &CountingRender);
  EXPECT_EQ(renders, 2);  // tried again, not served the failure
}

TEST_F(SynthRenderCacheTest, ANewCliBuildRemovesTheOlderBuildsRenders) {
  const fs::path cli = folder_ / "drvslam";
  WriteText(cli, "build 1");
  const std::optional<fs::path> old_render =
      CachedRender(cache_, cli.string(), "--seed 2", log_, &CountingRender);
  ASSERT_TRUE(old_render.has_value());
  ASSERT_TRUE(fs::is_directory(*old_render));
  WriteText(cli, "build 2, a longer binary");
  const std::optional<fs::path> new_render =
      CachedRender(cache_, cli.string(), "--seed 2", log_, &CountingRender);
  ASSERT_TRUE(new_render.has_value());
  EXPECT_NE(*new_render, *old_render);
  EXPECT_EQ(renders, 2);
  EXPECT_FALSE(fs::exists(*old_render));
  EXPECT_EQ(EntriesWithoutPartials(cache_), 1);
}

TEST_F(SynthRenderCacheTest, WithoutACacheFolderTheCallerRenders) {
  EXPECT_FALSE(CachedRender(fs::path(), "drvslam", "--seed 2", log_, &CountingRender).has_value());
  EXPECT_EQ(renders, 0);
}

}  // namespace
}  // namespace drvslam::test
