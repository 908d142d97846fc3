// DynamicFrontEnd, what it reports (dynamic_front_end.h): the frame's report fields, the run's
// statistics and the --debug-frames output.
#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "drvslam/core/error.h"
#include "drvslam/dynamic/dynamic_drawing.h"
#include "drvslam/dynamic/dynamic_front_end.h"

namespace drvslam {

void DynamicFrontEnd::RecordStatistics(const MotionRegions& regions,
                                       const std::vector<ObjectEvidence>& objects,
                                       const RemovalOutcome& removal,
                                       std::size_t features_extracted) {
  const DynamicOptions& o = config_.options;
  const MotionConsistencyResult& motion = regions.motion;
  const bool model_ok = motion.model != MotionModel::kNone;
  report_.model = motion.model;
  report_.pose_ok = motion.pose_ok;
  report_.tracks = static_cast<int>(motion.tracks.size());
  report_.moving_points = motion.moving_points;
  report_.share = removal.plan.share;
  report_.large_share = removal.plan.large_share;
  report_.features_extracted = static_cast<int>(features_extracted);
  ++stats_.frames;
  if (model_ok) ++stats_.frames_with_model;
  if (motion.model == MotionModel::kHomography) ++stats_.frames_homography;
  if (removal.plan.large_share) ++stats_.frames_large_share;
  stats_.features_extracted += features_extracted;
  stats_.features_removed += removal.removed.size();
  stats_.removed_on_objects += report_.removed_on_objects;
  stats_.removed_unlabelled += report_.removed_unlabelled;
  stats_.unlabelled_regions += removal.regions.size();
  stats_.map_points_culled += report_.map_points_culled;
  stats_.mask_pixels_completed += report_.completed_pixels;
  if (report_.sharpness.blurred) ++stats_.frames_blurred;
  if (report_.unlabelled_weighed) {
    switch (report_.unlabelled_evidence.verdict) {
      case UnlabelledVerdict::kTrusted:
        break;
      case UnlabelledVerdict::kBlurred:
        ++stats_.unlabelled_suppressed_blur;
        break;
      case UnlabelledVerdict::kMisfit:
        ++stats_.unlabelled_suppressed_misfit;
        break;
      case UnlabelledVerdict::kCameraFailure:
        ++stats_.unlabelled_suppressed_camera;
        break;
    }
    if (report_.unlabelled_evidence.epipolar_threshold > (motion.model == MotionModel::kHomography
                                                              ? o.homography_threshold
                                                              : o.epipolar_threshold) ||
        report_.unlabelled_evidence.reprojection_threshold > o.reprojection_threshold) {
      ++stats_.frames_threshold_raised;
    }
  }
  stats_.unlabelled_regions_pending += report_.unlabelled_pending;
  stats_.unlabelled_regions_carried += report_.unlabelled_carried;
  stats_.features_kept_back += report_.kept_back;
  if (report_.kept_back > 0) ++stats_.frames_floor;
  for (const ObjectEvidence& object : objects) {
    if (!object.potentially_moving) continue;
    ++stats_.object_frames;
    if (object.moving) ++stats_.moving_object_frames;
    moving_class_ids_.insert(object.track_id);
  }
  stats_.ids_issued = moving_class_ids_.size();
}

void DynamicFrontEnd::WriteDebugPicture(const cv::Mat& bgr, const std::vector<cv::KeyPoint>& kept,
                                        const std::vector<cv::KeyPoint>& removed) const {
  const cv::Mat picture =
      DrawDynamicFrame(bgr, report_.instances, report_.objects, report_.unlabelled, kept, removed);
  char name[64];
  std::snprintf(name, sizeof(name), "frame_%06zu.png", report_.frame_index);
  const std::string path = (std::filesystem::path(config_.debug_dir) / name).string();
  if (!cv::imwrite(path, picture)) throw Error(path + ": cannot write the debug picture");
}

void DynamicFrontEnd::WriteObjectRows() {
  for (std::size_t k = 0; k < report_.objects.size(); ++k) {
    const ObjectEvidence& e = report_.objects[k];
    const Instance& instance = report_.instances[k];
    char row[512];
    std::snprintf(row, sizeof(row),
                  "%zu,%.6f,%d,%s,%d,%d,%d,%d,%d,%.4f,%d,%d,%.4f,%d,%d,%.4f,%d,%d,%d,%d,%d,%.4f,%d,"
                  "%s,%d\n",
                  report_.frame_index, report_.timestamp, e.track_id,
                  NormalizeClassName(instance.class_name).c_str(), instance.source_id,
                  e.potentially_moving, e.predecessor, e.ring_features, e.ring_matched, e.delta,
                  e.tracks, e.moving_tracks, e.moving_share, e.reprojected_tracks,
                  e.reprojection_moving_tracks, e.reprojection_share, e.moving_delta_rule,
                  e.moving_share_rule, e.moving_reprojection_rule, e.moving_combined_rule, e.moving,
                  report_.share, report_.large_share, MotionModelName(report_.model),
                  report_.pose_ok);
    objects_csv_ << row;
  }
  objects_csv_.flush();
}

void DynamicFrontEnd::WriteFrameRow() {
  const DynamicFrameReport& r = report_;
  const UnlabelledEvidence& u = r.unlabelled_evidence;
  char row[512];
  std::snprintf(
      row, sizeof(row),
      "%zu,%.6f,%s,%d,%d,%d,%.2f,%.2f,%d,%s,%.4f,%.3f,%.3f,%d,%d,%.4f,%zu,%d,%d,%d,%d,%d\n",
      r.frame_index, r.timestamp, MotionModelName(r.model), r.pose_ok, r.tracks, r.moving_points,
      r.sharpness.sharpness, r.sharpness.reference, r.sharpness.blurred,
      r.unlabelled_weighed ? UnlabelledVerdictName(u.verdict) : "none", u.inlier_share,
      u.epipolar_threshold, u.reprojection_threshold, u.tested, u.moving, u.moving_share,
      r.unlabelled.size(), r.unlabelled_pending, r.features_extracted, r.removed_on_objects,
      r.removed_unlabelled, r.kept_back);
  frames_csv_ << row;
  frames_csv_.flush();
}

DynamicStats DynamicFrontEnd::Stats() const {
  DynamicStats stats = stats_;
  stats.skip_share_mean = stats.frames_skip_mask > 0
                              ? skip_share_sum_ / static_cast<double>(stats.frames_skip_mask)
                              : 0.0;
  if (async_) stats.segmentation = async_->Stats();
  if (masks_) stats.latency = masks_->Latency();
  if (pacer_) stats.pacing = pacer_->Stats();
  return stats;
}

}  // namespace drvslam
