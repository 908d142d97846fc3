// The cache of rendered synthetic sequences (synth_render_cache.h), with a stand-in renderer that
// counts its calls: no CLI runs here.
#include "synth_render_cache.h"

#include <gtest/gtest.h>

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

class SynthRenderCacheTest : public ::testing::Test {
 protected:
  void SetUp() override { renders = 0; }
  void TearDown() override { fs::remove_all(folder_); }
  const fs::path folder_ = drvslam::testing::UniqueTempFolder("drvslam_render_cache");
};

TEST_F(SynthRenderCacheTest, KeyFollowsTheContentsOfNamedFilesNotTheirNames) {
  WriteText(folder_ / "path_a.txt", "0 0 0 0 0 0 0 1\n");
  WriteText(folder_ / "path_b.txt", "0 0 0 0 0 0 0 1\n");
  WriteText(folder_ / "path_c.txt", "0 1 0 0 0 0 0 1\n");
  const std::string a =
      RenderKey("drvslam", "--seed 2 --trajectory " + (folder_ / "path_a.txt").string());
  const std::string b =
      RenderKey("drvslam", "--seed 2 --trajectory " + (folder_ / "path_b.txt").string());
  const std::string c =
      RenderKey("drvslam", "--seed 2 --trajectory " + (folder_ / "path_c.txt").string());
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  EXPECT_NE(RenderKey("drvslam", "--seed 2"), RenderKey("drvslam", "--seed 3"));
  // Word boundaries count: "--frames 12 3" is not "--frames 1 23".
  EXPECT_NE(RenderKey("drvslam", "--frames 12 3"), RenderKey("drvslam", "--frames 1 23"));
}

TEST_F(SynthRenderCacheTest, KeyChangesWhenTheCliIsRebuilt) {
  const fs::path cli = folder_ / "drvslam";
  WriteText(cli, "build 1");
  const std::string before = RenderKey(cli.string(), "--seed 2");
  fs::last_write_time(cli, fs::last_write_time(cli) + std::chrono::seconds(5));
  EXPECT_NE(RenderKey(cli.string(), "--seed 2"), before);
}

TEST_F(SynthRenderCacheTest, RendersOnceThenHandsBackTheSameFolder) {
  const fs::path cache = folder_ / "cache";
  const std::optional<fs::path> first =
      CachedRender(cache, "drvslam", "--seed 2", folder_ / "log", &CountingRender);
  ASSERT_TRUE(first.has_value());
  ASSERT_FALSE(first->empty());
  const std::optional<fs::path> second =
      CachedRender(cache, "drvslam", "--seed 2", folder_ / "log", &CountingRender);
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(*second, *first);
  EXPECT_EQ(renders, 1);
  EXPECT_EQ(ReadText(*first / "args.txt"), "--seed 2");
  CachedRender(cache, "drvslam", "--seed 3", folder_ / "log", &CountingRender);
  EXPECT_EQ(renders, 2);
  // Only finished renders stay in the cache: no partial folder is left behind.
  int entries = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(cache)) {
    EXPECT_EQ(entry.path().filename().string().find(".partial"), std::string::npos);
    ++entries;
  }
  EXPECT_EQ(entries, 2);
}

TEST_F(SynthRenderCacheTest, AFailedRenderIsNotKept) {
  const fs::path cache = folder_ / "cache";
  const std::optional<fs::path> failed =
      CachedRender(cache, "drvslam", "--seed 2", folder_ / "log", &FailingRender);
  ASSERT_TRUE(failed.has_value());
  EXPECT_TRUE(failed->empty());
  EXPECT_TRUE(fs::is_empty(cache));
  CachedRender(cache, "drvslam", "--seed 2", folder_ / "log", &CountingRender);
  EXPECT_EQ(renders, 2);  // tried again, not served the failure
}

TEST_F(SynthRenderCacheTest, WithoutACacheFolderTheCallerRenders) {
  EXPECT_FALSE(CachedRender(fs::path(), "drvslam", "--seed 2", folder_ / "log", &CountingRender)
                   .has_value());
  EXPECT_EQ(renders, 0);
}

}  // namespace
}  // namespace drvslam::test
