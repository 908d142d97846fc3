#include "drvslam/mapping/local_bundle_adjuster.h"

#include <gtest/gtest.h>

#include <random>
#include <set>

#include "drvslam/mapping/map_consistency.h"
#include "synthetic_map.h"

namespace drvslam {
namespace test {
namespace {

// Eight keyframes along a 3.5 m path over a wall of points: the last keyframe is covisible with
// its recent predecessors only, so the early ones see local points but are held fixed.
class LocalBundleAdjusterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_.AddRandomPoints(900, Eigen::Vector3d(-1.5, -1.0, 2.5), Eigen::Vector3d(5.0, 1.0, 3.5));
    for (int k = 0; k < 8; ++k) {
      truth_.push_back(CameraAt(Eigen::Vector3d(0.5 * k, 0.0, 0.0), 0.02 * k));
      map_.AddKeyFrame(scene_, truth_.back(), ViewOptions{});
    }
    newest_ = map_.keyframes.back();
    local_.insert(newest_->Id());
    for (const auto& keyframe : newest_->CovisiblesByWeight()) local_.insert(keyframe->Id());
  }

  // Moves the local keyframes (not the origin) and every point off the truth.
  void Perturb(unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> n(0.0, 1.0);
    for (const auto& keyframe : map_.keyframes) {
      if (!local_.count(keyframe->Id()) || keyframe->Id() == 0) continue;
      Vector6d twist;
      twist << 0.02 * n(rng), 0.02 * n(rng), 0.02 * n(rng), 0.005 * n(rng), 0.005 * n(rng),
          0.005 * n(rng);
      keyframe->SetPose(SE3::Exp(twist) * keyframe->Pose());
    }
    for (const auto& point : map_.map.MapPoints()) {
      point->SetPosition(point->Position() + 0.01 * Eigen::Vector3d(n(rng), n(rng), n(rng)));
    }
  }

  double LocalError() const {
    double error = 0.0;
    for (std::size_t k = 0; k < map_.keyframes.size(); ++k) {
      if (local_.count(map_.keyframes[k]->Id()))
        error += PositionError(*map_.keyframes[k], truth_[k]);
    }
    return error;
  }

  SyntheticScene scene_;
  SyntheticMap map_;
  std::vector<SE3> truth_;
  std::shared_ptr<KeyFrame> newest_;
  std::set<long> local_;
};

TEST_F(LocalBundleAdjusterTest, ReducesAKnownPerturbationAndKeepsFixedKeyFramesFixed) {
  ASSERT_LT(local_.size(), map_.keyframes.size() - 1) << "the scene must have fixed keyframes";
  Perturb(4);
  std::vector<SE3> before;
  for (const auto& keyframe : map_.keyframes) before.push_back(keyframe->Pose());
  const double error_before = LocalError();

  const LocalBundleAdjustmentStats stats =
      AdjustLocalMap(newest_, map_.map, LocalBundleAdjustmentOptions{});
  EXPECT_EQ(stats.local_keyframes, static_cast<int>(local_.size()));
  EXPECT_GE(stats.fixed_keyframes, 1);
  EXPECT_FALSE(stats.interrupted);
  EXPECT_EQ(stats.removed_observations, 0);
  const double error_after = LocalError();
  EXPECT_LT(error_after, 0.05 * error_before) << error_before << " -> " << error_after;

  for (std::size_t k = 0; k < map_.keyframes.size(); ++k) {
    const auto& keyframe = map_.keyframes[k];
    if (local_.count(keyframe->Id()) && keyframe->Id() != 0) continue;
    // Fixed keyframes (and the origin) do not move at all.
    EXPECT_EQ(keyframe->Pose().Translation(), before[k].Translation()) << "keyframe " << k;
    EXPECT_EQ(keyframe->Pose().Quaternion().coeffs(), before[k].Quaternion().coeffs());
  }
  // The local points are back near the truth.
  double worst = 0.0;
  for (const auto& point : newest_->MapPoints()) {
    if (!point) continue;
    const int index = point->IndexIn(newest_->Id());
    const int scene_index = map_.point_of_keypoint.back()[index];
    worst = std::max(worst, (point->Position() - scene_.Points()[scene_index]).norm());
  }
  EXPECT_LT(worst, 0.005);
  EXPECT_TRUE(CheckMapConsistency(map_.map).empty());
}

TEST_F(LocalBundleAdjusterTest, RemovesOutlierObservationsFromBothSides) {
  // The newest keyframe wrongly matches one of its keypoints to a point seen elsewhere.
  const auto slots = newest_->MapPoints();
  std::size_t victim_slot = 0;
  while (!slots[victim_slot] || slots[victim_slot]->ObservationCount() < 3) ++victim_slot;
  const auto victim = slots[victim_slot];
  std::shared_ptr<MapPoint> wrong;
  for (const auto& point : map_.keyframes[5]->MapPoints()) {
    if (point && point->IndexIn(newest_->Id()) < 0 &&
        (point->Position() - victim->Position()).norm() > 0.5) {
      wrong = point;
      break;
    }
  }
  ASSERT_TRUE(wrong);
  newest_->EraseMapPointAt(victim_slot);
  victim->EraseObservation(newest_->Id());
  wrong->AddObservation(newest_, static_cast<int>(victim_slot));
  newest_->AddMapPoint(wrong, victim_slot);
  ASSERT_TRUE(CheckMapConsistency(map_.map).empty());

  const LocalBundleAdjustmentStats stats =
      AdjustLocalMap(newest_, map_.map, LocalBundleAdjustmentOptions{});
  EXPECT_GE(stats.removed_observations, 1);
  EXPECT_EQ(wrong->IndexIn(newest_->Id()), -1);
  EXPECT_EQ(newest_->MapPointAt(victim_slot), nullptr);
  const auto problems = CheckMapConsistency(map_.map);
  EXPECT_TRUE(problems.empty()) << problems.front();
  // The one wrong observation did not pull the newest keyframe off.
  EXPECT_LT(PositionError(*newest_, truth_.back()), 1e-3);
}

TEST_F(LocalBundleAdjusterTest, ARaisedInterruptLeavesTheMapAlone) {
  Perturb(8);
  const SE3 before = newest_->Pose();
  std::atomic<bool> interrupt{true};
  const LocalBundleAdjustmentStats stats =
      AdjustLocalMap(newest_, map_.map, LocalBundleAdjustmentOptions{}, &interrupt);
  EXPECT_TRUE(stats.interrupted);
  EXPECT_EQ(stats.iterations, 0);
  EXPECT_EQ(newest_->Pose().Translation(), before.Translation());
}

}  // namespace
}  // namespace test
}  // namespace drvslam
