#include "drvslam/core/timing.h"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace drvslam {

double ThreadCpuMs() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return 1e3 * static_cast<double>(now.tv_sec) + 1e-6 * static_cast<double>(now.tv_nsec);
}

void StageTimings::Record(const std::string& stage, double milliseconds) {
  std::lock_guard<std::mutex> lock(mutex_);
  samples_[stage].Add(milliseconds);
  latest_[stage] = milliseconds;
}

std::map<std::string, double> StageTimings::Latest() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return latest_;
}

std::map<std::string, TimingSummary> StageTimings::Summaries() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::map<std::string, TimingSummary> summaries;
  for (const auto& [stage, samples] : samples_) summaries[stage] = Summarize(samples);
  return summaries;
}

TimingSummary Summarize(std::vector<double> samples_ms) {
  TimingSummary summary;
  summary.count = samples_ms.size();
  if (samples_ms.empty()) return summary;
  std::sort(samples_ms.begin(), samples_ms.end());
  const auto rank = [&](double p) {
    const std::size_t k = static_cast<std::size_t>(std::ceil(p * samples_ms.size()));
    return samples_ms[std::min(samples_ms.size() - 1, k == 0 ? 0 : k - 1)];
  };
  summary.median_ms = rank(0.5);
  summary.p95_ms = rank(0.95);
  summary.mean_ms = std::accumulate(samples_ms.begin(), samples_ms.end(), 0.0) / samples_ms.size();
  summary.max_ms = samples_ms.back();
  return summary;
}

TimingSummary Summarize(const BoundedSample& sample) {
  if (sample.Exact()) return Summarize(sample.Values());
  TimingSummary summary;
  summary.count = sample.Count();
  summary.median_ms = sample.NearestRank(0.5);
  summary.p95_ms = sample.NearestRank(0.95);
  summary.mean_ms = sample.Mean();
  summary.max_ms = sample.Max();
  return summary;
}

}  // namespace drvslam
