#include "drvslam/dynamic/dynamic_stats_json.h"

#include "drvslam/semantic/segmentation_stats_json.h"

namespace drvslam {

nlohmann::json DynamicStatsJson(const DynamicStats& s) {
  const double per_frame = s.frames > 0 ? static_cast<double>(s.features_removed) / s.frames : 0.0;
  return {{"segmenter", s.segmenter},
          {"realtime", s.realtime},
          {"frames", s.frames},
          {"frames_with_model", s.frames_with_model},
          {"frames_homography", s.frames_homography},
          {"frames_large_share", s.frames_large_share},
          {"frames_boosted", s.frames_boosted},
          {"features",
           {{"extracted", s.features_extracted},
            {"removed", s.features_removed},
            {"removed_on_objects", s.removed_on_objects},
            {"removed_unlabelled", s.removed_unlabelled},
            {"removed_per_frame", per_frame},
            {"kept_back", s.features_kept_back}}},
          {"frames_floor", s.frames_floor},
          {"frames_blurred", s.frames_blurred},
          {"unlabelled",
           {{"regions", s.unlabelled_regions},
            {"regions_pending", s.unlabelled_regions_pending},
            {"regions_carried", s.unlabelled_regions_carried},
            {"frames_threshold_raised", s.frames_threshold_raised},
            {"frames_suppressed",
             {{"blur", s.unlabelled_suppressed_blur},
              {"misfit", s.unlabelled_suppressed_misfit},
              {"camera", s.unlabelled_suppressed_camera}}}}},
          {"objects",
           {{"ids", s.ids_issued},
            {"sightings", s.object_frames},
            {"moving_sightings", s.moving_object_frames}}},
          {"skip_moving_extraction",
           {{"frames", s.frames_skip_mask}, {"mean_image_share", s.skip_share_mean}}},
          {"keyframe_masks",
           {{"keyframes", s.keyframes},
            {"expected", s.keyframes_expected},
            {"own_masks", s.keyframes_own_masks},
            {"waits", s.keyframe_waits},
            {"waits_fresh", s.keyframe_waits_fresh},
            {"map_starts", s.map_starts},
            {"map_starts_own_masks", s.map_starts_own_masks},
            {"late_masks", s.keyframes_late_masks},
            {"late_masks_missed", s.keyframes_late_missed},
            {"late_points_culled", s.late_points_culled},
            {"frames_masks_expired", s.frames_masks_expired},
            {"frames_crowd_carried", s.frames_crowd_carried}}},
          {"unlabelled_regions", s.unlabelled_regions},
          {"map_points_culled", s.map_points_culled},
          {"mask_pixels_completed", s.mask_pixels_completed}};
}

nlohmann::json DynamicSegmentationJson(const DynamicStats& stats) {
  if (!stats.segmentation) return nullptr;
  nlohmann::json json = SegmentationStatsJson(stats.segmenter, *stats.segmentation,
                                              stats.latency ? &*stats.latency : nullptr);
  if (stats.pacing) {
    json["backoff"] = {{"backoffs", stats.pacing->backoffs},
                       {"frames_held", stats.pacing->frames_held}};
  }
  return json;
}

}  // namespace drvslam
