// RealtimeFeeder: plays a recorded sequence as a live camera would deliver it. A feeder thread
// loads each frame ahead of time (imread and depth conversion happen there, not on the tracking
// thread) and hands it over at its timestamp, relative to the moment the feeder started, through
// a one-frame slot (LatestFrameSlot): a frame that arrives while the previous one still waits
// replaces it, and is counted as skipped. The consumer (the tracking thread) thus always gets the
// newest frame and never falls behind the sensor by more than the frame it is working on. The
// sensor does not wait for the loader either: when loading falls behind (a loaded machine),
// frames whose successor is already due are not loaded at all and count as skipped too.
//
// A camera hands over decoded images; decoding a recording's PNGs is a cost of playback, not of
// the pipeline (about a third of a core at 30 Hz, 640x480). So when the whole sequence fits in
// `preload_bytes`, the feeder decodes every frame before the clock starts (on all cores, at
// start-up) and then only hands them over; otherwise it loads each frame just before it is due.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "drvslam/core/latest_frame_slot.h"
#include "drvslam/core/thread_usage.h"
#include "drvslam/io/frame_rejections.h"
#include "drvslam/io/tum_dataset.h"

namespace drvslam {

class RealtimeFeeder {
 public:
  // Starts delivering frames [0, count) of `dataset` (which must outlive this object); frame i
  // arrives (timestamp(i) - timestamp(0)) / rate seconds after construction. rate > 0: 2 plays a
  // 30 Hz sequence at 60 Hz. With `rejections` (which must outlive this object), a frame that
  // fails to load with a FrameError is filed there and skipped, as a camera drops a bad frame;
  // without, it ends the delivery like any other error. The frames are decoded ahead when they
  // fit in `preload_bytes`.
  RealtimeFeeder(const TumDataset& dataset, std::size_t count, double rate = 1.0,
                 FrameRejections* rejections = nullptr,
                 std::size_t preload_bytes = kDefaultPreloadBytes);
  static constexpr std::size_t kDefaultPreloadBytes = std::size_t{3} << 30;
  // Stop.
  ~RealtimeFeeder();
  RealtimeFeeder(const RealtimeFeeder&) = delete;
  RealtimeFeeder& operator=(const RealtimeFeeder&) = delete;

  // Blocks until a frame has arrived and returns the newest one not yet taken; std::nullopt
  // once every frame was delivered (or Stop was called). When a frame failed to load, the frames
  // before it are delivered first, then this rethrows its Error.
  std::optional<RgbdFrame> Next();
  // Ends the delivery early and joins the feeder thread (the counts below are final then); Next
  // then returns what still waits, then nullopt. Call from the consumer's thread.
  void Stop();

  // Frames that arrived but were never taken: replaced in the slot by a newer one, or not even
  // loaded because a newer one was already due (SkippedWhileLoading).
  std::size_t Skipped() const { return slot_.Skipped() + SkippedWhileLoading(); }
  std::size_t SkippedWhileLoading() const;
  // Frames that arrived so far (taken, skipped or waiting).
  std::size_t Arrived() const { return slot_.Accepted() + SkippedWhileLoading(); }
  // The most a frame was handed over after its timestamp (the time to load it, when it was
  // started late), in ms.
  double MaxArrivalLagMs() const;
  // Whether the frames were decoded before the clock started, and how long that took (s).
  bool Preloaded() const;
  double PreloadSeconds() const;
  // The CPU the playback thread (drv-camera) and the decoding threads (drv-decode) used, each
  // recorded as it ended (their /proc entries end with them); complete after Stop.
  std::vector<ThreadUsage> EndedThreads() const;

 private:
  void Play(std::size_t count, double rate, std::size_t preload_bytes);
  // Decodes frames [0, count) into preloaded_ when they fit in `budget` bytes; false otherwise.
  bool Preload(std::size_t count, std::size_t budget);
  RgbdFrame Load(std::size_t i);
  // Records the calling thread's usage in ended_threads_; the last thing a thread does.
  void RecordEndedThread();

  const TumDataset& dataset_;
  FrameRejections* const rejections_;
  LatestFrameSlot<RgbdFrame> slot_;
  mutable std::mutex mutex_;  // guards stopping_, error_, max_lag_ms_, skipped_loading_
                              // and ended_threads_
  std::condition_variable stop_requested_;
  bool stopping_ = false;
  std::vector<ThreadUsage> ended_threads_;
  std::exception_ptr error_;
  double max_lag_ms_ = 0.0;
  std::size_t skipped_loading_ = 0;
  std::vector<std::optional<RgbdFrame>> preloaded_;  // written before the clock starts
  std::vector<std::exception_ptr> preload_errors_;   // per frame, written with preloaded_
  std::atomic<bool> preloaded_flag_{false};
  std::atomic<double> preload_seconds_{0.0};
  std::thread thread_;
};

}  // namespace drvslam
