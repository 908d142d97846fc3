// AsyncSegmenter: the segmentation thread. Submit() hands it a frame as soon as the frame
// arrives, so the network runs while the caller extracts ORB features; Wait() then collects
// that frame's masks. In sequential mode Submit() segments inline, so runs are deterministic.
// With drop_when_busy (sensor-rate tracking) the worker's input is a one-frame slot: Submit never
// blocks, a newer frame replaces one still waiting (counted as dropped), so whenever the network
// becomes free it takes the newest frame, unless the waiting one is kept (Keep: a keyframe's
// image), and then the newer frames are dropped instead; Latest() gives the newest finished
// masks and WaitFor() a frame's own masks within a bounded time, neither blocking longer.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <optional>
#include <thread>
#include <vector>

#include "drvslam/core/bounded_queue.h"
#include "drvslam/semantic/latency_stats.h"
#include "drvslam/semantic/segmenter.h"

namespace drvslam {

// One finished segmentation with the image it was computed on (needed to carry its masks to
// later frames by optical flow).
struct SegmentedFrame {
  Segmentation segmentation;
  cv::Mat image;
  double segment_ms = 0.0;  // wall time of Segmenter::Segment
};

struct AsyncSegmenterOptions {
  bool sequential = false;         // segment inside Submit() on the caller's thread
  std::size_t queue_capacity = 2;  // frames waiting for the worker (1 with drop_when_busy)
  bool drop_when_busy = false;     // a newer frame replaces a waiting one instead of blocking
  std::size_t keep_results = 8;    // results (segmented or failed frames) kept for Wait()/TryGet()
};

struct AsyncSegmenterStats {
  std::size_t submitted = 0;
  std::size_t segmented = 0;
  std::size_t failed = 0;   // Segment threw; Wait() rethrows
  std::size_t dropped = 0;  // skipped because the worker was busy (drop_when_busy)
  Spread segment_ms;
};

class AsyncSegmenter {
 public:
  // Throws drvslam::Error when `segmenter` is null.
  explicit AsyncSegmenter(std::shared_ptr<Segmenter> segmenter,
                          const AsyncSegmenterOptions& options = {});
  // Frames still queued are dropped; the one being segmented is finished first.
  ~AsyncSegmenter();
  AsyncSegmenter(const AsyncSegmenter&) = delete;
  AsyncSegmenter& operator=(const AsyncSegmenter&) = delete;

  // Starts segmenting a copy of `bgr`. Frame indices must increase; throws drvslam::Error
  // otherwise. May block while the queue is full (unless drop_when_busy). Call from one thread
  // (the tracking thread); Wait/TryGet/Latest/Stats may be called from any.
  void Submit(std::size_t frame_index, double timestamp, const cv::Mat& bgr);
  // Blocks until frame `frame_index` is segmented and returns it; rethrows the segmenter's
  // exception for that frame; throws drvslam::Error when the frame was never submitted, was
  // dropped, or its result is no longer kept.
  std::shared_ptr<const SegmentedFrame> Wait(std::size_t frame_index);
  // Waits at most `timeout_ms` for frame `frame_index`; its result when it finished in time,
  // else nullptr (also when it failed, was dropped or is unknown: never throws).
  std::shared_ptr<const SegmentedFrame> WaitFor(std::size_t frame_index, double timeout_ms);
  // How long until that frame's masks are expected, from the network's recent forward-pass
  // times: 0 when finished, the rest of the typical pass when it is being segmented, a whole
  // pass when it waits while the network is idle (the worker is about to take it); nullopt when
  // another frame is ahead of it or it is unknown, dropped or failed. Never blocks.
  std::optional<double> ExpectedWaitMs(std::size_t frame_index) const;
  // That frame's result when it is finished, else nullptr; never blocks.
  std::shared_ptr<const SegmentedFrame> TryGet(std::size_t frame_index) const;
  // With drop_when_busy: a frame still waiting for the network is not replaced by newer ones
  // (they are dropped instead until the network takes it). For frames whose masks are wanted
  // even late (a keyframe's). No effect on a frame already taken, finished or unknown.
  void Keep(std::size_t frame_index);
  // Whether the frame waits for the network or is being segmented: its result may still come.
  bool Pending(std::size_t frame_index) const;
  // The finished frame with the highest index, or nullptr; never blocks.
  std::shared_ptr<const SegmentedFrame> Latest() const;

  // The network's recent forward-pass time (an exponential average); nullopt before the first
  // pass finishes. Never blocks for longer than reading it.
  std::optional<double> TypicalPassMs() const;

  AsyncSegmenterStats Stats() const;
  const Segmenter& Backend() const { return *segmenter_; }

 private:
  enum class State { kQueued, kRunning, kDone, kFailed, kDropped };
  struct Slot {
    State state = State::kQueued;
    std::chrono::steady_clock::time_point started;  // when the network took it
    std::shared_ptr<const SegmentedFrame> result;
    std::exception_ptr error;
    bool kept = false;  // Keep(): newer frames do not replace it while it waits
    // Waiting for the network or being segmented: its result may still come.
    bool Unfinished() const { return state == State::kQueued || state == State::kRunning; }
  };
  struct Job {
    std::size_t frame_index;
    double timestamp;
    cv::Mat image;
  };

  void WorkerLoop();
  // Segments one job and records the outcome in its slot.
  void Run(const Job& job);
  // Dropped frames remembered at most (TrimLocked).
  static constexpr std::size_t kDroppedKept = 64;

  // Forgets results beyond keep_results and dropped frames beyond kDroppedKept, with every
  // finished slot older than those. Requires mutex_.
  void TrimLocked();
  // Whether a kept frame waits in the queue. Requires mutex_.
  bool KeptFrameWaitsLocked() const;

  std::shared_ptr<Segmenter> segmenter_;
  AsyncSegmenterOptions options_;
  BoundedQueue<Job> queue_;

  // mutex_ guards slots_, latest_, stats_, segment_ms_, stopping_ and has_submitted_/last_index_.
  mutable std::mutex mutex_;
  std::condition_variable finished_;
  std::map<std::size_t, Slot> slots_;
  std::shared_ptr<const SegmentedFrame> latest_;
  AsyncSegmenterStats stats_;
  BoundedSample segment_ms_;  // bounded memory over long runs
  // Recent forward-pass time: an exponential average, for ExpectedWaitMs.
  std::optional<double> typical_segment_ms_;
  bool stopping_ = false;
  bool has_submitted_ = false;
  std::size_t last_index_ = 0;

  std::thread worker_;
};

}  // namespace drvslam
