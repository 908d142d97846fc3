#include "drvslam/tools/synth/scenario.h"

#include "drvslam/core/error.h"

namespace drvslam::synth {
namespace {

std::vector<Scenario> MakeScenarios() {
  struct Path {
    PathKind kind;
    const char* text;
  };
  const Path paths[] = {
      {PathKind::kXyz, "camera translating along its x, y and z axes"},
      {PathKind::kStatic, "hand-held camera kept still"},
      {PathKind::kRpy, "camera rotating in roll, pitch and yaw"},
      {PathKind::kHalfsphere, "camera sweeping a half-sphere of 1 m diameter"},
      {PathKind::kCircuit,
       "camera circling the table looking outwards, one turn every 12 s, back at its start "
       "(a loop)"},
  };
  std::vector<Scenario> scenarios;
  for (const Path& path : paths) {
    const std::string suffix = "_" + PathKindName(path.kind);
    scenarios.push_back({"walking" + suffix, MotionKind::kWalking, path.kind, 2,
                         std::string("two people walking through the room; ") + path.text});
    scenarios.push_back(
        {"sitting" + suffix, MotionKind::kSitting, path.kind, 2,
         std::string("two people seated at the table, gesturing a little; ") + path.text});
    scenarios.push_back(
        {"pushed" + suffix, MotionKind::kPushed, path.kind, 2,
         std::string("two carts pushed through the room (a mover no COCO class names); ") +
             path.text});
    scenarios.push_back({"static" + suffix, MotionKind::kStatic, path.kind, 0,
                         std::string("the same room without people; ") + path.text});
  }
  return scenarios;
}

}  // namespace

const std::vector<Scenario>& Scenarios() {
  static const std::vector<Scenario> kScenarios = MakeScenarios();
  return kScenarios;
}

std::string ScenarioNames() {
  std::string names;
  for (const Scenario& scenario : Scenarios()) {
    if (!names.empty()) names += ", ";
    names += scenario.name;
  }
  return names;
}

const Scenario& FindScenario(const std::string& name) {
  for (const Scenario& scenario : Scenarios()) {
    if (scenario.name == name) return scenario;
  }
  throw Error("unknown scenario '" + name + "' (known: " + ScenarioNames() + ")");
}

std::string StaticCounterpart(const Scenario& scenario) {
  return "static_" + PathKindName(scenario.path);
}

}  // namespace drvslam::synth
