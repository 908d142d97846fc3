#include "drvslam/mapping/local_mapper.h"

#include <gtest/gtest.h>

#include <random>

#include "drvslam/core/error.h"
#include "drvslam/mapping/map_consistency.h"
#include "synthetic_map.h"

namespace drvslam {
namespace test {
namespace {

constexpr int kKeyFrames = 10;

// Feeds keyframes to a LocalMapper the way tracking makes them: slots hold the map points
// tracking matched (not yet linked back), and keypoints with depth but no point get new linked
// points. Poses carry a small error, as tracked poses do; every step is seeded.
class KeyFrameFeeder {
 public:
  explicit KeyFrameFeeder(Map& map) : map_(map), rng_(5) {
    scene_.AddRandomPoints(700, Eigen::Vector3d(-1.5, -1.0, 1.5), Eigen::Vector3d(3.0, 1.0, 3.5));
  }

  SE3 TruePose(int k) const { return CameraAt(Eigen::Vector3d(0.12 * k, 0.02 * k, 0.0), 0.01 * k); }

  std::shared_ptr<KeyFrame> Next() {
    const int k = static_cast<int>(made_);
    ViewOptions options;
    options.pixel_noise = 0.3;
    std::vector<int> point_of_keypoint;
    auto features = scene_.View(TruePose(k), options, &point_of_keypoint);
    std::normal_distribution<double> n(0.0, 1.0);
    Vector6d twist;
    twist << 0.004 * n(rng_), 0.004 * n(rng_), 0.004 * n(rng_), 0.001 * n(rng_), 0.001 * n(rng_),
        0.001 * n(rng_);
    const SE3 pose = k == 0 ? TruePose(0) : SE3::Exp(twist) * TruePose(k);
    std::vector<std::shared_ptr<MapPoint>> tracked(point_of_keypoint.size());
    for (std::size_t i = 0; i < point_of_keypoint.size(); ++i) {
      auto it = points_.find(point_of_keypoint[i]);
      if (it == points_.end()) continue;
      auto point = it->second;
      while (point && point->IsBad()) point = point->ReplacedBy();
      if (point && !point->IsBad()) tracked[i] = point;
    }
    auto keyframe =
        std::make_shared<KeyFrame>(map_.NextKeyFrameId(), k, 0.1 * k, features, pose, tracked);
    map_.AddKeyFrame(keyframe);
    // Depth points for up to 150 free keypoints, as tracking's keyframe creation adds.
    int added = 0;
    for (std::size_t i = 0; i < point_of_keypoint.size() && added < 150; ++i) {
      if (tracked[i]) continue;
      Eigen::Vector3d position;
      if (!keyframe->UnprojectDepth(i, &position)) continue;
      auto point = std::make_shared<MapPoint>(map_.NextMapPointId(), position, keyframe);
      point->AddObservation(keyframe, static_cast<int>(i));
      keyframe->AddMapPoint(point, i);
      point->ComputeDistinctiveDescriptor();
      point->UpdateNormalAndDepth(features->Geometry().pyramid);
      map_.AddMapPoint(point);
      points_[point_of_keypoint[i]] = point;
      ++added;
    }
    ++made_;
    return keyframe;
  }

 private:
  Map& map_;
  SyntheticScene scene_;
  std::mt19937 rng_;
  std::map<int, std::shared_ptr<MapPoint>> points_;
  std::size_t made_ = 0;
};

struct RunResult {
  std::vector<SE3> poses;
  std::vector<std::pair<long, Eigen::Vector3d>> points;
  LocalMappingStats stats;
  std::vector<std::string> problems;
  double mean_position_error = 0.0;
};

RunResult RunMapper(bool sequential, const LocalMappingOptions& options = {}) {
  Map map;
  KeyFrameFeeder feeder(map);
  RunResult result;
  {
    LocalMapper mapper(map, options, sequential);
    for (int k = 0; k < kKeyFrames; ++k) mapper.InsertKeyFrame(feeder.Next());
    mapper.Shutdown();
    EXPECT_TRUE(mapper.AcceptsKeyFrames());
    EXPECT_EQ(mapper.QueuedKeyFrames(), 0);
    result.stats = mapper.Stats();
  }
  for (const auto& keyframe : map.KeyFrames()) {
    result.poses.push_back(keyframe->Pose());
    result.mean_position_error +=
        test::PositionError(*keyframe, feeder.TruePose(static_cast<int>(keyframe->FrameId())));
  }
  result.mean_position_error /= static_cast<double>(result.poses.size());
  for (const auto& point : map.MapPoints())
    result.points.emplace_back(point->Id(), point->Position());
  result.problems = CheckMapConsistency(map);
  return result;
}

TEST(LocalMapperTest, SequentialRunsEveryStepAndKeepsTheMapConsistent) {
  const RunResult run = RunMapper(/*sequential=*/true);
  EXPECT_TRUE(run.problems.empty()) << run.problems.front();
  EXPECT_EQ(run.stats.keyframes_processed, kKeyFrames);
  EXPECT_EQ(run.stats.bundle_adjustments, kKeyFrames - 2);  // from the third keyframe on
  EXPECT_EQ(run.stats.bundle_adjustments_interrupted, 0);
  EXPECT_GT(run.stats.points_from_tracking, 0);
  EXPECT_GT(run.stats.points_triangulated, 0);
  EXPECT_GT(run.stats.points_culled, 0);
  // Tracked poses were off by about 7 mm; local BA brings them closer to the truth.
  EXPECT_LT(run.mean_position_error, 0.004);
}

TEST(LocalMapperTest, SequentialModeIsBitIdentical) {
  const RunResult a = RunMapper(true);
  const RunResult b = RunMapper(true);
  ASSERT_EQ(a.poses.size(), b.poses.size());
  for (std::size_t k = 0; k < a.poses.size(); ++k) {
    EXPECT_EQ(a.poses[k].Translation(), b.poses[k].Translation());
    EXPECT_EQ(a.poses[k].Quaternion().coeffs(), b.poses[k].Quaternion().coeffs());
  }
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].first, b.points[i].first);
    EXPECT_EQ(a.points[i].second, b.points[i].second);
  }
}

TEST(LocalMapperTest, ThreadedMappingFinishesTheQueueOnShutdown) {
  const RunResult run = RunMapper(/*sequential=*/false);
  EXPECT_TRUE(run.problems.empty()) << run.problems.front();
  EXPECT_EQ(run.stats.keyframes_processed, kKeyFrames);
  EXPECT_GE(run.stats.bundle_adjustments, 1);
  EXPECT_LT(run.mean_position_error, 0.01);
}

TEST(LocalMapperTest, DisabledMappingOnlyKeepsTheBooks) {
  LocalMappingOptions options;
  options.enabled = false;
  Map map;
  KeyFrameFeeder feeder(map);
  LocalMapper mapper(map, options, /*sequential=*/false);
  const auto first = feeder.Next();
  mapper.InsertKeyFrame(first);
  const auto second = feeder.Next();
  mapper.InsertKeyFrame(second);  // processed before returning: no thread
  // The tracked points of the second keyframe now know it, and the two are connected.
  int linked = 0;
  for (const auto& point : second->MapPoints()) {
    if (point && point->IndexIn(second->Id()) >= 0) ++linked;
  }
  EXPECT_GT(linked, 100);
  EXPECT_GT(second->Weight(first->Id()), 15);
  EXPECT_EQ(second->Parent(), first);
  const LocalMappingStats stats = mapper.Stats();
  EXPECT_EQ(stats.keyframes_processed, 2);
  EXPECT_EQ(stats.points_triangulated, 0);
  EXPECT_EQ(stats.bundle_adjustments, 0);
  EXPECT_TRUE(CheckMapConsistency(map).empty());
}

TEST(LocalMapperTest, ResetDropsQueuedWorkAndShutdownDoesNotHang) {
  Map map;
  KeyFrameFeeder feeder(map);
  LocalMapper mapper(map, LocalMappingOptions{}, /*sequential=*/false);
  for (int k = 0; k < 6; ++k) mapper.InsertKeyFrame(feeder.Next());
  mapper.RequestReset();
  map.Clear();
  mapper.Shutdown();
  EXPECT_TRUE(mapper.AcceptsKeyFrames());
  EXPECT_LE(mapper.Stats().keyframes_processed, 6);
  // After shutdown a keyframe still gets its bookkeeping, on the caller's thread.
  Map fresh;
  KeyFrameFeeder second_feeder(fresh);
  const auto keyframe = second_feeder.Next();
  mapper.InsertKeyFrame(keyframe);
  EXPECT_TRUE(CheckMapConsistency(fresh).empty());
}

TEST(LocalMapperTest, RejectsBadOptions) {
  Map map;
  LocalMappingOptions options;
  options.queue_capacity = 0;
  EXPECT_THROW(LocalMapper(map, options, true), Error);
}

}  // namespace
}  // namespace test
}  // namespace drvslam
