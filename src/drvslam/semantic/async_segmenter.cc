#include "drvslam/semantic/async_segmenter.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <optional>
#include <utility>

#include "drvslam/core/error.h"
#include "drvslam/core/thread_budget.h"
#include "drvslam/core/thread_name.h"

namespace drvslam {

AsyncSegmenter::AsyncSegmenter(std::shared_ptr<Segmenter> segmenter,
                               const AsyncSegmenterOptions& options)
    : segmenter_(std::move(segmenter)),
      options_(options),
      // Sensor rate: one waiting frame at most, so the network always starts on the newest.
      queue_(options.drop_when_busy ? 1 : options.queue_capacity) {
  if (!segmenter_) throw Error("AsyncSegmenter: no segmenter given");
  if (options_.keep_results == 0) options_.keep_results = 1;
  if (!options_.sequential) worker_ = std::thread([this] { WorkerLoop(); });
}

AsyncSegmenter::~AsyncSegmenter() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  queue_.Close();
  if (worker_.joinable()) worker_.join();
}

void AsyncSegmenter::Submit(std::size_t frame_index, double timestamp, const cv::Mat& bgr) {
  bool keep_waiting_frame = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (has_submitted_ && frame_index <= last_index_) {
      throw Error("AsyncSegmenter: frame " + std::to_string(frame_index) +
                  " submitted after frame " + std::to_string(last_index_) +
                  "; frame indices must increase");
    }
    has_submitted_ = true;
    last_index_ = frame_index;
    keep_waiting_frame = options_.drop_when_busy && KeptFrameWaitsLocked();
    slots_[frame_index] = Slot{};
    ++stats_.submitted;
  }
  Job job{frame_index, timestamp, bgr.clone()};
  if (options_.sequential) {
    Run(job);
    return;
  }
  // A kept frame the worker has taken meanwhile left room: TryPush then queues this one.
  const bool accepted = !options_.drop_when_busy ? queue_.Push(std::move(job))
                        : keep_waiting_frame     ? queue_.TryPush(std::move(job))
                                                 : queue_.PushDropOldest(std::move(job));
  if (!accepted) {
    std::lock_guard<std::mutex> lock(mutex_);
    slots_[frame_index].state = State::kDropped;
    ++stats_.dropped;
    finished_.notify_all();
  }
}

void AsyncSegmenter::WorkerLoop() {
  NameCurrentThread("drv-segment");
  LowerCurrentThreadPriority(BackgroundStage::kSegmentation);
  while (std::optional<Job> job = queue_.Pop()) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      // The queue is first-in first-out, so frames still marked queued that are older than this
      // one were pushed out of a full queue.
      for (auto& [index, slot] : slots_) {
        if (index >= job->frame_index) break;
        if (slot.state == State::kQueued) {
          slot.state = State::kDropped;
          ++stats_.dropped;
        }
      }
      if (stopping_) {
        slots_[job->frame_index].state = State::kDropped;
        ++stats_.dropped;
        finished_.notify_all();
        continue;
      }
      finished_.notify_all();
    }
    Run(*job);
  }
}

void AsyncSegmenter::Run(const Job& job) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    Slot& slot = slots_[job.frame_index];
    slot.state = State::kRunning;
    slot.started = std::chrono::steady_clock::now();
  }
  auto frame = std::make_shared<SegmentedFrame>();
  std::exception_ptr error;
  const auto start = std::chrono::steady_clock::now();
  try {
    frame->segmentation = segmenter_->Segment(job.image, job.timestamp, job.frame_index);
  } catch (...) {
    error = std::current_exception();
  }
  frame->segment_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  frame->image = job.image;

  std::lock_guard<std::mutex> lock(mutex_);
  Slot& slot = slots_[job.frame_index];
  if (error) {
    slot.state = State::kFailed;
    slot.error = error;
    ++stats_.failed;
  } else {
    slot.state = State::kDone;
    slot.result = frame;
    ++stats_.segmented;
    segment_ms_.Add(frame->segment_ms);
    // Weighted towards the last few passes: the pass time follows the machine's load.
    constexpr double kRecentWeight = 0.25;
    typical_segment_ms_ = typical_segment_ms_ ? (1.0 - kRecentWeight) * *typical_segment_ms_ +
                                                    kRecentWeight * frame->segment_ms
                                              : frame->segment_ms;
    if (!latest_ || latest_->segmentation.frame_index < job.frame_index) latest_ = frame;
  }
  TrimLocked();
  finished_.notify_all();
}

void AsyncSegmenter::TrimLocked() {
  // keep_results bounds the results (each holds an image and its masks); a dropped frame holds
  // nothing and is remembered longer (Wait names it dropped), up to kDroppedKept. Only finished
  // slots go: a kept frame waiting behind a long pass stays, however many newer frames were
  // refused meanwhile, and its result then counts like any other.
  std::size_t results = 0;
  std::size_t dropped = 0;
  for (auto it = slots_.rbegin(); it != slots_.rend(); ++it) {
    if (it->second.Unfinished()) continue;
    const bool beyond = it->second.state == State::kDropped ? ++dropped > kDroppedKept
                                                            : ++results > options_.keep_results;
    if (beyond) {
      for (auto old = slots_.begin(); old != it.base();) {
        old = old->second.Unfinished() ? std::next(old) : slots_.erase(old);
      }
      return;
    }
  }
}

std::shared_ptr<const SegmentedFrame> AsyncSegmenter::Wait(std::size_t frame_index) {
  const auto missing = [&] {
    return Error("AsyncSegmenter: frame " + std::to_string(frame_index) +
                 " was never submitted, or its result is no longer kept");
  };
  std::unique_lock<std::mutex> lock(mutex_);
  if (slots_.count(frame_index) == 0) throw missing();
  // Look the slot up afresh on every wake-up: trimming may erase it meanwhile.
  finished_.wait(lock, [&] {
    const auto slot = slots_.find(frame_index);
    return slot == slots_.end() || !slot->second.Unfinished();
  });
  const auto slot = slots_.find(frame_index);
  if (slot == slots_.end()) throw missing();
  switch (slot->second.state) {
    case State::kDone:
      return slot->second.result;
    case State::kFailed:
      std::rethrow_exception(slot->second.error);
    default:
      throw Error("AsyncSegmenter: frame " + std::to_string(frame_index) +
                  " was dropped because segmentation was busy");
  }
}

std::shared_ptr<const SegmentedFrame> AsyncSegmenter::WaitFor(std::size_t frame_index,
                                                              double timeout_ms) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double, std::milli>(std::max(0.0, timeout_ms)));
  std::unique_lock<std::mutex> lock(mutex_);
  // A frame replaced in the slot is marked dropped only when the worker takes the next one:
  // waiting for it just runs into the deadline.
  finished_.wait_until(lock, deadline, [&] {
    const auto slot = slots_.find(frame_index);
    return slot == slots_.end() || !slot->second.Unfinished();
  });
  const auto slot = slots_.find(frame_index);
  if (slot == slots_.end() || slot->second.state != State::kDone) return nullptr;
  return slot->second.result;
}

std::optional<double> AsyncSegmenter::TypicalPassMs() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return typical_segment_ms_;
}

std::optional<double> AsyncSegmenter::ExpectedWaitMs(std::size_t frame_index) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto slot = slots_.find(frame_index);
  if (slot == slots_.end()) return std::nullopt;
  // Before the first pass finishes there is no estimate: assume nothing, promise nothing.
  const double pass_ms = typical_segment_ms_.value_or(0.0);
  switch (slot->second.state) {
    case State::kDone:
      return 0.0;
    case State::kRunning: {
      const double elapsed_ms = std::chrono::duration<double, std::milli>(
                                    std::chrono::steady_clock::now() - slot->second.started)
                                    .count();
      return std::max(0.0, pass_ms - elapsed_ms);
    }
    case State::kQueued:
      for (const auto& [index, other] : slots_) {
        if (index != frame_index && (other.state == State::kRunning ||
                                     (other.state == State::kQueued && index < frame_index))) {
          return std::nullopt;
        }
      }
      return pass_ms;
    case State::kFailed:
    case State::kDropped:
      break;
  }
  return std::nullopt;
}

std::shared_ptr<const SegmentedFrame> AsyncSegmenter::TryGet(std::size_t frame_index) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto slot = slots_.find(frame_index);
  if (slot == slots_.end() || slot->second.state != State::kDone) return nullptr;
  return slot->second.result;
}

void AsyncSegmenter::Keep(std::size_t frame_index) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto slot = slots_.find(frame_index);
  if (slot != slots_.end() && slot->second.state == State::kQueued) slot->second.kept = true;
}

bool AsyncSegmenter::Pending(std::size_t frame_index) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto slot = slots_.find(frame_index);
  return slot != slots_.end() && slot->second.Unfinished();
}

bool AsyncSegmenter::KeptFrameWaitsLocked() const {
  for (const auto& [index, slot] : slots_) {
    if (slot.state == State::kQueued && slot.kept) return true;
  }
  return false;
}

std::shared_ptr<const SegmentedFrame> AsyncSegmenter::Latest() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return latest_;
}

AsyncSegmenterStats AsyncSegmenter::Stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  AsyncSegmenterStats stats = stats_;
  stats.segment_ms = SpreadOf(segment_ms_);
  return stats;
}

}  // namespace drvslam
