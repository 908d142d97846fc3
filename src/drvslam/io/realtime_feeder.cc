#include "drvslam/io/realtime_feeder.h"

#include <algorithm>
#include <chrono>

#include "drvslam/core/error.h"

namespace drvslam {

RealtimeFeeder::RealtimeFeeder(const TumDataset& dataset, std::size_t count, double rate,
                               FrameRejections* rejections)
    : dataset_(dataset), rejections_(rejections) {
  if (!(rate > 0.0)) throw Error("RealtimeFeeder: the playback rate must be positive");
  thread_ = std::thread([this, count, rate] { Play(count, rate); });
}

RealtimeFeeder::~RealtimeFeeder() { Stop(); }

void RealtimeFeeder::Stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  stop_requested_.notify_all();
  slot_.Close();
  if (thread_.joinable()) thread_.join();
}

void RealtimeFeeder::Play(std::size_t count, double rate) {
  const auto started = std::chrono::steady_clock::now();
  const double first = count > 0 ? dataset_.Timestamp(0) : 0.0;
  const auto due = [&](std::size_t i) {
    return started + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                         std::chrono::duration<double>((dataset_.Timestamp(i) - first) / rate));
  };
  std::size_t i = 0;
  while (i < count) {
    // Frames whose successor has arrived already would only be replaced: not loaded at all.
    const auto now = std::chrono::steady_clock::now();
    std::size_t newest = i;
    while (newest + 1 < count && due(newest + 1) <= now) ++newest;
    if (newest > i) {
      std::lock_guard<std::mutex> lock(mutex_);
      skipped_loading_ += newest - i;
      i = newest;
    }
    std::optional<RgbdFrame> frame;
    try {
      // Loaded before its arrival time, as a sensor has the image ready when it delivers it.
      frame = dataset_.Read(i);
      if (rejections_) rejections_->Accept();
    } catch (const FrameError& error) {
      if (!rejections_) {
        std::lock_guard<std::mutex> lock(mutex_);
        error_ = std::current_exception();
        break;
      }
      try {
        rejections_->Reject(i, error);
      } catch (...) {
        // Too many bad frames in a row: the delivery ends with that Error.
        std::lock_guard<std::mutex> lock(mutex_);
        error_ = std::current_exception();
        break;
      }
      ++i;
      continue;
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = std::current_exception();
      break;
    }
    std::unique_lock<std::mutex> lock(mutex_);
    if (stop_requested_.wait_until(lock, due(i), [&] { return stopping_; })) break;
    const double lag_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - due(i))
            .count();
    max_lag_ms_ = std::max(max_lag_ms_, lag_ms);
    lock.unlock();
    slot_.Put(std::move(*frame));
    ++i;
  }
  slot_.Close();
}

std::size_t RealtimeFeeder::SkippedWhileLoading() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return skipped_loading_;
}

double RealtimeFeeder::MaxArrivalLagMs() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return max_lag_ms_;
}

std::optional<RgbdFrame> RealtimeFeeder::Next() {
  std::optional<RgbdFrame> frame = slot_.Take();
  if (frame) return frame;
  std::lock_guard<std::mutex> lock(mutex_);
  if (error_) std::rethrow_exception(error_);
  return std::nullopt;
}

}  // namespace drvslam
