// The segmentation thread's numbers as JSON, in the shape `drvslam run` puts under
// "segmentation" in stats.json: per-frame segmentation time, frames dropped, and in realtime
// mode how old the masks used for tracking were.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "drvslam/semantic/async_segmenter.h"
#include "drvslam/semantic/latency_stats.h"

namespace drvslam {

// {"median": .., "p95": .., "max": .., "mean": ..}
nlohmann::json SpreadJson(const Spread& spread);

// {"backend", "submitted", "segmented", "failed", "dropped", "segment_ms": {...}} plus, when
// `latency` is given, "masks": {"frames", "fresh", "propagated", "without_masks", "lag_frames",
// "lag_ms", "propagation_ms"}.
nlohmann::json SegmentationStatsJson(const std::string& backend, const AsyncSegmenterStats& stats,
                                     const SegmentationLatencyStats* latency = nullptr);

}  // namespace drvslam
