#include "drvslam/dense/dense_frame.h"

#include <gtest/gtest.h>

#include "dense_test_frames.h"
#include "drvslam/core/error.h"

namespace drvslam {
namespace {

using testing::BoxInstance;
using testing::PlaneFrame;
using testing::SmallCamera;

TEST(BackProject, PlaneLandsAtItsDepthThroughThePinhole) {
  const CameraOptions camera = SmallCamera();
  DenseFrame frame = PlaneFrame(camera, 2.0f);
  frame.depth.at<float>(5, 7) = 1.0f;
  DenseMapOptions options;
  options.flying_pixel_step = 0.0;  // the lone nearer pixel stays
  const PixelRoles roles = PaintRoles(frame, options);
  const DenseCloud cloud = BackProject(frame, roles, PixelRole::kBackground, camera, options);
  ASSERT_EQ(cloud.size(), static_cast<std::size_t>(camera.width * camera.height));
  // Row-major order: pixel (x, y) is point y * width + x.
  const DensePoint& p = cloud[5 * camera.width + 7];
  EXPECT_FLOAT_EQ(p.position.z(), 1.0f);
  EXPECT_NEAR(p.position.x(), (7 - 80.0) * 1.0 / 150.0, 1e-6);
  EXPECT_NEAR(p.position.y(), (5 - 60.0) * 1.0 / 150.0, 1e-6);
  const DensePoint& q = cloud[100 * camera.width + 150];
  EXPECT_FLOAT_EQ(q.position.z(), 2.0f);
  EXPECT_NEAR(q.position.x(), (150 - 80.0) * 2.0 / 150.0, 1e-6);
  EXPECT_NEAR(q.position.y(), (100 - 60.0) * 2.0 / 150.0, 1e-6);
  EXPECT_EQ(q.r, 30);
  EXPECT_EQ(q.g, 20);
  EXPECT_EQ(q.b, 10);
  EXPECT_EQ(q.label, -1);
}

TEST(BackProject, DepthOutsideTheRangeIsLeftOut) {
  const CameraOptions camera = SmallCamera();
  DenseFrame frame = PlaneFrame(camera, 2.0f);
  frame.depth(cv::Rect(0, 0, 10, 10)).setTo(0.0f);   // no depth
  frame.depth(cv::Rect(10, 0, 10, 10)).setTo(9.0f);  // beyond max_depth
  frame.depth(cv::Rect(20, 0, 10, 10)).setTo(0.1f);  // nearer than min_depth
  frame.depth.at<float>(50, 50) = std::numeric_limits<float>::quiet_NaN();
  DenseMapOptions options;
  options.flying_pixel_step = 0.0;  // the depth steps are not what this test is about
  const PixelRoles roles = PaintRoles(frame, options);
  const DenseCloud cloud = BackProject(frame, roles, PixelRole::kBackground, camera, options);
  EXPECT_EQ(cloud.size(), static_cast<std::size_t>(camera.width * camera.height - 301));
  EXPECT_EQ(CountMappedPixels(frame, roles, options), cloud.size());
  for (const DensePoint& p : cloud) EXPECT_FLOAT_EQ(p.position.z(), 2.0f);
}

TEST(PaintRoles, MovingObjectsAreExcludedWithGrownMasks) {
  const CameraOptions camera = SmallCamera();
  DenseFrame frame = PlaneFrame(camera, 2.0f);
  DenseInstance person = BoxInstance(camera, cv::Rect(40, 30, 20, 20), 0);
  person.potentially_moving = true;
  person.moving = true;
  person.track_id = 3;
  frame.instances.push_back(person);
  DenseMapOptions options;
  options.mask_dilation = 2;
  options.mask_growth = 0;  // the fixed dilation alone
  const PixelRoles roles = PaintRoles(frame, options);
  const DenseCloud cloud = BackProject(frame, roles, PixelRole::kBackground, camera, options);
  // The 20 x 20 box grown by 2 px (elliptic corners): between 24^2 minus the corners and 24^2.
  const std::size_t removed = camera.width * camera.height - cloud.size();
  EXPECT_GT(removed, 20u * 20u + 4 * 2 * 20u);
  EXPECT_LE(removed, 24u * 24u);
  for (const DensePoint& p : cloud) EXPECT_NE(p.label, 0);
  EXPECT_EQ(roles.role.at<uint8_t>(40, 50), static_cast<uint8_t>(PixelRole::kExcluded));

  options.remove_dynamic = false;  // removal off: everything stays, labelled
  const PixelRoles kept_roles = PaintRoles(frame, options);
  const DenseCloud all = BackProject(frame, kept_roles, PixelRole::kBackground, camera, options);
  EXPECT_EQ(all.size(), static_cast<std::size_t>(camera.width * camera.height));
}

TEST(PaintRoles, StillPeopleStayUnlessAllPotentiallyMovingGo) {
  const CameraOptions camera = SmallCamera();
  DenseFrame frame = PlaneFrame(camera, 2.0f);
  DenseInstance person = BoxInstance(camera, cv::Rect(40, 30, 20, 20), 0);
  person.potentially_moving = true;
  person.track_id = 8;
  frame.instances.push_back(person);
  DenseMapOptions options;
  PixelRoles roles = PaintRoles(frame, options);
  EXPECT_EQ(roles.role.at<uint8_t>(40, 50), static_cast<uint8_t>(PixelRole::kBackground));
  EXPECT_EQ(roles.track.at<int32_t>(40, 50), 8);  // its points remember the object
  EXPECT_EQ(roles.track.at<int32_t>(10, 10), -1);
  options.remove_all_potentially_moving = true;
  roles = PaintRoles(frame, options);
  EXPECT_EQ(roles.role.at<uint8_t>(40, 50), static_cast<uint8_t>(PixelRole::kExcluded));
}

TEST(PaintRoles, KeyObjectsGetTheirRoleAndLabel) {
  const CameraOptions camera = SmallCamera();
  DenseFrame frame = PlaneFrame(camera, 2.0f);
  DenseInstance book = BoxInstance(camera, cv::Rect(100, 70, 30, 10), 73);
  book.key_object = true;
  frame.instances.push_back(book);
  const DenseMapOptions options;
  const PixelRoles roles = PaintRoles(frame, options);
  const DenseCloud objects = BackProject(frame, roles, PixelRole::kKeyObject, camera, options);
  ASSERT_EQ(objects.size(), 300u);
  for (const DensePoint& p : objects) EXPECT_EQ(p.label, 73);
  const DenseCloud background = BackProject(frame, roles, PixelRole::kBackground, camera, options);
  EXPECT_EQ(background.size(), static_cast<std::size_t>(camera.width * camera.height - 300));
}

TEST(PaintRoles, RejectsMasksOfAnotherSize) {
  const CameraOptions camera = SmallCamera();
  DenseFrame frame = PlaneFrame(camera, 2.0f);
  DenseInstance wrong;
  wrong.mask = cv::Mat::zeros(10, 10, CV_8UC1);
  frame.instances.push_back(wrong);
  EXPECT_THROW(PaintRoles(frame, DenseMapOptions()), Error);
  DenseFrame no_depth = PlaneFrame(camera, 2.0f);
  no_depth.depth = cv::Mat();
  EXPECT_THROW(PaintRoles(no_depth, DenseMapOptions()), Error);
}

}  // namespace
}  // namespace drvslam
