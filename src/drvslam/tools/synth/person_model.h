// PersonModel: a person made of ten textured boxes (torso, head, upper and lower arms and legs)
// posed by a handful of joint angles, so that walking, sitting down and gesturing move the
// right parts. About 0.6 x 0.3 x 1.75 m, as the people of the TUM dynamic sequences.
#pragma once

#include <Eigen/Core>
#include <array>

#include "drvslam/core/se3.h"
#include "drvslam/tools/synth/scene.h"

namespace drvslam::synth {

// Joint angles in radians; index 0 is the left side, 1 the right.
struct PersonPose {
  double sit = 0.0;                       // 0 standing .. 1 seated
  std::array<double, 2> leg_swing{0, 0};  // thigh forward
  std::array<double, 2> knee{0, 0};       // knee bend (>= 0)
  std::array<double, 2> arm_swing{0, 0};  // upper arm forward
  std::array<double, 2> arm_raise{0, 0};  // upper arm sideways (>= 0)
  std::array<double, 2> elbow{0, 0};      // forearm forward (>= 0)
  double torso_lean = 0.0;                // forward
  double torso_twist = 0.0;               // about the vertical, left positive
  double head_yaw = 0.0;                  // left positive
  double head_pitch = 0.0;                // down positive
};

// Body parts in the order PersonBody::textures lists them.
enum class BodyPart { kTorso, kHead, kUpperArm, kForearm, kThigh, kShin };
inline constexpr int kBodyPartCount = 6;

struct PersonBody {
  double height = 1.75;
  double seat_height = 0.46;  // hips rest this high (plus half a thigh) when seated
  std::array<int, kBodyPartCount> textures{0, 0, 0, 0, 0, 0};

  // Box size of a part (x across, y front-to-back, z along the limb).
  Eigen::Vector3d PartSize(BodyPart part) const;
};

// Appends the posed body: T_world_person places the person's frame (origin on the floor
// between the feet, x to the person's right, y forward, z up) in the world.
void AppendPerson(const PersonBody& body, const PersonPose& pose, const SE3& T_world_person,
                  int instance_id, TriangleList* out);

}  // namespace drvslam::synth
