// Map files: a round trip keeps every saved field, a loaded map has the saved graph and bags of
// words, and each kind of bad file (truncated, a corrupt byte, another format version, another
// vocabulary, other camera intrinsics, not a map at all) gets one drvslam::Error naming the file.
#include "drvslam/mapfile/map_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/core/settings.h"
#include "drvslam/loop/default_vocabulary.h"
#include "drvslam/loop/keyframe_database.h"
#include "drvslam/loop/vocabulary_io.h"
#include "drvslam/map/map.h"
#include "drvslam/mapfile/byte_codec.h"
#include "drvslam/mapfile/map_compatibility.h"
#include "drvslam/system.h"
#include "drvslam/system_options.h"
#include "drvslam/system_stats.h"
#include "drvslam/tracking/tracker_options.h"
#include "test_support/error_message.h"
#include "test_support/missing_data.h"
#include "test_support/temp_folder.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

constexpr int kKeypoints = 60;
constexpr int kPoints = 40;
constexpr int kSharedWeight = 40;

// Two keyframes 5 cm apart that both observe kPoints points, keypoints on a grid with depth.
MapFileContents SmallMap(const Settings& settings, const VocabularyIdentity& vocabulary) {
  MapFileContents contents;
  contents.settings_digest = SettingsDigest(settings);
  contents.settings_text = FormatSettings(settings);
  contents.camera = settings.camera;
  contents.pyramid_levels = settings.orb.n_levels;
  contents.pyramid_scale_factor = settings.orb.scale_factor;
  contents.vocabulary = vocabulary;
  cv::RNG rng(7);
  for (int k = 0; k < 2; ++k) {
    KeyFrameRecord keyframe;
    keyframe.id = k;
    keyframe.frame_id = 10 * k;
    keyframe.timestamp = 1.0 + k;
    keyframe.T_cw = SE3(Eigen::Quaterniond::Identity(), Eigen::Vector3d(-0.05 * k, 0.0, 0.0));
    keyframe.descriptors.create(kKeypoints, 32, CV_8UC1);
    rng.fill(keyframe.descriptors, cv::RNG::UNIFORM, 0, 256);
    for (int i = 0; i < kKeypoints; ++i) {
      keyframe.keypoints.emplace_back(50.f + 50.f * (i % 10), 50.f + 60.f * (i / 10), 31.f,
                                      10.f * i, 1.f, i % 3);
      keyframe.depth.push_back(2.0f);
    }
    keyframe.connections = {{1 - k, kSharedWeight}};
    keyframe.parent_id = k == 0 ? -1 : 0;
    contents.keyframes.push_back(std::move(keyframe));
  }
  const PinholeCamera camera(settings.camera);
  for (int i = 0; i < kPoints; ++i) {
    MapPointRecord point;
    point.id = i;
    const cv::KeyPoint& kp = contents.keyframes[0].keypoints[i];
    point.position = camera.Backproject(Eigen::Vector2d(kp.pt.x, kp.pt.y), 2.0);
    point.reference_keyframe_id = 0;
    point.visible = 5;
    point.found = 4;
    point.observations = {{0, i}, {1, i}};
    contents.points.push_back(std::move(point));
  }
  contents.next_keyframe_id = 2;
  contents.next_map_point_id = kPoints;
  return contents;
}

std::string ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void WriteBytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

class MapFileTest : public ::testing::Test {
 protected:
  void SetUp() override { folder_ = drvslam::testing::UniqueTempFolder("drvslam_map_file_test"); }
  void TearDown() override { fs::remove_all(folder_); }

  // The build's vocabulary, or false (the test is skipped) when it was not built.
  bool LoadDefaultVocabulary() {
    const std::string path = DefaultVocabularyPath();
    if (path.empty()) return false;
    vocabulary_ = LoadVocabulary(path);
    identity_ = IdentifyVocabulary(vocabulary_);
    return true;
  }

  // A System started from `path`; throws what loading throws.
  std::unique_ptr<System> LoadInto(const std::string& path, const Settings& settings,
                                   bool localization = false) {
    SystemOptions options;
    options.sequential = true;
    options.load_map = path;
    options.localization = localization;
    return std::make_unique<System>(settings, TrackerOptions(), options);
  }

  // The message of the drvslam::Error that loading `path` throws ("" when none is thrown).
  std::string LoadError(const std::string& path, const Settings& settings = Settings()) {
    try {
      LoadInto(path, settings);
    } catch (const Error& error) {
      return error.what();
    }
    return "";
  }

  fs::path folder_;
  BowVocabulary vocabulary_;
  VocabularyIdentity identity_;
};

TEST_F(MapFileTest, RoundTripKeepsEveryField) {
  const Settings settings;
  MapFileContents saved = SmallMap(settings, {1000, 1111, 0x1234});
  saved.dense = DenseMapSnapshot();
  saved.dense->anchors.push_back({1, SE3(), 12.5});
  DenseVoxelRecord voxel;
  voxel.point.position = Eigen::Vector3f(0.1f, 0.2f, 1.5f);
  voxel.point.r = 200;
  voxel.point.label = 56;
  voxel.weight = 0.25f;
  voxel.views = 3;
  voxel.evidence = -2;
  voxel.span = 7;
  saved.dense->coarse.push_back(voxel);
  const std::string path = (folder_ / "map.bin").string();
  const std::size_t bytes = WriteMapFile(path, saved);
  EXPECT_EQ(bytes, fs::file_size(path));
  EXPECT_FALSE(fs::exists(path + ".part"));

  const MapFileContents loaded = ReadMapFile(path);
  EXPECT_EQ(loaded.settings_digest, saved.settings_digest);
  EXPECT_EQ(loaded.settings_text, saved.settings_text);
  EXPECT_EQ(loaded.camera.fx, saved.camera.fx);
  EXPECT_EQ(loaded.camera.width, saved.camera.width);
  EXPECT_EQ(loaded.vocabulary, saved.vocabulary);
  ASSERT_EQ(loaded.keyframes.size(), 2u);
  const KeyFrameRecord& k1 = loaded.keyframes[1];
  EXPECT_EQ(k1.frame_id, 10);
  EXPECT_EQ(k1.parent_id, 0);
  EXPECT_DOUBLE_EQ(k1.T_cw.Translation().x(), -0.05);
  ASSERT_EQ(k1.keypoints.size(), static_cast<std::size_t>(kKeypoints));
  EXPECT_EQ(k1.keypoints[7].pt.x, saved.keyframes[1].keypoints[7].pt.x);
  EXPECT_EQ(k1.keypoints[7].octave, 1);
  EXPECT_EQ(cv::norm(k1.descriptors, saved.keyframes[1].descriptors, cv::NORM_HAMMING), 0.0);
  EXPECT_EQ(k1.connections, saved.keyframes[1].connections);
  ASSERT_EQ(loaded.points.size(), static_cast<std::size_t>(kPoints));
  EXPECT_EQ(loaded.points[3].position, saved.points[3].position);
  EXPECT_EQ(loaded.points[3].observations, saved.points[3].observations);
  EXPECT_EQ(loaded.points[3].found, 4);
  ASSERT_TRUE(loaded.dense);
  ASSERT_EQ(loaded.dense->coarse.size(), 1u);
  EXPECT_EQ(loaded.dense->anchors[0].keyframe_id, 1);
  EXPECT_EQ(loaded.dense->coarse[0].point.position, voxel.point.position);
  EXPECT_EQ(loaded.dense->coarse[0].point.label, 56);
  EXPECT_EQ(loaded.dense->coarse[0].evidence, -2);
  EXPECT_EQ(loaded.dense->coarse[0].span, 7);
  EXPECT_EQ(loaded.dense->anchors[0].timestamp, 12.5);
}

TEST_F(MapFileTest, LoadedMapHasTheSavedGraphAndBagsOfWords) {
  if (!LoadDefaultVocabulary()) DRVSLAM_MISSING_TEST_DATA() << "the build's vocabulary";
  const Settings settings;
  const std::string path = (folder_ / "map.bin").string();
  WriteMapFile(path, SmallMap(settings, identity_));
  const auto system = LoadInto(path, settings);
  const Map& map = system->GetMap();
  ASSERT_EQ(map.KeyFrameCount(), 2u);
  EXPECT_EQ(map.MapPointCount(), static_cast<std::size_t>(kPoints));
  const auto keyframes = map.KeyFrames();
  ASSERT_TRUE(keyframes[1]->Parent());
  EXPECT_EQ(keyframes[1]->Parent()->Id(), 0);
  EXPECT_EQ(keyframes[0]->Weight(1), kSharedWeight);
  EXPECT_TRUE(keyframes[0]->HasBow());
  EXPECT_FALSE(keyframes[0]->Bow().empty());
  EXPECT_EQ(system->KeyFrames().Size(), 2u);
  // Observations were rebuilt on both sides.
  const auto points = map.MapPoints();
  EXPECT_EQ(points[5]->ObservationCount(), 2);
  EXPECT_EQ(keyframes[1]->MapPointAt(5), points[5]);
  EXPECT_EQ(system->Stats().map_loaded_keyframes, 2u);
}

TEST_F(MapFileTest, TruncatedFileIsNamed) {
  const std::string path = (folder_ / "truncated.bin").string();
  WriteMapFile(path, SmallMap(Settings(), {1, 2, 3}));
  const std::string bytes = ReadBytes(path);
  WriteBytes(path, bytes.substr(0, bytes.size() / 2));
  const std::string message = testing::ErrorMessageOf([&] { ReadMapFile(path); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("truncated map file"), std::string::npos) << message;
  // Cut inside the header too.
  WriteBytes(path, bytes.substr(0, 12));
  EXPECT_THROW(ReadMapFile(path), Error);
}

TEST_F(MapFileTest, CorruptByteIsNamed) {
  const std::string path = (folder_ / "corrupt.bin").string();
  WriteMapFile(path, SmallMap(Settings(), {1, 2, 3}));
  std::string bytes = ReadBytes(path);
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x10);
  WriteBytes(path, bytes);
  const std::string message = testing::ErrorMessageOf([&] { ReadMapFile(path); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("corrupt map file: checksum mismatch"), std::string::npos) << message;
}

TEST_F(MapFileTest, CorruptContentsBehindAValidChecksumAreNamed) {
  // A writer bug, not damage: an observation past its keyframe's keypoints.
  MapFileContents contents = SmallMap(Settings(), {1, 2, 3});
  contents.points[0].observations[1].second = kKeypoints + 5;
  const std::string path = (folder_ / "inconsistent.bin").string();
  WriteMapFile(path, contents);
  const std::string message = testing::ErrorMessageOf([&] { ReadMapFile(path); });
  EXPECT_NE(message.find(path + ": corrupt map file: map point 0"), std::string::npos) << message;
}

TEST_F(MapFileTest, OtherFormatVersionIsNamed) {
  const std::string path = (folder_ / "version.bin").string();
  WriteMapFile(path, SmallMap(Settings(), {1, 2, 3}));
  std::string bytes = ReadBytes(path);
  bytes[8] = static_cast<char>(kMapFileVersion + 1);  // the version follows the 8-byte magic
  WriteBytes(path, bytes);
  const std::string message = testing::ErrorMessageOf([&] { ReadMapFile(path); });
  EXPECT_NE(message.find(path + ": map file format version " + std::to_string(kMapFileVersion + 1) +
                         "; this build reads version " + std::to_string(kMapFileVersion)),
            std::string::npos)
      << message;
}

TEST_F(MapFileTest, NotAMapFileIsNamed) {
  const std::string path = (folder_ / "settings.yaml").string();
  WriteBytes(path, "%YAML:1.0\nCamera.fx: 500\n");
  const std::string message = LoadError(path);
  EXPECT_NE(message.find(path + ": not a drvslam map file"), std::string::npos) << message;
  const std::string missing = (folder_ / "absent.bin").string();
  EXPECT_NE(LoadError(missing).find(missing + ": cannot open the map file"), std::string::npos);
}

TEST_F(MapFileTest, OtherVocabularyIsNamed) {
  if (!LoadDefaultVocabulary()) DRVSLAM_MISSING_TEST_DATA() << "the build's vocabulary";
  VocabularyIdentity other = identity_;
  other.hash ^= 1;
  const std::string path = (folder_ / "vocabulary.bin").string();
  WriteMapFile(path, SmallMap(Settings(), other));
  const std::string message = LoadError(path);
  EXPECT_NE(message.find(path + ": the map was saved with another vocabulary"), std::string::npos)
      << message;
  // The same file with the right vocabulary loads (the error came from the vocabulary alone).
  WriteMapFile(path, SmallMap(Settings(), identity_));
  EXPECT_EQ(LoadError(path), "");
}

TEST_F(MapFileTest, OtherImageSizeIsAnError) {
  if (!LoadDefaultVocabulary()) DRVSLAM_MISSING_TEST_DATA() << "the build's vocabulary";
  Settings saved;
  saved.camera.width = 320;
  saved.camera.height = 240;
  const std::string path = (folder_ / "size.bin").string();
  WriteMapFile(path, SmallMap(saved, identity_));
  const std::string message = LoadError(path);
  EXPECT_NE(message.find(path + ": the map was made with 320x240 images; Camera.width/height is "
                                "640x480"),
            std::string::npos)
      << message;
}

TEST_F(MapFileTest, IntrinsicsFarOffAreAnErrorSlightlyOffAWarning) {
  if (!LoadDefaultVocabulary()) DRVSLAM_MISSING_TEST_DATA() << "the build's vocabulary";
  const Settings now;
  Settings far = now;
  far.camera.fx *= 1.10;
  const std::string path = (folder_ / "intrinsics.bin").string();
  WriteMapFile(path, SmallMap(far, identity_));
  const std::string message = LoadError(path, now);
  EXPECT_NE(message.find(path + ": the map was made with other camera intrinsics: Camera.fx"),
            std::string::npos)
      << message;

  Settings near = now;
  near.camera.fx *= 1.005;
  WriteMapFile(path, SmallMap(near, identity_));
  const std::vector<std::string> warnings =
      CheckMapCompatibility(ReadMapFile(path), now, &vocabulary_, path);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find(path + ": camera intrinsics differ slightly from the map's: "
                                    "Camera.fx"),
            std::string::npos)
      << warnings[0];
  EXPECT_EQ(LoadError(path, now), "");
  // Identical intrinsics and settings: no warning.
  WriteMapFile(path, SmallMap(now, identity_));
  EXPECT_TRUE(CheckMapCompatibility(ReadMapFile(path), now, &vocabulary_, path).empty());
}

TEST_F(MapFileTest, LocalizationWithoutAMapIsAnError) {
  SystemOptions options;
  options.sequential = true;
  options.localization = true;
  EXPECT_THROW(System(Settings(), TrackerOptions(), options), Error);
}

TEST_F(MapFileTest, SavingToAnUnwritablePathNamesIt) {
  if (!LoadDefaultVocabulary()) DRVSLAM_MISSING_TEST_DATA() << "the build's vocabulary";
  SystemOptions options;
  options.sequential = true;
  System system(Settings(), TrackerOptions(), options);
  const std::string path = (folder_ / "no_such_folder" / "map.bin").string();
  const std::string message = testing::ErrorMessageOf([&] { system.SaveMap(path); });
  EXPECT_NE(message.find(path + ": cannot write the map file"), std::string::npos) << message;
}

TEST(ByteCodecTest, Crc32OfTheStandardCheckString) {
  // The CRC-32 check value of "123456789" (zlib, PNG).
  EXPECT_EQ(Crc32("123456789", 9), 0xCBF43926u);
}

}  // namespace
}  // namespace drvslam
