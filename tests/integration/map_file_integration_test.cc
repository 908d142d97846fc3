// Map files end to end: a map made along one camera path of a synthetic room (saved with
// --save-map) is loaded by a run along another path of the same room (--load-map): with
// --localization it must relocalize within kMaxFramesToRelocalize frames and track within 1 cm
// of the truth without any alignment of its own (the map's frame is put into the truth's by
// the mapping run's alignment), adding nothing to the map, and verify the pose two frames later;
// without it the map grows. A map made in a room with walking people (ORACLE ground-truth masks)
// holds no point on them, while the same run without dynamic handling plants points on them (so
// the check can fail).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <string>
#include <vector>

#include "drvslam/io/text_lines.h"
#include "drvslam/io/trajectory_io.h"
#include "drvslam/mapfile/map_file.h"
#include "drvslam/tools/eval/ate.h"
#include "drvslam/tools/runner/sequence_runner.h"
#include "drvslam/tracking/localization_check.h"
#include "synthesized_sequence.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

constexpr int kFrames = 150;
constexpr int kMaxFramesToRelocalize = 10;
constexpr double kMaxAteMetres = 0.01;

RunSummary RunSlam(const fs::path& dataset, const fs::path& out, const std::string& segmenter,
                   const std::string& save_map, const std::string& load_map, bool localization) {
  RunOptions options;
  options.dataset = dataset.string();
  options.out_dir = out.string();
  options.sequential = true;
  options.dynamic.segmenter = segmenter;
  options.dense = "off";
  options.save_map = save_map;
  options.load_map = load_map;
  options.localization = localization;
  return RunSequence(options);
}

Trajectory GroundTruth(const fs::path& dataset) {
  return ReadTumTrajectory((dataset / "groundtruth.txt").string());
}

Trajectory Estimate(const fs::path& out) {
  return ReadTumTrajectory((out / "CameraTrajectory.txt").string(), /*allow_empty=*/true);
}

// Index in the sequence's frame list of the first tracked frame (-1: none).
int FirstTrackedFrame(const fs::path& dataset, const Trajectory& estimate) {
  if (estimate.empty()) return -1;
  int index = 0;
  int found = -1;
  ForEachDataLine(
      (dataset / "associations.txt").string(), [&](int, const std::vector<std::string>& fields) {
        if (found < 0 && std::abs(std::stod(fields[0]) - estimate[0].timestamp) < 1e-4) {
          found = index;
        }
        ++index;
      });
  return found;
}

// Map points observed, in any keyframe, on a pixel of a person in that frame's ground-truth
// instance mask.
std::size_t PointsOnPeople(const MapFileContents& map, const fs::path& dataset) {
  std::set<int> people;
  ForEachDataLine((dataset / "instances.txt").string(),
                  [&](int, const std::vector<std::string>& fields) {
                    if (fields.size() >= 3 && fields[0] == "instance" && fields[2] == "person") {
                      people.insert(std::stoi(fields[1]));
                    }
                  });
  std::map<long, cv::Mat> masks;  // per keyframe id
  for (const KeyFrameRecord& keyframe : map.keyframes) {
    char name[64];
    std::snprintf(name, sizeof(name), "%.6f.png", keyframe.timestamp);
    masks[keyframe.id] = cv::imread((dataset / "masks" / name).string(), cv::IMREAD_UNCHANGED);
  }
  std::size_t on_people = 0;
  for (const MapPointRecord& point : map.points) {
    bool on_person = false;
    for (const auto& [keyframe_id, index] : point.observations) {
      const cv::Mat& mask = masks[keyframe_id];
      const KeyFrameRecord* keyframe = nullptr;
      for (const KeyFrameRecord& k : map.keyframes) {
        if (k.id == keyframe_id) keyframe = &k;
      }
      if (mask.empty() || keyframe == nullptr) continue;
      const cv::Point2f& pt = keyframe->keypoints[index].pt;
      const int u = static_cast<int>(std::lround(pt.x)), v = static_cast<int>(std::lround(pt.y));
      if (u < 0 || v < 0 || u >= mask.cols || v >= mask.rows) continue;
      const int instance =
          mask.depth() == CV_16U ? mask.at<uint16_t>(v, u) : mask.at<uint8_t>(v, u);
      on_person |= people.count(instance) > 0;
    }
    on_people += on_person ? 1 : 0;
  }
  return on_people;
}

class MapFileIntegrationTest : public ::testing::Test {
 protected:
  void SetUp() override { root_ = test::FreshTempFolder("drvslam_map_file_integration"); }
  void TearDown() override { fs::remove_all(root_); }

  // Synthesizes `scenario` (seed 1: the room is the seed's, the path the scenario's).
  fs::path Sequence(const std::string& name, const std::string& scenario) {
    fs::create_directories(root_ / name);
    const std::string error =
        test::SynthesizeSequence(root_ / name, "--scenario " + scenario + " --frames " +
                                                   std::to_string(kFrames) + " --seed 1");
    EXPECT_EQ(error, "");
    return root_ / name / "seq";
  }

  // Localizes `dataset` in `map` and checks relocalization, accuracy in the map's frame put
  // into the truth's by `alignment`, and that nothing was added.
  void ExpectLocalizes(const fs::path& dataset, const std::string& map, const Alignment& alignment,
                       std::size_t map_keyframes, std::size_t map_points) {
    const fs::path out = root_ / "localize";
    const RunSummary summary = RunSlam(dataset, out, "none", "", map, /*localization=*/true);
    EXPECT_EQ(summary.stats.keyframes, map_keyframes);
    EXPECT_LE(summary.stats.map_points, map_points);
    EXPECT_EQ(summary.stats.map_loaded_keyframes, map_keyframes);
    const Trajectory estimate = Estimate(out);
    const int first = FirstTrackedFrame(dataset, estimate);
    ASSERT_GE(first, 0) << "never relocalized in the loaded map";
    EXPECT_LE(first, kMaxFramesToRelocalize);
    // Verified (docs/maps-and-localization.md) once the next frames confirm the pose: at most a
    // frame later than the confirmation needs.
    const long verified = summary.stats.first_verified_frame;
    EXPECT_GE(verified, first + LocalizationCheck::kConfirmFrames - 1);
    EXPECT_LE(verified, first + LocalizationCheck::kConfirmFrames);
    EXPECT_EQ(summary.stats.relocalizations_ambiguous, 0);
    EXPECT_EQ(summary.stats.relocalizations_depth_rejected, 0);
    AteOptions options;
    options.fixed_alignment = alignment;
    options.sequence_frames = kFrames;
    const AteResult ate = ComputeAte(GroundTruth(dataset), estimate, options);
    EXPECT_LE(ate.errors.rmse, kMaxAteMetres);
    EXPECT_GE(ate.coverage, 0.9);
    std::printf(
        "localized: first tracked frame %d, first verified frame %ld, ATE rmse %.4f m (no "
        "alignment fitted), coverage %.3f\n",
        first, verified, ate.errors.rmse, ate.coverage);
  }

  fs::path root_;
};

TEST_F(MapFileIntegrationTest, LocalizesAnotherPathInASavedStaticMap) {
  const fs::path a = Sequence("a", "static_xyz");
  const fs::path b = Sequence("b", "static_halfsphere");
  const std::string map = (root_ / "static.map").string();
  const RunSummary mapped = RunSlam(a, root_ / "map_run", "none", map, "", false);
  ASSERT_EQ(mapped.map_saved_to, map);
  const AteResult a_ate = ComputeAte(GroundTruth(a), Estimate(root_ / "map_run"), AteOptions());
  ExpectLocalizes(b, map, a_ate.alignment, mapped.stats.keyframes, mapped.stats.map_points);

  // Without --localization the loaded map grows, its keyframes kept.
  const RunSummary extended = RunSlam(b, root_ / "extend", "none", "", map, false);
  EXPECT_GT(extended.stats.keyframes, mapped.stats.keyframes);
  AteOptions options;
  options.fixed_alignment = a_ate.alignment;
  const AteResult b_ate = ComputeAte(GroundTruth(b), Estimate(root_ / "extend"), options);
  EXPECT_LE(b_ate.errors.rmse, kMaxAteMetres);
  EXPECT_EQ(FirstTrackedFrame(b, Estimate(root_ / "extend")), 0);
  std::printf("extended: %zu keyframes from %zu loaded, ATE rmse %.4f m (no alignment fitted)\n",
              extended.stats.keyframes, mapped.stats.keyframes, b_ate.errors.rmse);
}

TEST_F(MapFileIntegrationTest, MapOfAWalkingSceneHasNoPointsOnThePeople) {
  const fs::path a = Sequence("a", "walking_xyz");
  const fs::path b = Sequence("b", "static_halfsphere");
  // ORACLE masks (the sequence's ground truth) for the mapping run.
  const std::string map = (root_ / "walking.map").string();
  const RunSummary mapped = RunSlam(a, root_ / "map_run", "gt", map, "", false);
  const MapFileContents contents = ReadMapFile(map);
  const std::size_t on_people = PointsOnPeople(contents, a);
  EXPECT_EQ(on_people, 0u);
  // The check can fail: without dynamic handling the people are mapped.
  const std::string baseline_map = (root_ / "baseline.map").string();
  RunSlam(a, root_ / "baseline_run", "none", baseline_map, "", false);
  const MapFileContents baseline = ReadMapFile(baseline_map);
  const std::size_t baseline_on_people = PointsOnPeople(baseline, a);
  EXPECT_GT(baseline_on_people, 20u);
  std::printf("map points on people: %zu of %zu (gt masks, ORACLE), %zu of %zu (dynamic off)\n",
              on_people, contents.points.size(), baseline_on_people, baseline.points.size());

  const AteResult a_ate = ComputeAte(GroundTruth(a), Estimate(root_ / "map_run"), AteOptions());
  ExpectLocalizes(b, map, a_ate.alignment, mapped.stats.keyframes, mapped.stats.map_points);
}

}  // namespace
}  // namespace drvslam
