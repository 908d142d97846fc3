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
