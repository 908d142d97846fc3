#include "drvslam/io/realtime_feeder.h"

#include <algorithm>
#include <chrono>

#include "drvslam/core/error.h"

namespace drvslam {

RealtimeFeeder::RealtimeFeeder(const TumDataset& dataset, std::size_t count, double rate)
    : dataset_(dataset) {
  if (!(rate > 0.0)) throw Error("RealtimeFeeder: the playback rate must be positive");
  thread_ = std::thread([this, count, rate] { Play(count, rate); });
}

RealtimeFeeder::~RealtimeFeeder() {
  Stop();
  if (thread_.joinable()) thread_.join();
}

void RealtimeFeeder::Stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  stop_requested_.notify_all();
  slot_.Close();
}

void RealtimeFeeder::Play(std::size_t count, double rate) {
  const auto started = std::chrono::steady_clock::now();
  const double first = count > 0 ? dataset_.Timestamp(0) : 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    std::optional<RgbdFrame> frame;
    try {
      // Loaded before its arrival time, as a sensor has the image ready when it delivers it.
      frame = dataset_.Read(i);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = std::current_exception();
      break;
    }
    const auto due =
        started + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                      std::chrono::duration<double>((frame->timestamp - first) / rate));
    std::unique_lock<std::mutex> lock(mutex_);
    if (stop_requested_.wait_until(lock, due, [&] { return stopping_; })) break;
    const double lag_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - due).count();
    max_lag_ms_ = std::max(max_lag_ms_, lag_ms);
    lock.unlock();
    slot_.Put(std::move(*frame));
  }
  slot_.Close();
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
