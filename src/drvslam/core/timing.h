// Per-stage timing: each pipeline stage records its milliseconds per frame; the summary gives
// the median and 95th percentile that stats.json and the benchmarks report.
// Thread-safety: guarded by mutex_, so stages on different threads may record. Memory per stage
// is bounded (BoundedSample): exact statistics up to BoundedSample::kExactLimit frames, then
// quantiles within 0.5 % (count, mean and max stay exact).
#pragma once

#include <chrono>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "drvslam/core/bounded_sample.h"

namespace drvslam {

struct TimingSummary {
  std::size_t count = 0;
  double median_ms = 0.0;
  double p95_ms = 0.0;
  double mean_ms = 0.0;
  double max_ms = 0.0;
};

class StageTimings {
 public:
  void Record(const std::string& stage, double milliseconds);
  // Stages in name order.
  std::map<std::string, TimingSummary> Summaries() const;
  // The latest time recorded for each stage (what a live viewer shows per frame).
  std::map<std::string, double> Latest() const;

 private:
  mutable std::mutex mutex_;
  std::map<std::string, BoundedSample> samples_;
  std::map<std::string, double> latest_;
};

// Summary of a sample (nearest-rank percentiles; zeros for an empty sample).
TimingSummary Summarize(std::vector<double> samples_ms);
// The same for a BoundedSample: Summarize(values) while it is exact, else from its histogram.
TimingSummary Summarize(const BoundedSample& sample);

// CPU time the calling thread has used, in milliseconds (CLOCK_THREAD_CPUTIME_ID). Next to a
// Stopwatch's wall time it tells work from waiting: on a busy machine wall time mostly measures
// the wait for a core.
double ThreadCpuMs();

// Milliseconds elapsed since construction.
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double ElapsedMs() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_)
        .count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace drvslam
