// RealtimeFeeder: plays a recorded sequence as a live camera would deliver it. A feeder thread
// loads each frame ahead of time (imread and depth conversion happen there, not on the tracking
// thread) and hands it over at its timestamp, relative to the moment the feeder started, through
// a one-frame slot (LatestFrameSlot): a frame that arrives while the previous one still waits
// replaces it, and is counted as skipped. The consumer (the tracking thread) thus always gets the
// newest frame and never falls behind the sensor by more than the frame it is working on.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

#include "drvslam/core/latest_frame_slot.h"
#include "drvslam/io/tum_dataset.h"

namespace drvslam {

class RealtimeFeeder {
 public:
  // Starts delivering frames [0, count) of `dataset` (which must outlive this object); frame i
  // arrives (timestamp(i) - timestamp(0)) / rate seconds after construction. rate > 0: 2 plays a
  // 30 Hz sequence at 60 Hz.
  RealtimeFeeder(const TumDataset& dataset, std::size_t count, double rate = 1.0);
  // Stops the feeder and joins its thread.
  ~RealtimeFeeder();
  RealtimeFeeder(const RealtimeFeeder&) = delete;
  RealtimeFeeder& operator=(const RealtimeFeeder&) = delete;

  // Blocks until a frame has arrived and returns the newest one not yet taken; std::nullopt
  // once every frame was delivered (or Stop was called). When a frame failed to load, the frames
  // before it are delivered first, then this rethrows its Error.
  std::optional<RgbdFrame> Next();
  // Ends the delivery early (thread-safe); Next then returns what still waits, then nullopt.
  void Stop();

  // Frames that arrived but were replaced by a newer one before the consumer took them.
  std::size_t Skipped() const { return slot_.Skipped(); }
  // Frames that arrived so far (taken, skipped or waiting).
  std::size_t Arrived() const { return slot_.Accepted(); }
  // The most a frame arrived after its timestamp (loading it took longer than the frame period:
  // the feeder, not tracking, fell behind the sensor), in ms.
  double MaxArrivalLagMs() const;

 private:
  void Play(std::size_t count, double rate);

  const TumDataset& dataset_;
  LatestFrameSlot<RgbdFrame> slot_;
  mutable std::mutex mutex_;  // guards stopping_, error_ and max_lag_ms_
  std::condition_variable stop_requested_;
  bool stopping_ = false;
  std::exception_ptr error_;
  double max_lag_ms_ = 0.0;
  std::thread thread_;
};

}  // namespace drvslam
