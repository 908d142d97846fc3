#include "drvslam/semantic/latency_stats.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace drvslam {

Spread SpreadOf(std::vector<double> values) {
  Spread spread;
  if (values.empty()) return spread;
  std::sort(values.begin(), values.end());
  const auto at = [&](double fraction) {
    // Linear interpolation between closest ranks.
    const double position = fraction * static_cast<double>(values.size() - 1);
    const std::size_t low = static_cast<std::size_t>(std::floor(position));
    const std::size_t high = std::min(low + 1, values.size() - 1);
    return values[low] + (position - static_cast<double>(low)) * (values[high] - values[low]);
  };
  spread.median = at(0.5);
  spread.p95 = at(0.95);
  spread.max = values.back();
  spread.mean = std::accumulate(values.begin(), values.end(), 0.0) / values.size();
  return spread;
}

Spread SpreadOf(const BoundedSample& sample) {
  if (sample.Exact()) return SpreadOf(sample.Values());
  Spread spread;
  spread.median = sample.NearestRank(0.5);
  spread.p95 = sample.NearestRank(0.95);
  spread.max = sample.Max();
  spread.mean = sample.Mean();
  return spread;
}

void LatencyRecorder::AddFresh() {
  ++counts_.frames;
  ++counts_.fresh;
  lag_frames_.Add(0.0);
  lag_ms_.Add(0.0);
}

void LatencyRecorder::AddPropagated(std::size_t lag_frames, double lag_ms, double propagation_ms) {
  ++counts_.frames;
  ++counts_.propagated;
  lag_frames_.Add(static_cast<double>(lag_frames));
  lag_ms_.Add(lag_ms);
  propagation_ms_.Add(propagation_ms);
}

void LatencyRecorder::AddWithoutMasks() {
  ++counts_.frames;
  ++counts_.without_masks;
}

SegmentationLatencyStats LatencyRecorder::Summary() const {
  SegmentationLatencyStats stats = counts_;
  stats.lag_frames = SpreadOf(lag_frames_);
  stats.lag_ms = SpreadOf(lag_ms_);
  stats.propagation_ms = SpreadOf(propagation_ms_);
  return stats;
}

}  // namespace drvslam
