#include "drvslam/tools/synth/person_model.h"

#include <cmath>

namespace drvslam::synth {
namespace {

// Fractions of the body height, as average adult proportions.
constexpr double kLegFraction = 0.47;
constexpr double kTorsoFraction = 0.36;
constexpr double kNeckFraction = 0.04;
constexpr double kHeadFraction = 0.13;
constexpr double kUpperArmFraction = 0.19;
constexpr double kForearmFraction = 0.22;
constexpr double kHipHalfWidth = 0.1;
constexpr double kShoulderHalfWidth = 0.25;

Eigen::Matrix3d Rx(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).toRotationMatrix();
}
Eigen::Matrix3d Ry(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix();
}
Eigen::Matrix3d Rz(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

}  // namespace

Eigen::Vector3d PersonBody::PartSize(BodyPart part) const {
  const double h = height;
  switch (part) {
    case BodyPart::kTorso:
      return {0.40, 0.24, kTorsoFraction * h};
    case BodyPart::kHead:
      return {0.19, 0.22, kHeadFraction * h};
    case BodyPart::kUpperArm:
      return {0.09, 0.09, kUpperArmFraction * h};
    case BodyPart::kForearm:
      return {0.08, 0.08, kForearmFraction * h};
    case BodyPart::kThigh:
      return {0.15, 0.15, 0.5 * kLegFraction * h};
    case BodyPart::kShin:
      return {0.12, 0.12, 0.5 * kLegFraction * h};
  }
  return {0.1, 0.1, 0.1};
}

void AppendPerson(const PersonBody& body, const PersonPose& pose, const SE3& T_world_person,
                  int instance_id, TriangleList* out) {
  const auto part = [&](BodyPart which, const Eigen::Matrix3d& R, const Eigen::Vector3d& centre) {
    SurfaceTag tag;
    tag.texture = body.textures[static_cast<int>(which)];
    tag.instance_id = instance_id;
    AddBox(T_world_person * SE3(R, centre), body.PartSize(which), tag, out);
  };
  const double h = body.height;
  const double thigh = body.PartSize(BodyPart::kThigh).z();
  const double shin = body.PartSize(BodyPart::kShin).z();
  const double seated_hip = body.seat_height + 0.5 * body.PartSize(BodyPart::kThigh).y();
  const double hip_z = (1.0 - pose.sit) * kLegFraction * h + pose.sit * seated_hip;
  const Eigen::Vector3d down(0, 0, -1), up(0, 0, 1);

  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? -1.0 : 1.0;  // left leg at -x
    const Eigen::Vector3d hip(sign * kHipHalfWidth, 0.0, hip_z);
    const Eigen::Matrix3d thigh_R = Rx(pose.leg_swing[side] + pose.sit * 0.5 * M_PI);
    part(BodyPart::kThigh, thigh_R, hip + thigh_R * down * (0.5 * thigh));
    const Eigen::Vector3d knee = hip + thigh_R * down * thigh;
    const Eigen::Matrix3d shin_R = thigh_R * Rx(-(pose.knee[side] + pose.sit * 0.5 * M_PI));
    part(BodyPart::kShin, shin_R, knee + shin_R * down * (0.5 * shin));
  }

  const Eigen::Vector3d pelvis(0.0, 0.0, hip_z);
  const Eigen::Matrix3d torso_R = Rz(pose.torso_twist) * Rx(-pose.torso_lean);
  const double torso = body.PartSize(BodyPart::kTorso).z();
  part(BodyPart::kTorso, torso_R, pelvis + torso_R * up * (0.5 * torso));
  const Eigen::Vector3d neck = pelvis + torso_R * up * (torso + kNeckFraction * h);
  const Eigen::Matrix3d head_R = torso_R * Rz(pose.head_yaw) * Rx(-pose.head_pitch);
  part(BodyPart::kHead, head_R, neck + head_R * up * (0.5 * body.PartSize(BodyPart::kHead).z()));

  const double upper_arm = body.PartSize(BodyPart::kUpperArm).z();
  const double forearm = body.PartSize(BodyPart::kForearm).z();
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? -1.0 : 1.0;
    const Eigen::Vector3d shoulder =
        pelvis + torso_R * Eigen::Vector3d(sign * kShoulderHalfWidth, 0.0, torso - 0.05);
    // Raising sideways turns the hanging arm towards its own side.
    const Eigen::Matrix3d upper_R =
        torso_R * Rx(pose.arm_swing[side]) * Ry(-sign * pose.arm_raise[side]);
    part(BodyPart::kUpperArm, upper_R, shoulder + upper_R * down * (0.5 * upper_arm));
    const Eigen::Vector3d elbow = shoulder + upper_R * down * upper_arm;
    const Eigen::Matrix3d fore_R = upper_R * Rx(pose.elbow[side]);
    part(BodyPart::kForearm, fore_R, elbow + fore_R * down * (0.5 * forearm));
  }
}

}  // namespace drvslam::synth
