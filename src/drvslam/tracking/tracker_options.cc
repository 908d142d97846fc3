#include "drvslam/tracking/tracker_options.h"

#include <string>

#include "drvslam/core/error.h"
#include "drvslam/core/option_check.h"

namespace drvslam {

void TrackerOptions::Check() const {
  RequireOption(min_initial_points >= 10, "Tracking.minInitialPoints", min_initial_points,
                "must be at least 10");
  RequireOption(max_frames_between_keyframes >= 0, "Tracking.maxFramesBetweenKeyframes",
                max_frames_between_keyframes, "must be >= 0");
  RequireOption(new_points_per_keyframe >= 0, "Tracking.newPointsPerKeyframe",
                new_points_per_keyframe, "must be >= 0");
  RequireOption(min_inliers >= 6, "Tracking.minInliers", min_inliers, "must be at least 6");
}

const OptionTable<TrackerOptions>& TrackerOptionTable() {
  static const OptionTable<TrackerOptions> table = [] {
    using T = TrackerOptions;
    OptionTable<T> t("Tracking", "the tracking thread");
    t.Int("minInitialPoints", &T::min_initial_points, Bounds::AtLeast(10),
          "Features with valid depth the first frame needs to build the initial map.")
        .Int("maxFramesBetweenKeyframes", &T::max_frames_between_keyframes,
             Bounds::AtLeast(0).Note("0 = Camera.fps"),
             "A keyframe is due at the latest after this many frames.")
        .Int("newPointsPerKeyframe", &T::new_points_per_keyframe, Bounds::AtLeast(0),
             "Map points created from close depth per keyframe when few are tracked.")
        .Int("minInliers", &T::min_inliers, Bounds::AtLeast(6),
             "Inliers after local-map tracking for a frame to count as tracked.")
        .Bool("resetWhenLost", &T::reset_when_lost,
              "When lost: 1 starts a new map, 0 keeps trying to recover.")
        .Bool("bowReferenceMatching", &T::bow_reference_matching,
              "Match the reference keyframe by bag of words (1) or brute force (0).");
    return t;
  }();
  return table;
}

TrackerOptions LoadTrackerOptions(const SettingsFile& file) {
  TrackerOptions o;
  o.min_initial_points = file.GetInt("Tracking.minInitialPoints", o.min_initial_points);
  o.max_frames_between_keyframes =
      file.GetInt("Tracking.maxFramesBetweenKeyframes", o.max_frames_between_keyframes);
  o.new_points_per_keyframe =
      file.GetInt("Tracking.newPointsPerKeyframe", o.new_points_per_keyframe);
  o.min_inliers = file.GetInt("Tracking.minInliers", o.min_inliers);
  o.reset_when_lost = file.GetBool("Tracking.resetWhenLost", o.reset_when_lost);
  o.bow_reference_matching =
      file.GetBool("Tracking.bowReferenceMatching", o.bow_reference_matching);
  return CheckedOptions(file.Path(), o);
}

}  // namespace drvslam
