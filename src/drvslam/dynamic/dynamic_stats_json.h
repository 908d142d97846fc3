// The dynamic module's numbers as JSON, in the shape `drvslam run` puts under "dynamic" (and
// "segmentation") in stats.json.
#pragma once

#include <nlohmann/json.hpp>

#include "drvslam/dynamic/dynamic_front_end.h"

namespace drvslam {

// {"segmenter", "realtime", "frames", "frames_with_model", "frames_homography",
//  "frames_large_share", "frames_boosted", "features": {"extracted", "removed",
//  "removed_on_objects", "removed_unlabelled", "removed_per_frame", "kept_back"},
//  "frames_floor", "frames_blurred", "unlabelled": {"regions", "regions_pending",
//  "frames_threshold_raised", "frames_suppressed": {"blur", "misfit", "camera"}}, "objects":
//  {"ids", "sightings", "moving_sightings"}, "unlabelled_regions", "map_points_culled"}
nlohmann::json DynamicStatsJson(const DynamicStats& stats);

// SegmentationStatsJson of the stats' segmentation thread, or null without a segmenter.
nlohmann::json DynamicSegmentationJson(const DynamicStats& stats);

}  // namespace drvslam
