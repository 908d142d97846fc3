#include "drvslam/mapping/keyframe_culling.h"

#include <gtest/gtest.h>

#include "drvslam/mapping/map_consistency.h"
#include "drvslam/tracking/trajectory_recorder.h"
#include "synthetic_map.h"

namespace drvslam {
namespace test {
namespace {

// Six keyframes within a few centimetres, all seeing the same points.
void BuildHover(SyntheticScene& scene, SyntheticMap& map, double near_z, double far_z) {
  scene.AddRandomPoints(200, Eigen::Vector3d(-0.6, -0.45, near_z),
                        Eigen::Vector3d(0.6, 0.45, far_z));
  for (int k = 0; k < 6; ++k) {
    map.AddKeyFrame(scene, CameraAt(Eigen::Vector3d(0.01 * k, 0.0, 0.0)), ViewOptions{});
  }
}

TEST(KeyFrameGraphTest, ConnectedKeyFramesAreFreedWithTheirMap) {
  std::vector<std::weak_ptr<KeyFrame>> watched;
  {
    SyntheticScene scene;
    SyntheticMap map;
    BuildHover(scene, map, 1.5, 2.5);
    for (const auto& keyframe : map.keyframes) {
      // Every keyframe sees the others: each holds links to its neighbours.
      ASSERT_EQ(keyframe->CovisiblesByWeight().size(), map.keyframes.size() - 1);
      watched.push_back(keyframe);
    }
  }
  // Links between keyframes must not keep them alive once the map and its owners are gone.
  for (std::size_t k = 0; k < watched.size(); ++k) EXPECT_TRUE(watched[k].expired()) << k;
}

TEST(KeyFrameCullingTest, RedundantKeyFramesGoButNeverTheOrigin) {
  SyntheticScene scene;
  SyntheticMap map;
  BuildHover(scene, map, 1.5, 2.5);  // within the close-depth limit (about 3 m)
  const auto& newest = map.keyframes.back();
  // Culled in covisibility order (ties by id) while each point keeps three other observers:
  // keyframes 1, 2 and 3 go; then 4 has only two others left per point (0 and 5).
  EXPECT_EQ(CullRedundantKeyFrames(newest, map.map, KeyFrameCullingRules{}), 3);
  for (int k : {1, 2, 3}) EXPECT_TRUE(map.keyframes[k]->IsBad()) << k;
  for (int k : {0, 4, 5}) EXPECT_FALSE(map.keyframes[k]->IsBad()) << k;
  EXPECT_EQ(map.map.KeyFrameCount(), 3u);
  EXPECT_EQ(map.map.MapPointCount(), map.map_point_of.size());
  int three = 0;
  for (const auto& point : map.map.MapPoints()) {
    EXPECT_GE(point->ObservationCount(), 2);
    three += point->ObservationCount() == 3 ? 1 : 0;
  }
  EXPECT_GE(three, 190);
  // The graph was repaired: no covisibility edge or tree link leads to a culled keyframe.
  const auto problems = CheckMapConsistency(map.map);
  EXPECT_TRUE(problems.empty()) << problems.front();
  for (const auto& keyframe : map.map.KeyFrames()) {
    for (const auto& neighbour : keyframe->CovisiblesByWeight()) EXPECT_FALSE(neighbour->IsBad());
  }
  // Nothing further is redundant.
  EXPECT_EQ(CullRedundantKeyFrames(newest, map.map, KeyFrameCullingRules{}), 0);
}

TEST(KeyFrameCullingTest, DistinctViewsAreKept) {
  SyntheticScene scene;
  SyntheticMap map;
  scene.AddRandomPoints(600, Eigen::Vector3d(-1.5, -0.8, 1.5), Eigen::Vector3d(4.5, 0.8, 2.5));
  for (int k = 0; k < 4; ++k) {
    map.AddKeyFrame(scene, CameraAt(Eigen::Vector3d(1.0 * k, 0.0, 0.0)), ViewOptions{});
  }
  EXPECT_EQ(CullRedundantKeyFrames(map.keyframes.back(), map.map, KeyFrameCullingRules{}), 0);
  EXPECT_EQ(map.map.KeyFrameCount(), 4u);
}

TEST(KeyFrameCullingTest, OnlyCloseDepthPointsCount) {
  SyntheticScene scene;
  SyntheticMap map;
  BuildHover(scene, map, 4.0, 5.0);  // beyond the close-depth limit
  EXPECT_FALSE(IsRedundantKeyFrame(*map.keyframes[2], KeyFrameCullingRules{}));
  EXPECT_EQ(CullRedundantKeyFrames(map.keyframes.back(), map.map, KeyFrameCullingRules{}), 0);
}

TEST(KeyFrameCullingTest, ObserversMustSeeThePointAtASimilarOrFinerScale) {
  SyntheticScene scene;
  SyntheticMap map;
  scene.AddRandomPoints(200, Eigen::Vector3d(-0.6, -0.45, 1.5), Eigen::Vector3d(0.6, 0.45, 2.5));
  ViewOptions fine;
  ViewOptions coarse;
  coarse.octave = 3;
  map.AddKeyFrame(scene, CameraAt(Eigen::Vector3d::Zero()), fine);
  map.AddKeyFrame(scene, CameraAt(Eigen::Vector3d(0.01, 0, 0)), fine);
  for (int k = 2; k < 5; ++k)
    map.AddKeyFrame(scene, CameraAt(Eigen::Vector3d(0.01 * k, 0, 0)), coarse);
  // Keyframe 1 sees everything at level 0; the others but the origin only at level 3.
  EXPECT_FALSE(IsRedundantKeyFrame(*map.keyframes[1], KeyFrameCullingRules{}));
  // Keyframe 2 (level 3) has finer observers in 0 and 1 and equal ones in 3 and 4.
  EXPECT_TRUE(IsRedundantKeyFrame(*map.keyframes[2], KeyFrameCullingRules{}));
}

TEST(KeyFrameCullingTest, ChildrenOfACulledKeyFrameMoveToALiveParent) {
  SyntheticScene scene;
  SyntheticMap map;
  BuildHover(scene, map, 1.5, 2.5);
  const auto child = map.keyframes[2];
  const auto parent = child->Parent();
  ASSERT_TRUE(parent);
  const auto grandchildren = child->Children();
  CullRedundantKeyFrames(map.keyframes.back(), map.map, KeyFrameCullingRules{});
  ASSERT_TRUE(child->IsBad());
  // Its children now hang below a live keyframe.
  for (const auto& grandchild : grandchildren) {
    if (grandchild->IsBad()) continue;
    ASSERT_TRUE(grandchild->Parent());
    EXPECT_FALSE(grandchild->Parent()->IsBad());
  }
}

// Shifts the world under `parent` by a fixed twist D, as a loop correction would: the recorder's
// first frame, tracked at T_cw relative to a keyframe whose parent is `parent`, must move with it.
void ExpectFirstFrameFollowsACorrectionOf(KeyFrame& parent, const SE3& T_cw,
                                          const TrajectoryRecorder& recorder) {
  Vector6d twist;
  twist << 0.1, -0.05, 0.02, 0.01, 0.03, -0.02;
  const SE3 D = SE3::Exp(twist);
  parent.SetPose(parent.Pose() * D);
  const SE3 expected_T_wc = (T_cw * D).Inverse();
  const SE3 actual_T_wc = recorder.CameraTrajectory()[0].T_wc;
  EXPECT_LT((actual_T_wc.Translation() - expected_T_wc.Translation()).norm(), 1e-9);
  EXPECT_LT(RotationAngle(actual_T_wc.Inverse() * expected_T_wc), 1e-9);
}

TEST(KeyFrameCullingTest, FramesOfACulledKeyFrameFollowItsParent) {
  SyntheticScene scene;
  SyntheticMap map;
  BuildHover(scene, map, 1.5, 2.5);
  const auto culled = map.keyframes[1];
  // A frame tracked 3 cm beside keyframe 1, with keyframe 1 as its reference.
  const SE3 T_cw = CameraAt(Eigen::Vector3d(0.04, 0.01, 0.0), 0.02);
  TrajectoryRecorder recorder;
  recorder.AddTracked(1.0, T_cw, culled);
  ASSERT_EQ(CullRedundantKeyFrames(map.keyframes.back(), map.map, KeyFrameCullingRules{}), 3);
  ASSERT_TRUE(culled->IsBad());
  const auto parent = culled->Parent();
  ASSERT_TRUE(parent && !parent->IsBad());
  // Removal alone does not move the frame.
  EXPECT_LT(
      (recorder.CameraTrajectory()[0].T_wc.Translation() - T_cw.Inverse().Translation()).norm(),
      1e-12);
  // A later correction of the parent (here a shift of the world by D) carries the frame along.
  ExpectFirstFrameFollowsACorrectionOf(*parent, T_cw, recorder);
}

TEST(KeyFrameCullingTest, TheTrajectoryDoesNotKeepRemovedKeyFramesOrTheirPoints) {
  // Issue 16 item 3: history must not hold what the map let go. The recorder keeps a removed
  // reference keyframe only until it has noted its link to the parent, and a removed keyframe
  // lets go of its map points.
  SyntheticScene scene;
  SyntheticMap map;
  BuildHover(scene, map, 1.5, 2.5);
  std::shared_ptr<KeyFrame> culled = map.keyframes[1];
  const SE3 T_cw = CameraAt(Eigen::Vector3d(0.04, 0.01, 0.0), 0.02);
  TrajectoryRecorder recorder;
  recorder.AddTracked(1.0, T_cw, culled);
  ASSERT_EQ(CullRedundantKeyFrames(map.keyframes.back(), map.map, KeyFrameCullingRules{}), 3);
  ASSERT_TRUE(culled->IsBad());
  for (const auto& point : culled->MapPoints()) EXPECT_EQ(point, nullptr);
  const auto parent = culled->Parent();
  ASSERT_TRUE(parent && !parent->IsBad());
  const std::weak_ptr<KeyFrame> watch = culled;
  map.keyframes.erase(map.keyframes.begin() + 1);
  culled.reset();
  ASSERT_FALSE(watch.expired()) << "the recorder holds it until its next fold";
  // Frames tracked on: the recorder notes the removed keyframe's link and lets it go.
  for (int i = 0; i < 200; ++i) recorder.AddTracked(2.0 + i, T_cw, parent);
  EXPECT_TRUE(watch.expired()) << "a removed keyframe outlives the map in the trajectory";
  // The first frame still follows the parent.
  EXPECT_LT(
      (recorder.CameraTrajectory()[0].T_wc.Translation() - T_cw.Inverse().Translation()).norm(),
      1e-12);
  ExpectFirstFrameFollowsACorrectionOf(*parent, T_cw, recorder);
}

}  // namespace
}  // namespace test
}  // namespace drvslam

namespace drvslam {
namespace test {
namespace {

// The recorder names the frames tracked again after a loss, where the saved trajectory's
// smoothing must assume no motion; a loss before the first tracked frame names none.
TEST(TrajectoryRecorderTest, NamesTheFramesTrackedAgainAfterALoss) {
  SyntheticScene scene;
  SyntheticMap map;
  BuildHover(scene, map, 1.5, 2.5);
  const std::shared_ptr<KeyFrame>& keyframe = map.keyframes[0];
  TrajectoryRecorder recorder;
  recorder.AddLost(0.0);
  recorder.AddTracked(1.0, keyframe->Pose(), keyframe);
  recorder.AddTracked(2.0, keyframe->Pose(), keyframe);
  recorder.AddLost(3.0);
  recorder.AddLost(4.0);
  recorder.AddTracked(5.0, keyframe->Pose(), keyframe);
  recorder.AddTracked(6.0, keyframe->Pose(), keyframe);
  recorder.AddLost(7.0);
  recorder.AddTracked(8.0, keyframe->Pose(), keyframe);
  std::vector<std::size_t> resumed;
  const Trajectory trajectory = recorder.CameraTrajectory(&resumed);
  ASSERT_EQ(trajectory.size(), 5u);
  EXPECT_EQ(resumed, (std::vector<std::size_t>{2, 4}));
  EXPECT_EQ(trajectory[2].timestamp, 5.0);
  EXPECT_EQ(recorder.CameraTrajectory().size(), trajectory.size());
}

}  // namespace
}  // namespace test
}  // namespace drvslam
