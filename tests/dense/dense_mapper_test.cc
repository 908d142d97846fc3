#include "drvslam/dense/dense_mapper.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "dense_test_frames.h"
#include "drvslam/dense/dense_export.h"
#include "drvslam/dense/point_cloud_io.h"
#include "drvslam/map/frame_features.h"
#include "drvslam/map/keyframe.h"
#include "test_support/temp_folder.h"

namespace drvslam {
namespace {

using testing::BoxInstance;
using testing::PlaneFrame;
using testing::SmallCamera;

constexpr int kBookClass = 73;
constexpr int kPersonClass = 0;

std::shared_ptr<KeyFrame> MakeKeyFrame(const CameraOptions& camera, const SE3& T_wc, long id) {
  auto geometry = std::make_shared<const SensorGeometry>(camera, ScalePyramid(), 3.0);
  auto features = std::make_shared<const FrameFeatures>(geometry, std::vector<cv::KeyPoint>(),
                                                        cv::Mat(), cv::Mat());
  return std::make_shared<KeyFrame>(id, id, 0.0, features, T_wc.Inverse(),
                                    std::vector<std::shared_ptr<MapPoint>>());
}

// A frame of a plane 0.6 m away with a book lying on it, the camera shifted sideways by
// `shift` metres.
DenseFrame BookFrame(const CameraOptions& camera, long id, double shift) {
  const SE3 T_wc(Eigen::Matrix3d::Identity(), Eigen::Vector3d(shift, 0, 0));
  DenseFrame frame = PlaneFrame(camera, 0.6f, T_wc, id);
  DenseInstance book = BoxInstance(camera, cv::Rect(60, 40, 40, 30), kBookClass);
  book.key_object = true;
  frame.instances.push_back(book);
  return frame;
}

std::size_t CountLabel(const DenseCloud& cloud, int label) {
  std::size_t n = 0;
  for (const DensePoint& p : cloud) n += p.label == label;
  return n;
}

TEST(DenseMapper, KeyObjectsAreDenserThanTheBackground) {
  const CameraOptions camera = SmallCamera();
  DenseMapOptions options;
  options.enhancement_frames = 3;  // one frame before the keyframe, two after it
  options.min_views = 1;           // one keyframe: its background counts
  options.min_view_span = 0.0;     // one view spans less than 1 s
  DenseMapper mapper(camera, options, /*sequential=*/true);
  mapper.AddFrame(BookFrame(camera, 0, 0.0));
  mapper.AddKeyFrame(BookFrame(camera, 1, 0.0013), nullptr);
  EXPECT_EQ(mapper.Stats().keyframes, 0u);  // waits for the frames after it
  for (int i = 2; i < 4; ++i) mapper.AddFrame(BookFrame(camera, i, 0.0013 * i));
  const DenseCloud cloud = mapper.Assemble();
  const DenseMapStats stats = mapper.Stats();
  EXPECT_EQ(stats.keyframes, 1u);
  EXPECT_EQ(stats.enhancement_frames, 3u);
  EXPECT_EQ(stats.full_resolution_points, static_cast<std::size_t>(camera.width * camera.height));
  const double book_pixels = 40 * 30;
  const double background_pixels = camera.width * camera.height - book_pixels;
  const double book_density = CountLabel(cloud, kBookClass) / book_pixels;
  const double background_density = CountLabel(cloud, -1) / background_pixels;
  // 4 mm pixels at 0.6 m: the 3 cm background leaf keeps one point in about 56 pixels, the
  // 5 mm object leaf about two in three pixels.
  EXPECT_GT(book_density, 0.5);
  EXPECT_LT(background_density, 0.05);
  EXPECT_GT(book_density / background_density, 20.0);
  EXPECT_EQ(stats.exported_points, cloud.size());
}

TEST(DenseMapper, WithoutEnhancementFramesOnlyTheKeyFrameCounts) {
  const CameraOptions camera = SmallCamera();
  DenseMapOptions options;
  options.enhancement_frames = 0;
  DenseMapper mapper(camera, options, true);
  for (int i = 0; i < 3; ++i) mapper.AddFrame(BookFrame(camera, i, 0.0013 * i));
  mapper.AddKeyFrame(BookFrame(camera, 3, 0.0039), nullptr);
  EXPECT_EQ(mapper.Stats().enhancement_frames, 0u);
  const DenseCloud cloud = mapper.Assemble();
  EXPECT_LE(CountLabel(cloud, kBookClass), 40u * 30u);
}

// A saved map (Snapshot, as --save-map writes it) restored into a new mapper exports the same
// points: the voxels keep their view span and the anchors their time stamps, which
// DenseMap.minViewSpan confirms points by.
TEST(DenseMapper, ARestoredSnapshotExportsTheSameMap) {
  const CameraOptions camera = SmallCamera();
  DenseMapOptions options;
  options.enhancement_frames = 0;
  DenseMapper original(camera, options, true);
  for (int i = 0; i < 6; ++i) original.AddKeyFrame(BookFrame(camera, i, 0.002 * i), nullptr);
  const DenseCloud before = original.Assemble();
  ASSERT_GT(before.size(), 100u);
  DenseMapper restored(camera, options, true);
  restored.Restore(original.Snapshot(), [](long) { return nullptr; });
  const DenseCloud after = restored.Assemble();
  ASSERT_EQ(after.size(), before.size());
  for (std::size_t i = 0; i < before.size(); ++i) {
    ASSERT_LT((after[i].position - before[i].position).norm(), 1e-5f) << i;
  }
}

TEST(DenseMapper, ThreadedAndSequentialGiveTheSameMap) {
  const CameraOptions camera = SmallCamera();
  DenseMapOptions options;
  options.queue_capacity = 2;
  DenseMapper sequential(camera, options, true);
  DenseMapper threaded(camera, options, false);
  for (int i = 0; i < 12; ++i) {
    for (DenseMapper* mapper : {&sequential, &threaded}) {
      DenseFrame frame = BookFrame(camera, i, 0.01 * i);
      if (i % 4 == 0) {
        mapper->AddKeyFrame(std::move(frame), nullptr);
      } else {
        mapper->AddFrame(std::move(frame));
      }
    }
  }
  threaded.Shutdown();
  const DenseCloud a = sequential.Assemble();
  const DenseCloud b = threaded.Assemble();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].position, b[i].position) << i;
    ASSERT_EQ(a[i].label, b[i].label) << i;
  }
  EXPECT_EQ(threaded.Stats().keyframes, 3u);
  // After shutdown keyframes are integrated on the caller's thread.
  threaded.AddKeyFrame(BookFrame(camera, 20, 0.5), nullptr);
  EXPECT_EQ(threaded.Stats().keyframes, 4u);
}

// Keyframes handed over faster than the dense thread integrates them (prepared in advance, then
// handed over back to back; one fits the realtime queue): in a realtime run they are dropped and
// counted and the hand-over never waits; otherwise every one is integrated.
TEST(DenseMapper, NeverBlockDropsKeyFramesItHasNoRoomForAndCountsThem) {
  const CameraOptions camera = SmallCamera();
  DenseMapOptions options;
  options.live_queue_capacity = 1;  // realtime runs use this one
  options.queue_capacity = 64;      // room for every keyframe: the other runs never drop
  options.enhancement_frames = 0;   // a keyframe is handed over at once
  constexpr std::size_t kKeyFrames = 40;
  for (const bool never_block : {true, false}) {
    std::vector<DenseFrame> frames;
    for (std::size_t i = 0; i < kKeyFrames; ++i) {
      frames.push_back(BookFrame(camera, static_cast<long>(i), 0.01 * i));
    }
    DenseMapper mapper(camera, options, /*sequential=*/false, nullptr, never_block);
    for (DenseFrame& frame : frames) mapper.AddKeyFrame(std::move(frame), nullptr);
    mapper.Shutdown();
    const DenseMapStats stats = mapper.Stats();
    EXPECT_EQ(stats.keyframes + stats.keyframes_dropped, kKeyFrames) << never_block;
    if (never_block) {
      EXPECT_GT(stats.keyframes_dropped, 0u);
      EXPECT_GE(stats.keyframes, 1u);
    } else {
      EXPECT_EQ(stats.keyframes_dropped, 0u);
    }
  }
}

TEST(DenseMapper, PointsFollowTheirKeyFrameWhenItsPoseIsCorrected) {
  const CameraOptions camera = SmallCamera();
  DenseMapOptions options;
  options.min_views = 1;
  options.min_view_span = 0.0;  // one view spans less than 1 s
  options.enhancement_frames = 0;
  DenseMapper mapper(camera, options, true);
  const std::shared_ptr<KeyFrame> keyframe = MakeKeyFrame(camera, SE3(), 0);
  mapper.AddKeyFrame(PlaneFrame(camera, 2.0f), keyframe);
  const DenseCloud before = mapper.Assemble();
  ASSERT_FALSE(before.empty());
  for (const DensePoint& p : before) EXPECT_NEAR(p.position.z(), 2.0f, 1e-4);
  // Bundle adjustment moves the keyframe 0.5 m along z (T_wc); its points follow.
  keyframe->SetPose(SE3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 0.5)).Inverse());
  const DenseCloud after = mapper.Assemble();
  ASSERT_EQ(after.size(), before.size());
  for (const DensePoint& p : after) EXPECT_NEAR(p.position.z(), 2.5f, 1e-4);
  // Revisiting the same place adds nothing: the world voxels are taken.
  mapper.AddKeyFrame(
      PlaneFrame(camera, 2.0f, SE3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 0.5))),
      nullptr);
  EXPECT_LE(mapper.Assemble().size(), after.size() + after.size() / 10);
}

TEST(DenseMapper, AnObjectThatStartsMovingLeavesNoGhost) {
  const CameraOptions camera = SmallCamera();
  for (const bool sticky : {true, false}) {
    DenseMapOptions options;
    options.sticky_moving = sticky;
    options.min_views = 1;        // the still person is mapped from one keyframe
    options.min_view_span = 0.0;  // one view spans less than 1 s
    options.enhancement_frames = 0;
    DenseMapper mapper(camera, options, true);
    DenseFrame still = PlaneFrame(camera, 2.0f, SE3(), 0);
    DenseInstance person = BoxInstance(camera, cv::Rect(40, 30, 40, 60), kPersonClass);
    person.potentially_moving = true;
    person.track_id = 5;
    still.instances.push_back(person);
    still.depth(cv::Rect(40, 30, 40, 60)).setTo(1.0f);  // the person stands in front
    mapper.AddKeyFrame(still, nullptr);
    EXPECT_GT(CountLabel(mapper.Assemble(), kPersonClass), 0u);
    // Later the same object walks away (judged moving).
    DenseFrame walking = PlaneFrame(camera, 2.0f, SE3(), 1);
    person.moving = true;
    walking.instances.push_back(person);
    mapper.AddFrame(walking);
    const std::size_t left = CountLabel(mapper.Assemble(), kPersonClass);
    if (sticky) {
      EXPECT_EQ(left, 0u);
    } else {
      EXPECT_GT(left, 0u);
    }
  }
}

TEST(DenseMapper, ResetDropsTheMap) {
  const CameraOptions camera = SmallCamera();
  DenseMapOptions options;
  options.min_views = 1;
  options.min_view_span = 0.0;  // one view spans less than 1 s
  DenseMapper mapper(camera, options, false);
  mapper.AddKeyFrame(PlaneFrame(camera, 2.0f), nullptr);
  mapper.Reset();
  mapper.AddKeyFrame(PlaneFrame(camera, 1.0f), nullptr);
  mapper.Shutdown();
  const DenseCloud cloud = mapper.Assemble();
  ASSERT_FALSE(cloud.empty());
  for (const DensePoint& p : cloud) EXPECT_NEAR(p.position.z(), 1.0f, 1e-4);
  EXPECT_EQ(mapper.Stats().resets, 1u);
}

TEST(DenseMapper, ExportsOnRequestWhileMapping) {
  const CameraOptions camera = SmallCamera();
  DenseMapper mapper(camera, DenseMapOptions(), /*sequential=*/false);
  mapper.AddKeyFrame(BookFrame(camera, 0, 0.0), nullptr);
  mapper.AddKeyFrame(BookFrame(camera, 1, 0.3), nullptr);
  const std::string folder = (testing::ProcessTempFolder() / "dense_export").string();
  const DenseExport first = ExportDenseMap(mapper, folder);  // the thread may still run
  mapper.Shutdown();
  const DenseExport last = ExportDenseMap(mapper, folder);
  EXPECT_LE(first.points, last.points);
  EXPECT_EQ(ReadPlyCloud(last.ply_path).size(), last.points);
  EXPECT_TRUE(std::filesystem::exists(last.pcd_path));
  EXPECT_EQ(mapper.Stats().keyframes, 2u);
}

TEST(DenseMapper, RemovedKeyFramesFollowTheirParent) {
  const CameraOptions camera = SmallCamera();
  const std::shared_ptr<KeyFrame> parent = MakeKeyFrame(camera, SE3(), 0);
  const SE3 offset(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.2, 0, 0));
  const std::shared_ptr<KeyFrame> child = MakeKeyFrame(camera, offset, 1);
  child->SetParent(parent);
  EXPECT_NEAR((CurrentKeyFramePose(*child).Translation() - offset.Translation()).norm(), 0, 1e-9);
  child->SetBad();
  const SE3 moved(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 1, 0));
  parent->SetPose(moved.Inverse());
  EXPECT_NEAR((CurrentKeyFramePose(*child).Translation() - Eigen::Vector3d(0.2, 1.0, 0)).norm(), 0,
              1e-9);
}

TEST(DenseMapper, CulledKeyFramesAreReleasedAndTheirPointsFollowTheParent) {
  const CameraOptions camera = SmallCamera();
  DenseMapOptions options;
  options.min_views = 1;
  options.min_view_span = 0.0;  // two keyframes, no time between them
  options.enhancement_frames = 0;
  DenseMapper mapper(camera, options, true);
  const std::shared_ptr<KeyFrame> parent = MakeKeyFrame(camera, SE3(), 0);
  const SE3 offset(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, -0.5));
  std::shared_ptr<KeyFrame> child = MakeKeyFrame(camera, offset, 1);
  child->SetParent(parent);
  mapper.AddKeyFrame(PlaneFrame(camera, 2.0f, offset, 1), child);
  const std::weak_ptr<KeyFrame> watched = child;
  // Local mapping culls the child: the map no longer holds it.
  child->SetBad();
  child.reset();
  // The next keyframe hands the culled one's anchor to its parent...
  mapper.AddKeyFrame(PlaneFrame(camera, 2.0f, SE3(), 2), parent);
  EXPECT_TRUE(watched.expired()) << "the dense map still holds a culled keyframe";
  // ...and its points still follow the parent's corrections: everything moves 0.5 m along z.
  const DenseCloud before = mapper.Assemble();
  ASSERT_FALSE(before.empty());
  parent->SetPose(SE3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 0.5)).Inverse());
  const DenseCloud after = mapper.Assemble();
  ASSERT_EQ(after.size(), before.size());
  for (std::size_t i = 0; i < after.size(); ++i) {
    EXPECT_NEAR(after[i].position.z() - before[i].position.z(), 0.5f, 1e-4);
  }
}

}  // namespace
}  // namespace drvslam
