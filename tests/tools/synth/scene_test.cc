#include "drvslam/tools/synth/scene.h"

#include <gtest/gtest.h>

#include <cmath>

#include "drvslam/tools/synth/billboard.h"
#include "drvslam/tools/synth/person_model.h"
#include "drvslam/tools/synth/scene_builder.h"

namespace drvslam::synth {
namespace {

Eigen::Vector3d Normal(const Triangle& t) { return (t.p[1] - t.p[0]).cross(t.p[2] - t.p[0]); }

Eigen::Vector3d Centroid(const Triangle& t) { return (t.p[0] + t.p[1] + t.p[2]) / 3.0; }

TEST(SceneTest, BoxFacesPointOutwardsAndTileTheAtlas) {
  const SE3 pose(Eigen::Matrix3d(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())),
                 Eigen::Vector3d(1, -2, 0.5));
  const Eigen::Vector3d size(0.4, 0.3, 1.2);
  TriangleList triangles;
  AddBox(pose, size, SurfaceTag(), &triangles);
  ASSERT_EQ(triangles.size(), 12u);
  double area = 0.0;
  for (const Triangle& t : triangles) {
    EXPECT_GT(Normal(t).dot(Centroid(t) - pose.Translation()), 0.0);
    area += 0.5 * Normal(t).norm();
  }
  EXPECT_NEAR(area, 2.0 * (0.4 * 0.3 + 0.4 * 1.2 + 0.3 * 1.2), 1e-12);
  // The six faces' atlas rectangles cover the atlas' used area without overlap, and keep the
  // faces' aspect ratios (equal texel density).
  const Eigen::Vector2d atlas = BoxAtlasSize(size);
  double uv_area = 0.0;
  for (int face = 0; face < 6; ++face) {
    const UvRect r = BoxAtlasFace(size, face);
    EXPECT_GE(r.u0, 0.0f);
    EXPECT_LE(r.u1, 1.0f + 1e-6f);
    EXPECT_LE(r.v1, 1.0f + 1e-6f);
    uv_area += (r.u1 - r.u0) * atlas.x() * (r.v1 - r.v0) * atlas.y();
  }
  EXPECT_NEAR(uv_area, 2.0 * (0.4 * 0.3 + 0.4 * 1.2 + 0.3 * 1.2), 1e-6);
}

TEST(SceneTest, CylinderSidesPointOutwards) {
  TriangleList triangles;
  AddCylinder(SE3(), 0.05, 0.2, 16, SurfaceTag(), &triangles);
  EXPECT_EQ(triangles.size(), 16u * 2 + 14u);
  for (const Triangle& t : triangles) {
    const Eigen::Vector3d c = Centroid(t);
    const Eigen::Vector3d n = Normal(t);
    if (c.z() > 0.2 - 1e-9) {
      EXPECT_GT(n.z(), 0.0);  // top cap
    } else {
      EXPECT_GT(n.dot(Eigen::Vector3d(c.x(), c.y(), 0.0)), 0.0);
    }
  }
}

TEST(SceneTest, PersonIsAsTallAsTheBodyAndSitsLower) {
  PersonBody body;
  body.height = 1.78;
  TriangleList standing, seated;
  AppendPerson(body, PersonPose(), SE3(), 4, &standing);
  PersonPose sit;
  sit.sit = 1.0;
  AppendPerson(body, sit, SE3(), 4, &seated);
  ASSERT_EQ(standing.size(), 10u * 12u);
  const auto extent = [](const TriangleList& list, int axis, bool top) {
    double value = top ? -1e9 : 1e9;
    for (const Triangle& t : list) {
      for (const Eigen::Vector3d& p : t.p)
        value = top ? std::max(value, p[axis]) : std::min(value, p[axis]);
    }
    return value;
  };
  EXPECT_NEAR(extent(standing, 2, true), 1.78, 1e-9);
  EXPECT_NEAR(extent(standing, 2, false), 0.0, 1e-9);
  // About 0.6 x 0.3 m across.
  EXPECT_NEAR(extent(standing, 0, true) - extent(standing, 0, false), 0.6, 0.05);
  EXPECT_NEAR(extent(standing, 1, true) - extent(standing, 1, false), 0.24, 0.01);
  // Seated: the head drops by the leg length less the seat height, the knees stick forward.
  EXPECT_LT(extent(seated, 2, true), 1.78 - 0.2);
  EXPECT_GT(extent(seated, 1, true), 0.35);
  for (const Triangle& t : standing) EXPECT_EQ(t.instance_id, 4);
}

TEST(SceneTest, BillboardFacesItsDirection) {
  TriangleList triangles;
  BillboardPlacement placement;
  placement.base = {1.0, 2.0, 0.0};
  placement.facing = {0.0, -1.0};
  AppendBillboard(3, 0.5, 1.7, placement, 6, &triangles);
  ASSERT_EQ(triangles.size(), 2u);
  for (const Triangle& t : triangles) {
    EXPECT_TRUE(t.double_sided);
    EXPECT_EQ(t.texture, 3);
    EXPECT_GT(Normal(t).normalized().dot(Eigen::Vector3d(0, -1, 0)), 0.999);
    for (const Eigen::Vector3d& p : t.p) {
      EXPECT_NEAR(p.y(), 2.0, 1e-12);
      EXPECT_LE(std::abs(p.x() - 1.0), 0.25 + 1e-12);
    }
  }
}

TEST(SceneTest, StaticSceneHasKeyObjectsWithCocoClasses) {
  TextureBank bank(0.25);
  const StaticScene scene = BuildStaticScene(RoomLayout(), 5, &bank);
  std::vector<std::string> classes;
  for (const SynthInstance& instance : scene.instances) {
    EXPECT_GE(instance.id, kFirstObjectInstanceId);
    EXPECT_GE(instance.coco_id, 0);
    classes.push_back(instance.class_name);
  }
  for (const char* expected : {"book", "laptop", "keyboard", "cup", "chair"}) {
    EXPECT_NE(std::find(classes.begin(), classes.end(), expected), classes.end()) << expected;
  }
  // Every triangle of an instance id belongs to a listed instance; all textures exist.
  for (const Triangle& t : scene.triangles) {
    EXPECT_LT(t.texture, bank.Size());
    if (t.instance_id == 0) continue;
    EXPECT_TRUE(std::any_of(scene.instances.begin(), scene.instances.end(),
                            [&](const SynthInstance& i) { return i.id == t.instance_id; }));
  }
  // Same seed, same scene.
  TextureBank again(0.25);
  const StaticScene twin = BuildStaticScene(RoomLayout(), 5, &again);
  ASSERT_EQ(twin.triangles.size(), scene.triangles.size());
  EXPECT_EQ(twin.triangles[500].p[1], scene.triangles[500].p[1]);
}

}  // namespace
}  // namespace drvslam::synth
