// Scenarios: named combinations of what the actors do and how the camera moves, mirroring the
// TUM RGB-D dynamic sequences (fr3/walking_*, fr3/sitting_*). Every dynamic scenario has a
// static_* counterpart with the same camera path and room and no actors, so a result on a
// dynamic scene can be compared with the same path through a static world.
#pragma once

#include <string>
#include <vector>

#include "drvslam/tools/synth/camera_path.h"

namespace drvslam::synth {

enum class MotionKind { kWalking, kSitting, kStatic };

struct Scenario {
  std::string name;
  MotionKind motion = MotionKind::kStatic;
  PathKind path = PathKind::kStatic;
  int default_actors = 0;
  std::string description;
};

// walking_{xyz,static,rpy,halfsphere}, sitting_{...}, static_{...}.
const std::vector<Scenario>& Scenarios();
// Throws Error listing the valid names when `name` is not one.
const Scenario& FindScenario(const std::string& name);
// The names, comma separated (for help texts and errors).
std::string ScenarioNames();
// The scenario with the same camera path and no actors ("walking_xyz" -> "static_xyz").
std::string StaticCounterpart(const Scenario& scenario);

}  // namespace drvslam::synth
