#include "drvslam/mapping/local_mapping_options.h"

#include <cmath>
#include <sstream>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/core/option_check.h"

namespace drvslam {
namespace {

template <typename T>
void Require(bool ok, const std::string& key, T value, const std::string& rule) {
  if (ok) return;
  std::ostringstream message;
  message << key << " = " << value << " " << rule;
  throw Error(message.str());
}

}  // namespace

void LocalMappingOptions::Check() const {
  Require(triangulation_neighbours >= 1, "LocalMapping.triangulationNeighbours",
          triangulation_neighbours, "must be at least 1");
  Require(fusion_neighbours >= 1, "LocalMapping.fusionNeighbours", fusion_neighbours,
          "must be at least 1");
  Require(std::isfinite(min_found_ratio) && min_found_ratio >= 0.0 && min_found_ratio <= 1.0,
          "LocalMapping.minFoundRatio", min_found_ratio, "must be in [0, 1]");
  Require(min_point_observations >= 1, "LocalMapping.minPointObservations", min_point_observations,
          "must be at least 1");
  Require(ba_max_local_keyframes >= 0, "LocalMapping.baMaxLocalKeyFrames", ba_max_local_keyframes,
          "must be >= 0");
  Require(ba_first_pass_iterations >= 1, "LocalMapping.baFirstPassIterations",
          ba_first_pass_iterations, "must be at least 1");
  Require(ba_second_pass_iterations >= 0, "LocalMapping.baSecondPassIterations",
          ba_second_pass_iterations, "must be >= 0");
  Require(std::isfinite(redundant_ratio) && redundant_ratio > 0.0 && redundant_ratio <= 1.0,
          "LocalMapping.redundantRatio", redundant_ratio, "must be in (0, 1]");
  Require(redundant_observers >= 1, "LocalMapping.redundantObservers", redundant_observers,
          "must be at least 1");
  Require(queue_capacity >= 1, "LocalMapping.queueCapacity", queue_capacity, "must be at least 1");
}

LocalMappingOptions LoadLocalMappingOptions(const SettingsFile& file) {
  LocalMappingOptions o;
  o.enabled = file.GetBool("LocalMapping.enabled", o.enabled);
  o.triangulation_neighbours =
      file.GetInt("LocalMapping.triangulationNeighbours", o.triangulation_neighbours);
  o.fusion_neighbours = file.GetInt("LocalMapping.fusionNeighbours", o.fusion_neighbours);
  o.min_found_ratio = file.GetDouble("LocalMapping.minFoundRatio", o.min_found_ratio);
  o.min_point_observations =
      file.GetInt("LocalMapping.minPointObservations", o.min_point_observations);
  o.bundle_adjustment = file.GetBool("LocalMapping.bundleAdjustment", o.bundle_adjustment);
  o.ba_max_local_keyframes =
      file.GetInt("LocalMapping.baMaxLocalKeyFrames", o.ba_max_local_keyframes);
  o.ba_first_pass_iterations =
      file.GetInt("LocalMapping.baFirstPassIterations", o.ba_first_pass_iterations);
  o.ba_second_pass_iterations =
      file.GetInt("LocalMapping.baSecondPassIterations", o.ba_second_pass_iterations);
  o.keyframe_culling = file.GetBool("LocalMapping.keyFrameCulling", o.keyframe_culling);
  o.redundant_ratio = file.GetDouble("LocalMapping.redundantRatio", o.redundant_ratio);
  o.redundant_observers = file.GetInt("LocalMapping.redundantObservers", o.redundant_observers);
  o.queue_capacity = file.GetInt("LocalMapping.queueCapacity", o.queue_capacity);
  return CheckedOptions(file.Path(), o);
}

}  // namespace drvslam
