#include "drvslam/tools/synth/camera_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "drvslam/core/error.h"
#include "drvslam/io/trajectory_io.h"
#include "test_support/missing_data.h"

namespace drvslam::synth {
namespace {

constexpr double kDegree = M_PI / 180.0;

double AngleBetween(const SE3& a, const SE3& b) { return RotationAngle(a.Inverse() * b); }

// Distance from `point` to the optical axis of a camera pose.
double AxisDistance(const SE3& T_wc, const Eigen::Vector3d& point) {
  const Eigen::Vector3d axis = T_wc.Rotation().col(2);
  const Eigen::Vector3d offset = point - T_wc.Translation();
  return (offset - offset.dot(axis) * axis).norm();
}

TEST(CameraPathTest, CircuitLooksOutwardsAndReturnsToItsStart) {
  const ViewAnchor anchor;
  const CameraPath circuit = CameraPath::Procedural(PathKind::kCircuit, anchor, 4);
  EXPECT_EQ(PathKindName(circuit.Kind()), "circuit");
  const Eigen::Vector2d centre = anchor.target.head<2>();
  double turned = 0.0;
  for (double t = 0.0; t < CameraPath::kCircuitPeriod; t += 0.1) {
    const SE3 pose = circuit.PoseAt(t);
    const Eigen::Vector2d radial = pose.Translation().head<2>() - centre;
    EXPECT_NEAR(radial.norm(), CameraPath::kCircuitRadius, 0.01);
    // The optical axis points away from the table and down.
    const Eigen::Vector3d axis = pose.Rotation().col(2);
    EXPECT_GT(axis.head<2>().normalized().dot(radial.normalized()), 0.99);
    EXPECT_LT(axis.z(), -0.2);
    turned = std::max(turned, AngleBetween(circuit.PoseAt(0.0), pose));
  }
  EXPECT_GT(turned, 170.0 * kDegree);
  const SE3 start = circuit.PoseAt(0.0);
  const SE3 again = circuit.PoseAt(CameraPath::kCircuitPeriod);
  EXPECT_LT((start.Translation() - again.Translation()).norm(), 0.01);
  EXPECT_LT(AngleBetween(start, again), 1.0 * kDegree);
}

TEST(CameraPathTest, ProceduralPathsStayWithinTheirMotion) {
  const ViewAnchor anchor;
  const SE3 home = anchor.Pose();
  const CameraPath xyz = CameraPath::Procedural(PathKind::kXyz, anchor, 4);
  const CameraPath rpy = CameraPath::Procedural(PathKind::kRpy, anchor, 4);
  const CameraPath sphere = CameraPath::Procedural(PathKind::kHalfsphere, anchor, 4);
  const CameraPath still = CameraPath::Procedural(PathKind::kStatic, anchor, 4);
  double xyz_reach = 0, rpy_turn = 0, sphere_turn = 0;
  for (double t = 0.0; t < 30.0; t += 0.1) {
    const SE3 a = xyz.PoseAt(t);
    const Eigen::Vector3d move =
        home.Rotation().transpose() * (a.Translation() - home.Translation());
    EXPECT_LE(std::abs(move.x()), 0.31);
    EXPECT_LE(std::abs(move.y()), 0.21);
    EXPECT_LE(std::abs(move.z()), 0.26);
    EXPECT_LE(AngleBetween(home, a), 3.0 * kDegree);
    xyz_reach = std::max(xyz_reach, move.norm());

    const SE3 b = rpy.PoseAt(t);
    EXPECT_LE((b.Translation() - home.Translation()).norm(), 0.025);
    rpy_turn = std::max(rpy_turn, AngleBetween(home, b));

    const SE3 c = sphere.PoseAt(t);
    EXPECT_NEAR((c.Translation() - anchor.position).norm(), 0.5, 0.01);
    // Behind the anchor's image plane, looking at the target.
    EXPECT_LE(home.Rotation().col(2).dot(c.Translation() - anchor.position), 0.05);
    EXPECT_LE(AxisDistance(c, anchor.target), 0.03);
    sphere_turn = std::max(sphere_turn, AngleBetween(home, c));

    const SE3 d = still.PoseAt(t);
    EXPECT_LE((d.Translation() - home.Translation()).norm(), 0.005);
    EXPECT_LE(AngleBetween(home, d), 0.5 * kDegree);
  }
  EXPECT_GT(xyz_reach, 0.25);
  EXPECT_GT(rpy_turn, 20.0 * kDegree);
  EXPECT_GT(sphere_turn, 5.0 * kDegree);
}

TEST(CameraPathTest, ProceduralPathsDependOnlyOnTheSeed) {
  const ViewAnchor anchor;
  const CameraPath a = CameraPath::Procedural(PathKind::kXyz, anchor, 9);
  const CameraPath b = CameraPath::Procedural(PathKind::kXyz, anchor, 9);
  const CameraPath c = CameraPath::Procedural(PathKind::kXyz, anchor, 10);
  EXPECT_EQ(a.PoseAt(3.3).Translation(), b.PoseAt(3.3).Translation());
  EXPECT_GT((a.PoseAt(3.3).Translation() - c.PoseAt(3.3).Translation()).norm(), 1e-3);
  EXPECT_TRUE(std::isinf(a.Duration()));
}

// A recorded path in a z-up world: circling a point 1.2 m away while looking at it.
Trajectory CirclingRecording(const Eigen::Vector3d& centre) {
  Trajectory recorded;
  for (int i = 0; i <= 200; ++i) {
    const double angle = 0.01 * i;
    const Eigen::Vector3d eye =
        centre + Eigen::Vector3d(1.2 * std::cos(angle), 1.2 * std::sin(angle), 0.7);
    recorded.push_back({100.0 + 0.05 * i, LookAt(eye, centre)});
  }
  return recorded;
}

TEST(CameraPathTest, ReplayKeepsRelativeMotionAndLooksAtTheTable) {
  const Eigen::Vector3d centre(5.0, -3.0, 0.8);
  const Trajectory recorded = CirclingRecording(centre);
  const ViewAnchor anchor;
  const CameraPath path = CameraPath::Replay(recorded, anchor);
  EXPECT_EQ(path.Kind(), PathKind::kReplay);
  EXPECT_DOUBLE_EQ(path.RecordedStart(), 100.0);
  EXPECT_NEAR(path.Duration(), 10.0, 1e-9);
  const SE3 first = path.PoseAt(0.0);
  for (std::size_t i = 0; i < recorded.size(); i += 17) {
    const double t = recorded[i].timestamp - 100.0;
    const SE3 expected = recorded[0].T_wc.Inverse() * recorded[i].T_wc;
    const SE3 actual = first.Inverse() * path.PoseAt(t);
    EXPECT_LT((expected.Translation() - actual.Translation()).norm(), 1e-9);
    EXPECT_LT(AngleBetween(expected, actual), 1e-9);
    // Where every camera looked (the centre) is now the anchor's target (to the gentle pull of
    // the focus estimate's prior); heights kept.
    EXPECT_LT(
        AxisDistance(path.PoseAt(t), Eigen::Vector3d(anchor.target.x(), anchor.target.y(), 0.8)),
        0.01);
    EXPECT_NEAR(path.PoseAt(t).Translation().z(), 1.5, 1e-9);
  }
  // Seen from the anchor's side: the first camera looks along +y like the anchor.
  EXPECT_GT(first.Rotation().col(2).y(), 0.5);
  // Between two recorded poses: slerp and linear interpolation.
  const SE3 a = path.PoseAt(0.05), b = path.PoseAt(0.1), mid = path.PoseAt(0.075);
  EXPECT_LT((mid.Translation() - 0.5 * (a.Translation() + b.Translation())).norm(), 1e-12);
  EXPECT_NEAR(AngleBetween(a, mid), 0.5 * AngleBetween(a, b), 1e-9);
  // Outside the recording the end poses hold.
  EXPECT_LT((path.PoseAt(-1.0).Translation() - first.Translation()).norm(), 1e-12);
  EXPECT_LT((path.PoseAt(99.0).Translation() - path.PoseAt(10.0).Translation()).norm(), 1e-12);
}

TEST(CameraPathTest, ReplayLevelsACameraFrameRecording) {
  // The same circle expressed in its first camera's frame (y down, z forward), as an odometry
  // output would be: the replay must still come out upright.
  const Trajectory world = CirclingRecording({0, 0, 0.8});
  Trajectory camera_frame;
  const SE3 T_0w = world[0].T_wc.Inverse();
  for (const StampedPose& pose : world) camera_frame.push_back({pose.timestamp, T_0w * pose.T_wc});
  const CameraPath path = CameraPath::Replay(camera_frame, ViewAnchor());
  for (double t = 0.0; t <= 10.0; t += 1.0) {
    // Image x stays horizontal: no roll was introduced.
    EXPECT_NEAR(path.PoseAt(t).Rotation().col(0).z(), 0.0, 1e-9);
    EXPECT_LT(path.PoseAt(t).Rotation().col(1).z(), 0.0);  // image down points down
  }
  EXPECT_NEAR(path.PoseAt(0.0).Translation().z(), ViewAnchor().position.z(), 1e-9);
  EXPECT_THROW(CameraPath::Replay(Trajectory(world.begin(), world.begin() + 1), ViewAnchor()),
               Error);
}

TEST(CameraPathTest, LongTumRecordingStaysInsideTheGrownRoom) {
  const std::string file = std::string(DRVSLAM_SHARED_DIR) +
                           "/tum-groundtruth/rgbd_dataset_freiburg3_long_office_household/"
                           "groundtruth.txt";
  if (!std::filesystem::exists(file)) DRVSLAM_MISSING_TEST_DATA() << "missing " << file;
  const CameraPath path = CameraPath::Replay(ReadTumTrajectory(file), ViewAnchor());
  EXPECT_NEAR(path.Duration(), 87.09, 0.1);
  std::vector<Eigen::Vector3d> centres;
  double lowest = 1e9, looked_at_table = 0;
  int samples = 0;
  for (double t = 0.0; t < path.Duration(); t += 0.5, ++samples) {
    const SE3 pose = path.PoseAt(t);
    centres.push_back(pose.Translation());
    lowest = std::min(lowest, pose.Translation().z());
    // The table (around the origin) is in front of the camera.
    looked_at_table += (pose.Inverse() * Eigen::Vector3d(0, 0, 0.75)).z() > 0.0;
  }
  RoomLayout layout;
  layout.Enclose(centres, 1.0);
  for (const Eigen::Vector3d& c : centres) {
    EXPECT_GT(c.x(), layout.min.x() + 0.99);
    EXPECT_LT(c.y(), layout.max.y() - 0.99);
    EXPECT_LT(c.z(), layout.max.z() - 0.99);
  }
  EXPECT_GE(lowest, 0.3);
  EXPECT_GT(looked_at_table / samples, 0.9);
}

}  // namespace
}  // namespace drvslam::synth
