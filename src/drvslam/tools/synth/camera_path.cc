#include "drvslam/tools/synth/camera_path.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "drvslam/core/enum_names.h"
#include "drvslam/core/error.h"
#include "drvslam/tools/synth/random.h"

namespace drvslam::synth {
namespace {

constexpr double kFullTurn = 2.0 * M_PI;
constexpr double kDegree = M_PI / 180.0;
// Hand shake: a few mm and a few tenths of a degree, 0.7 to 3 Hz.
constexpr double kShakeTranslation = 0.002;
constexpr double kShakeRotation = 0.25 * kDegree;
// Replayed cameras stay at least this high above the floor.
constexpr double kMinCameraHeight = 0.3;
// A z-up recording whose first camera is this high is taken to have its origin on the floor.
constexpr double kMinFloorHeight = 0.5;
constexpr double kMaxFloorHeight = 2.5;
// The cameras' x axes must spread this much (mean squared sine of their turn) before up is
// estimated from them: about 13 degrees.
constexpr double kMinTurnSpread = 0.05;

Eigen::Matrix3d SmallRotation(double rx, double ry, double rz) {
  return (Eigen::AngleAxisd(ry, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rx, Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(rz, Eigen::Vector3d::UnitZ()))
      .toRotationMatrix();
}

// The recorded world's up direction. Hand-held cameras keep their image rows level, so when
// the cameras turned enough, up is the direction all their x axes are most perpendicular to;
// otherwise (a camera that kept its heading) it is the mean image-up. Recordings are usually
// made in a frame with gravity along an axis (TUM: z up), so a result near an axis snaps to it.
Eigen::Vector3d RecordedUp(const Trajectory& recorded) {
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  Eigen::Vector3d mean_up = Eigen::Vector3d::Zero();
  for (const StampedPose& pose : recorded) {
    const Eigen::Matrix3d R = pose.T_wc.Rotation();
    spread += R.col(0) * R.col(0).transpose();
    mean_up -= R.col(1);
  }
  mean_up.normalize();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(spread);
  const Eigen::Vector3d values = solver.eigenvalues();  // ascending
  const double count = static_cast<double>(recorded.size());
  Eigen::Vector3d up = mean_up;
  double snap = std::cos(45.0 * kDegree);
  if (values[1] > kMinTurnSpread * count && values[0] < 0.25 * values[1]) {
    up = solver.eigenvectors().col(0);
    if (up.dot(mean_up) < 0.0) up = -up;
    snap = std::cos(5.0 * kDegree);
  }
  int axis = 0;
  if (up.cwiseAbs().maxCoeff(&axis) >= snap) {
    const double sign = up[axis] >= 0.0 ? 1.0 : -1.0;
    up = Eigen::Vector3d::Zero();
    up[axis] = sign;
  }
  return up;
}

}  // namespace

std::string PathKindName(PathKind kind) {
  static constexpr EnumName<PathKind> kNames[] = {
      {PathKind::kXyz, "xyz"},       {PathKind::kStatic, "static"},
      {PathKind::kRpy, "rpy"},       {PathKind::kHalfsphere, "halfsphere"},
      {PathKind::kReplay, "replay"}, {PathKind::kCircuit, "circuit"}};
  return NameOf(kind, kNames, "unknown");
}

CameraPath CameraPath::Procedural(PathKind kind, const ViewAnchor& anchor, uint64_t seed) {
  if (kind == PathKind::kReplay) throw Error("camera path: a replay needs a recorded trajectory");
  CameraPath path;
  path.kind_ = kind;
  path.anchor_ = anchor;
  path.anchor_pose_ = anchor.Pose();
  Random rng(SubSeed(seed, RandomStream::kCameraPath));
  for (double& phase : path.phase_) phase = rng.Uniform(0.0, kFullTurn);
  for (int axis = 0; axis < 6; ++axis) {
    for (int k = 0; k < 3; ++k) {
      path.shake_frequency_[axis][k] = rng.Uniform(0.7, 3.0);
      path.shake_phase_[axis][k] = rng.Uniform(0.0, kFullTurn);
    }
  }
  return path;
}

CameraPath CameraPath::Replay(const Trajectory& recorded, const ViewAnchor& anchor) {
  if (recorded.size() < 2) throw Error("camera path: a replayed trajectory needs at least 2 poses");
  CameraPath path;
  path.kind_ = PathKind::kReplay;
  path.anchor_ = anchor;
  path.anchor_pose_ = anchor.Pose();
  path.recorded_start_ = recorded.front().timestamp;

  const Eigen::Vector3d up = RecordedUp(recorded);
  const Eigen::Matrix3d level =
      Eigen::Quaterniond::FromTwoVectors(up, Eigen::Vector3d::UnitZ()).toRotationMatrix();

  // Where the cameras look: the least-squares meeting point of the optical axes, pulled
  // gently towards the point the first camera sees at the anchor's viewing distance (which
  // decides it when the axes are nearly parallel).
  const std::size_t stride = std::max<std::size_t>(1, recorded.size() / 2000);
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  int samples = 0;
  for (std::size_t i = 0; i < recorded.size(); i += stride) {
    const Eigen::Vector3d c = level * recorded[i].T_wc.Translation();
    const Eigen::Vector3d d = level * recorded[i].T_wc.Rotation().col(2);
    const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - d * d.transpose();
    A += across;
    b += across * c;
    ++samples;
  }
  const Eigen::Vector3d c0 = level * recorded.front().T_wc.Translation();
  const Eigen::Vector3d d0 = level * recorded.front().T_wc.Rotation().col(2);
  const double view_distance = (anchor.target - anchor.position).norm();
  const double weight = 0.002 * samples;
  A += weight * Eigen::Matrix3d::Identity();
  b += weight * (c0 + view_distance * d0);
  const Eigen::Vector3d focus = A.ldlt().solve(b);

  // Turn about the vertical so the first camera looks at the focus from the anchor's side.
  Eigen::Vector2d seen = (focus - c0).head<2>();
  if (seen.norm() < 0.2) seen = d0.head<2>();
  if (seen.norm() < 1e-6) seen = Eigen::Vector2d(0.0, 1.0);
  const Eigen::Vector2d wanted = (anchor.target - anchor.position).head<2>();
  const double yaw = std::atan2(wanted.y(), wanted.x()) - std::atan2(seen.y(), seen.x());
  const Eigen::Matrix3d yaw_R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d turn = yaw_R * level;
  // focus and c0 are in the levelled frame already.
  const Eigen::Vector3d focus_turned = yaw_R * focus;
  const Eigen::Vector3d c0_turned = yaw_R * c0;
  // Height: a z-up recording (TUM ground truth) has its origin on the floor, so its heights
  // are kept - the real cameras looked at real desks about as high as the synthetic table.
  // Otherwise the first camera is put at the anchor's height.
  const bool floor_origin =
      up.z() > 0.999 && c0_turned.z() > kMinFloorHeight && c0_turned.z() < kMaxFloorHeight;
  const Eigen::Vector3d shift(anchor.target.x() - focus_turned.x(),
                              anchor.target.y() - focus_turned.y(),
                              floor_origin ? 0.0 : anchor.position.z() - c0_turned.z());
  const SE3 placement(turn, shift);
  double lowest = std::numeric_limits<double>::infinity();
  for (const StampedPose& pose : recorded) {
    path.times_.push_back(pose.timestamp - path.recorded_start_);
    path.poses_.push_back(placement * pose.T_wc);
    lowest = std::min(lowest, path.poses_.back().Translation().z());
  }
  if (lowest < kMinCameraHeight) {
    const SE3 lift(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, kMinCameraHeight - lowest));
    for (SE3& pose : path.poses_) pose = lift * pose;
  }
  return path;
}

double CameraPath::Duration() const {
  if (kind_ != PathKind::kReplay) return std::numeric_limits<double>::infinity();
  return times_.back();
}

SE3 CameraPath::PoseAt(double t) const {
  if (kind_ == PathKind::kReplay) {
    if (t <= times_.front()) return poses_.front();
    if (t >= times_.back()) return poses_.back();
    const std::size_t i = static_cast<std::size_t>(
        std::upper_bound(times_.begin(), times_.end(), t) - times_.begin());
    const double alpha = (t - times_[i - 1]) / (times_[i] - times_[i - 1]);
    const Eigen::Quaterniond q = poses_[i - 1].Quaternion().slerp(alpha, poses_[i].Quaternion());
    const Eigen::Vector3d p =
        (1.0 - alpha) * poses_[i - 1].Translation() + alpha * poses_[i].Translation();
    return SE3(q, p);
  }

  // Hand shake in the camera frame: three incommensurate sines per axis.
  double shake[6];
  for (int axis = 0; axis < 6; ++axis) {
    double sum = 0.0;
    for (int k = 0; k < 3; ++k) {
      sum += std::sin(kFullTurn * shake_frequency_[axis][k] * t + shake_phase_[axis][k]);
    }
    shake[axis] = sum / 3.0 * (axis < 3 ? kShakeTranslation : kShakeRotation);
  }
  const SE3 hand(SmallRotation(shake[3], shake[4], shake[5]),
                 Eigen::Vector3d(shake[0], shake[1], shake[2]));
  const double* phase = phase_;
  switch (kind_) {
    case PathKind::kXyz: {
      const Eigen::Vector3d move(0.30 * std::sin(kFullTurn * t / 7.0 + phase[0]),
                                 0.20 * std::sin(kFullTurn * t / 9.3 + phase[1]),
                                 0.25 * std::sin(kFullTurn * t / 11.7 + phase[2]));
      const Eigen::Matrix3d wobble =
          SmallRotation(1.5 * kDegree * std::sin(kFullTurn * t / 5.1 + phase[3]),
                        1.5 * kDegree * std::sin(kFullTurn * t / 6.7 + phase[4]),
                        1.0 * kDegree * std::sin(kFullTurn * t / 8.3 + phase[5]));
      return anchor_pose_ * SE3(wobble, move) * hand;
    }
    case PathKind::kRpy: {
      const Eigen::Matrix3d turn =
          SmallRotation(15.0 * kDegree * std::sin(kFullTurn * t / 6.3 + phase[1]),
                        25.0 * kDegree * std::sin(kFullTurn * t / 8.0 + phase[0]),
                        15.0 * kDegree * std::sin(kFullTurn * t / 5.1 + phase[2]));
      const Eigen::Vector3d sway(0.01 * std::sin(kFullTurn * t / 4.3 + phase[3]),
                                 0.01 * std::sin(kFullTurn * t / 5.9 + phase[4]),
                                 0.01 * std::sin(kFullTurn * t / 3.7 + phase[5]));
      return anchor_pose_ * SE3(turn, sway) * hand;
    }
    case PathKind::kHalfsphere: {
      // Polar angle from the backward axis between 5 and 75 degrees, azimuth turning steadily.
      const double polar = (40.0 + 35.0 * std::sin(kFullTurn * t / 9.7 + phase[0])) * kDegree;
      const double azimuth = kFullTurn * t / 12.0 + phase[1];
      const Eigen::Matrix3d R = anchor_pose_.Rotation();
      const Eigen::Vector3d direction =
          std::cos(polar) * -R.col(2) +
          std::sin(polar) * (std::cos(azimuth) * R.col(0) + std::sin(azimuth) * R.col(1));
      return LookAt(anchor_.position + 0.5 * direction, anchor_.target) * hand;
    }
    case PathKind::kCircuit: {
      // Starts on the side of the standard viewpoint, looking away from the table.
      const Eigen::Vector2d start = (anchor_.position - anchor_.target).head<2>().normalized();
      const double angle = std::atan2(start.y(), start.x()) + kFullTurn * t / kCircuitPeriod;
      const Eigen::Vector3d outwards(std::cos(angle), std::sin(angle), 0.0);
      const Eigen::Vector3d eye(anchor_.target.x() + kCircuitRadius * outwards.x(),
                                anchor_.target.y() + kCircuitRadius * outwards.y(), 1.3);
      const Eigen::Vector3d look = outwards - std::tan(20.0 * kDegree) * Eigen::Vector3d::UnitZ();
      return LookAt(eye, eye + look) * hand;
    }
    default:
      return anchor_pose_ * hand;
  }
}

}  // namespace drvslam::synth
