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

const OptionTable<LocalMappingOptions>& LocalMappingOptionTable() {
  static const OptionTable<LocalMappingOptions> table = [] {
    using M = LocalMappingOptions;
    OptionTable<M> t("LocalMapping", "the local mapping thread (defaults: ORB-SLAM2 RGB-D)");
    t.Bool("enabled", &M::enabled,
           "0: keyframes get only their bookkeeping, on the tracking thread (a baseline).")
        .Int("triangulationNeighbours", &M::triangulation_neighbours, Bounds::AtLeast(1),
             "Covisible keyframes searched for new points.")
        .Int("fusionNeighbours", &M::fusion_neighbours, Bounds::AtLeast(1),
             "Covisible keyframes searched for duplicate points.")
        .Real("minFoundRatio", &M::min_found_ratio, Bounds::In(0, 1),
              "Recent points found in fewer than this share of the frames that should see them "
              "are culled.")
        .Int("minPointObservations", &M::min_point_observations, Bounds::AtLeast(1),
             "Recent points seen by fewer keyframes two keyframes after creation are culled.")
        .Bool("bundleAdjustment", &M::bundle_adjustment, "Local bundle adjustment per keyframe.")
        .Int("baMaxLocalKeyFrames", &M::ba_max_local_keyframes,
             Bounds::AtLeast(0).Note("0 = all covisibles"),
             "Keyframes local BA moves at most: the new one and its strongest covisibles.")
        .Int("baFirstPassIterations", &M::ba_first_pass_iterations, Bounds::AtLeast(1),
             "Local BA iterations before outliers are dropped.")
        .Int("baSecondPassIterations", &M::ba_second_pass_iterations, Bounds::AtLeast(0),
             "Local BA iterations after outliers are dropped.")
        .Bool("keyFrameCulling", &M::keyframe_culling, "Cull redundant keyframes.")
        .Real("redundantRatio", &M::redundant_ratio, Bounds::AboveUpTo(0, 1),
              "A keyframe is redundant when this share of its close points is seen by "
              "redundantObservers others.")
        .Int("redundantObservers", &M::redundant_observers, Bounds::AtLeast(1),
             "Other keyframes (same or finer scale) that make a point redundant.")
        .Int("queueCapacity", &M::queue_capacity, Bounds::AtLeast(1),
             "Keyframes waiting for local mapping before tracking blocks.");
    return t;
  }();
  return table;
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
