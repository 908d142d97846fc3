#include "drvslam/dense/dense_stats_json.h"

namespace drvslam {

nlohmann::json DenseStatsJson(const DenseMapStats& s) {
  const double megabyte = 1024.0 * 1024.0;
  nlohmann::json json;
  json["frames"] = s.frames;
  json["keyframes"] = s.keyframes;
  json["keyframes_dropped"] = s.keyframes_dropped;
  json["enhancement_frames"] = s.enhancement_frames;
  json["points"] = s.points;
  json["background_points"] = s.background_points;
  json["object_points"] = s.object_points;
  json["exported_points"] = s.exported_points;
  json["megabytes"] = s.exported_points * kPlyBytesPerPoint / megabyte;
  json["memory_megabytes"] = s.memory_megabytes;
  json["full_resolution_points"] = s.full_resolution_points;
  json["full_resolution_megabytes"] = s.full_resolution_points * kPlyBytesPerPoint / megabyte;
  // Undefined (null) before any keyframe was integrated: there is nothing to reduce.
  json["reduction_vs_full_resolution"] =
      s.full_resolution_points > 0
          ? nlohmann::json(1.0 - static_cast<double>(s.exported_points) / s.full_resolution_points)
          : nlohmann::json(nullptr);
  json["reduction_baseline"] = kDenseReductionBaseline;
  json["resets"] = s.resets;
  json["carving_votes"] = s.carving_votes;
  json["keyframe_ms"] = {{"median", s.keyframe_ms.median_ms},
                         {"p95", s.keyframe_ms.p95_ms},
                         {"mean", s.keyframe_ms.mean_ms},
                         {"max", s.keyframe_ms.max_ms},
                         {"count", s.keyframe_ms.count}};
  return json;
}

}  // namespace drvslam
