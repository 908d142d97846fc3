#include "drvslam/mapping/local_mapping_options.h"

namespace drvslam {

void LocalMappingOptions::Check() const { LocalMappingOptionTable().Check(*this); }

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
  return LocalMappingOptionTable().Load(file);
}

}  // namespace drvslam
