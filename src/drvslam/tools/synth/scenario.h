// Scenarios: named combinations of what the actors do and how the camera moves, mirroring the
// TUM RGB-D dynamic sequences (fr3/walking_*, fr3/sitting_*), and pushed_*: carts pushed along
// the walkers' lanes, a mover that no COCO class names (only geometry can find it without the
// ground truth's masks). Every dynamic scenario has a
// static_* counterpart with the same camera path and room and no actors, so a result on a
// dynamic scene can be compared with the same path through a static world.
#pragma once

#include <string>
#include <vector>

#include "drvslam/tools/synth/camera_path.h"

namespace drvslam::synth {

enum class MotionKind { kWalking, kSitting, kPushed, kStatic };

// The class of the pushed_* scenarios' movers: no COCO class.
inline constexpr const char* kCartClass = "cart";

struct Scenario {
  std::string name;
  MotionKind motion = MotionKind::kStatic;
  PathKind path = PathKind::kStatic;
  int default_actors = 0;
  std::string description;
  // What the actors are labelled when --actor-class does not say: "person", or kCartClass.
  std::string ActorClass() const { return motion == MotionKind::kPushed ? kCartClass : "person"; }
};

// walking_{xyz,static,rpy,halfsphere,circuit}, sitting_{...}, pushed_{...}, static_{...}.
const std::vector<Scenario>& Scenarios();
// Throws Error listing the valid names when `name` is not one.
const Scenario& FindScenario(const std::string& name);
// The names, comma separated (for help texts and errors).
std::string ScenarioNames();
// The scenario with the same camera path and no actors ("walking_xyz" -> "static_xyz").
std::string StaticCounterpart(const Scenario& scenario);

}  // namespace drvslam::synth
