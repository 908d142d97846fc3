#include "drvslam/semantic/segmentation_stats_json.h"

namespace drvslam {

nlohmann::json SpreadJson(const Spread& spread) {
  return {
      {"median", spread.median}, {"p95", spread.p95}, {"max", spread.max}, {"mean", spread.mean}};
}

nlohmann::json SegmentationStatsJson(const std::string& backend, const AsyncSegmenterStats& stats,
                                     const SegmentationLatencyStats* latency) {
  nlohmann::json json = {
      {"backend", backend},           {"submitted", stats.submitted},
      {"segmented", stats.segmented}, {"failed", stats.failed},
      {"dropped", stats.dropped},     {"segment_ms", SpreadJson(stats.segment_ms)}};
  if (latency != nullptr) {
    json["masks"] = {{"frames", latency->frames},
                     {"fresh", latency->fresh},
                     {"propagated", latency->propagated},
                     {"without_masks", latency->without_masks},
                     {"lag_frames", SpreadJson(latency->lag_frames)},
                     {"lag_ms", SpreadJson(latency->lag_ms)},
                     {"propagation_ms", SpreadJson(latency->propagation_ms)}};
  }
  return json;
}

}  // namespace drvslam
